#include "optimize/svg_chart.h"

#include <algorithm>
#include <cmath>

namespace vkdr {

double iterationTickStep(size_t count) {
    double raw = std::max(1.0, double(count) / 5.0);
    double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (double multiple : {1.0, 2.0, 5.0}) {
        if (multiple * power >= raw) return multiple * power;
    }
    return 10.0 * power;
}

std::string svgHeader(double width, double height) {
    return svgFormat("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" viewBox=\"0 0 %g %g\" "
                     "font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%%\" height=\"100%%\" "
                     "fill=\"white\"/>\n",
                     width, height, width, height);
}

}  // namespace vkdr
