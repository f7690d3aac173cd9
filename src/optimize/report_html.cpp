#include "optimize/report_html.h"

#include <charconv>

#include "core/format_text.h"
#include "image/png_encode.h"
#include "optimize/base64.h"
#include "optimize/difference_colour_map.h"
#include "optimize/loss_chart.h"
#include "optimize/metric_chart.h"
#include "optimize/trajectory_chart.h"
#include "optimize/value_summary.h"

namespace vkdr {
namespace {

constexpr const char* kStyle = R"(body { font-family: sans-serif; margin: 1.5em; max-width: 75em; color: #222; }
table { border-collapse: collapse; }
td, th { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
td.number { font-family: monospace; }
code { white-space: pre-wrap; word-break: break-all; }
.images { display: grid; grid-template-columns: repeat(4, 1fr); gap: 0.8em; }
figure { margin: 0; }
figure img { width: 100%; height: auto; image-rendering: pixelated; border: 1px solid #ccc; }
figcaption { font-size: 0.9em; }
.colour-bar { position: relative; height: 2.4em; font-size: 0.8em; }
.colour-bar img { width: 100%; height: 0.9em; border: none; display: block; }
.colour-bar span { position: absolute; top: 1.1em; transform: translateX(-50%); white-space: nowrap; }
.colour-bar span.first { transform: none; }
.colour-bar span.last { transform: translateX(-100%); }
.charts { display: flex; flex-wrap: wrap; gap: 1em; }
)";

std::string escaped(const std::string& text) {
    std::string html;
    for (char c : text) {
        switch (c) {
            case '&': html += "&amp;"; break;
            case '<': html += "&lt;"; break;
            case '>': html += "&gt;"; break;
            case '"': html += "&quot;"; break;
            default: html += c;
        }
    }
    return html;
}

// Each value as the shortest decimal that reads back as the same float: what params.json holds.
// Every digit a float needs, or the summary of a parameter of many values.
std::string exactValues(const std::vector<float>& values) {
    if (isSummarised(values.size())) return escaped(summaryText(values));
    std::string text;
    for (float value : values) {
        char number[32];
        auto [end, error] = std::to_chars(number, number + sizeof(number), value);
        text += (text.empty() ? "" : " ") + std::string(number, end);
    }
    return text;
}

std::string pngImage(const std::vector<unsigned char>& png, int width, int height, const std::string& kind) {
    return "<img class=\"" + kind + "\" width=\"" + std::to_string(width) + "\" height=\"" + std::to_string(height) +
           "\" alt=\"" + kind + "\" src=\"data:image/png;base64," + base64(png) + "\">";
}

std::string figure(const std::string& image, const std::string& caption) {
    return "<figure>" + image + "<figcaption>" + caption + "</figcaption></figure>\n";
}

std::string colourBarHtml(float scale) {
    ColourBar bar = colourBar(scale);
    std::string html = "<div class=\"colour-bar\">" + pngImage(encodePngRgb8(bar.width, bar.height, bar.rgb),
                                                              bar.width, bar.height, "colour-bar");
    for (size_t i = 0; i < bar.ticks.size(); ++i) {
        const ColourBarTick& tick = bar.ticks[i];
        const char* end = i == 0 ? " class=\"first\"" : i + 1 == bar.ticks.size() ? " class=\"last\"" : "";
        html += "<span" + std::string(end) + " style=\"left: " + formatText("%g", 100.0 * tick.position) + "%\">" +
                (i + 1 == bar.ticks.size() ? "&ge; " : "") + formatText("%.3g", tick.value) + "</span>";
    }
    return html + "</div>\n";
}

std::string viewSection(const ReportView& view) {
    ColourMappedDifference difference = colourMappedDifference(view.current, view.target, kDifferencePercentile);
    std::string name = view.camera.empty() ? "the scene's first camera" : "camera " + view.camera;
    std::string html = "<section class=\"view\" data-camera=\"" + escaped(view.camera) + "\">\n<h2>View: " +
                       escaped(name) + "</h2>\n<div class=\"images\">\n";
    auto image = [&](const Image& picture, const std::string& kind) {
        return pngImage(encodePng(picture), picture.width, picture.height, kind);
    };
    html += figure(image(view.target, "target"), "target");
    html += figure(image(view.start, "start"), "start (iteration 0's render)");
    html += figure(image(view.current, "current"), "current (the last iteration's render)");
    html += figure(pngImage(encodePngRgb8(difference.width, difference.height, difference.rgb), difference.width,
                            difference.height, "difference") +
                       colourBarHtml(difference.scale),
                   "|current &minus; target|, the largest of each pixel's channels");
    return html + "</div>\n</section>\n";
}

std::string settingsSection(const ReportPage& page) {
    std::string html = "<section id=\"run\">\n<h2>Run</h2>\n<table class=\"settings\">\n";
    html += "<tr><th>command</th><td><code>" + escaped(page.commandLine) + "</code></td></tr>\n";
    html += "<tr><th>scene</th><td><code>" + escaped(page.scene) + "</code></td></tr>\n";
    for (const auto& [name, value] : page.settings) {
        html += "<tr><th>" + escaped(name) + "</th><td>" + escaped(value) + "</td></tr>\n";
    }
    return html + "</table>\n</section>\n";
}

std::string parameterSection(const ReportPage& page) {
    bool truthKnown = false;
    for (const ParameterFit& fit : page.fits) truthKnown = truthKnown || !fit.truth.empty();
    std::string html = "<section id=\"parameters\">\n<h2>Parameters</h2>\n<table class=\"parameters\">\n"
                       "<tr><th>parameter</th><th>start</th><th>fitted</th>";
    html += truthKnown ? "<th>true</th><th>error</th></tr>\n" : "</tr>\n";
    for (const ParameterFit& fit : page.fits) {
        html += "<tr><td>" + escaped(fit.name) + "</td><td class=\"number start\">" + exactValues(fit.start) +
                "</td><td class=\"number fitted\">" + exactValues(fit.fitted) + "</td>";
        if (truthKnown) {
            html += "<td class=\"number truth\">" + exactValues(fit.truth) + "</td><td class=\"number\">" +
                    escaped(fitErrors(fit)) + "</td>";
        }
        html += "</tr>\n";
    }
    return html + "</table>\n</section>\n";
}

std::string chartSection(const ReportPage& page) {
    std::string html = "<section id=\"charts\">\n<h2>Loss and parameters per iteration</h2>\n<div class=\"charts\">\n";
    html += "<figure class=\"loss\">" + lossChartSvg(page.losses, page.lossName) + "<figcaption>" +
            escaped(page.lossName) + " loss per iteration (the mean over views)</figcaption></figure>\n";
    for (size_t i = 0; i < page.trajectories.size() && i < page.fits.size(); ++i) {
        html += "<figure class=\"trajectory\">" + trajectoryChartSvg(page.trajectories[i], page.fits[i]) +
                "<figcaption>" + escaped(page.fits[i].name) + "</figcaption></figure>\n";
    }
    for (const MetricSeries& metric : page.metrics) {
        html += "<figure class=\"metric\">" + metricChartSvg(metric) + "<figcaption>" + escaped(metric.name) +
                " per iteration</figcaption></figure>\n";
    }
    return html + "</div>\n</section>\n";
}

}  // namespace

std::string reportHtml(const ReportPage& page) {
    std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                       "<title>vkdiffrender optimisation: " + escaped(page.scene) + "</title>\n<style>\n" + kStyle +
                       "</style>\n</head>\n<body>\n<h1>vkdiffrender optimisation</h1>\n";
    html += settingsSection(page) + parameterSection(page) + chartSection(page);
    html += "<section id=\"views\">\n<h2>Views</h2>\n<p class=\"tone-mapping\">Target, start and current images are "
            "linear RGB shown with the sRGB transfer function at exposure 0 EV (values as rendered, not scaled), "
            "clipped to [0, 1], 8 bits per channel, as the run's PNG files. The difference image shows each "
            "pixel's largest channel difference in false colour; the top of its colour bar is the " +
            formatText("%g", 100.0 * kDifferencePercentile) +
            "th percentile of those differences over the view's pixels, and larger ones show in the top colour."
            "</p>\n";
    for (const ReportView& view : page.views) html += viewSection(view);
    return html + "</section>\n</body>\n</html>\n";
}

}  // namespace vkdr
