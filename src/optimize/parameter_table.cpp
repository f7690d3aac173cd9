#include "optimize/parameter_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/format_text.h"
#include "optimize/value_summary.h"

namespace vkdr {
namespace {

// A row of cells, each padded to its column's width, two spaces apart.
std::string alignedRow(const std::vector<std::string>& cells, const std::vector<size_t>& widths) {
    std::string row;
    for (size_t i = 0; i < cells.size(); ++i) {
        row += cells[i];
        if (i + 1 < cells.size()) row += std::string(widths[i] - cells[i].size() + 2, ' ');
    }
    return row + "\n";
}

// Values space-separated, each as `pattern` (printf) formats it.
std::string joinedValues(const std::vector<float>& values, const char* pattern) {
    std::string text;
    for (float value : values) {
        char number[32];
        std::snprintf(number, sizeof(number), pattern, double(value));
        text += (text.empty() ? "" : " ") + std::string(number);
    }
    return text;
}

}  // namespace

std::string fitValues(const std::vector<float>& values, const char* pattern) {
    return isSummarised(values.size()) ? summaryText(values) : joinedValues(values, pattern);
}

std::string fitErrors(const ParameterFit& fit) {
    if (isSummarised(fit.fitted.size())) {
        if (std::optional<double> error = relativeL2Error(fit.fitted, fit.truth)) {
            return formatText("relative L2 error %.2f%%", 100.0 * *error);
        }
        // True values all 0 (or not known): no error is relative to them.
        std::optional<double> error = rmsError(fit.fitted, fit.truth);
        return error ? formatText("RMS error %.3g abs", *error) : "";
    }
    std::string text;
    for (size_t c = 0; c < fit.truth.size() && c < fit.fitted.size(); ++c) {
        double truth = fit.truth[c], error = double(fit.fitted[c]) - truth;
        char number[32];
        if (truth == 0.0) {
            std::snprintf(number, sizeof(number), "%+.3g abs", error);
        } else {
            std::snprintf(number, sizeof(number), "%+.2f%%", 100.0 * error / std::abs(truth));
        }
        text += (text.empty() ? "" : " ") + std::string(number);
    }
    return text;
}

std::string parameterTable(const std::vector<ParameterFit>& fits) {
    const bool truthKnown = std::any_of(fits.begin(), fits.end(), [](const ParameterFit& fit) {
        return !fit.truth.empty();
    });
    std::vector<std::vector<std::string>> rows = {{"parameter", "start", "fitted"}};
    if (truthKnown) rows[0].insert(rows[0].end(), {"true", "error"});
    for (const ParameterFit& fit : fits) {
        rows.push_back({fit.name, fitValues(fit.start, "%.4g"), fitValues(fit.fitted, "%.5g")});
        if (truthKnown) rows.back().insert(rows.back().end(), {fitValues(fit.truth, "%.4g"), fitErrors(fit)});
    }
    std::vector<size_t> widths(rows[0].size(), 0);
    for (const auto& row : rows) {
        for (size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], row[i].size());
    }
    std::string table;
    for (const auto& row : rows) table += alignedRow(row, widths);
    return table;
}

}  // namespace vkdr
