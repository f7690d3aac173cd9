// What `optimize` shows a user: the table of fitted values it prints and report.html,
// checked for structure against the run's other files.
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "report_html_reader.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 16, kHeight = 12;
const char* const kParameters[] = {"media/fog/sigma_a", "media/fog/g"};

class OptimizeReport : public CliScratchTest {
protected:
    void SetUp() override {
        CliScratchTest::SetUp();
        RunResult target = run("render " + fog() + " --width " + std::to_string(kWidth) + " --height " +
                               std::to_string(kHeight) + " --spp 4 --max-depth 2 -o " + (dir_ / "target.exr").string());
        ASSERT_EQ(target.exitCode, 0) << target.err;
    }
    std::string optimizeCommand(const fs::path& out) const {
        return "optimize " + fog() + " --target " + (dir_ / "target.exr").string() +
               " --param media/fog/sigma_a --param media/fog/g --set media/fog/sigma_a=0.2 --iters 3 --spp 1 "
               "--max-depth 2 --adam-epsilon 1e-6 --out " + out.string();
    }
};

// The numbers in a table cell ("0.05 0.06 0.07").
std::vector<double> numbers(const std::string& cell) {
    std::istringstream in(cell);
    std::vector<double> values;
    for (double value; in >> value;) values.push_back(value);
    return values;
}

TEST_F(OptimizeReport, PrintsTheFittedValuesAndWritesASelfContainedReport) {
    fs::path out = dir_ / "out";
    RunResult result = run(optimizeCommand(out));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    nlohmann::json params = nlohmann::json::parse(slurp(out / "params.json"));

    // The printed table: a header, then each parameter's start and fitted values, printed
    // with %.5g: rounded to five significant digits, within 5e-5 of the value relatively.
    EXPECT_NE(result.out.find("parameter"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("start"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("fitted"), std::string::npos) << result.out;
    EXPECT_EQ(result.out.find("true"), std::string::npos) << "no true values outside experiments: " << result.out;
    for (const char* name : kParameters) {
        size_t row = result.out.find(std::string(name) + " ");
        ASSERT_NE(row, std::string::npos) << name << "\n" << result.out;
        std::vector<double> printed = numbers(result.out.substr(row + std::string(name).size(),
                                                                result.out.find('\n', row) - row));
        const nlohmann::json& fitted = params[name];
        ASSERT_EQ(printed.size(), 2 * fitted.size()) << result.out;  // start, then fitted
        for (size_t c = 0; c < fitted.size(); ++c) {
            EXPECT_NEAR(printed[fitted.size() + c], fitted[c].get<double>(), 5e-5 * std::abs(fitted[c].get<double>()))
                << name;
        }
    }
    EXPECT_NE(result.out.find("0.2 0.2 0.2"), std::string::npos) << "the start value set by --set: " << result.out;

    std::string html = slurp(out / "report.html");
    ASSERT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(html.find("</html>"), std::string::npos);
    // Self-contained: nothing fetched, nothing run.
    EXPECT_EQ(html.find("src=\"http"), std::string::npos);
    EXPECT_EQ(html.find("href=\"http"), std::string::npos);
    EXPECT_EQ(html.find("<link"), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos);
    EXPECT_EQ(html.find("url("), std::string::npos);

    // One view, with four images of the view's size that decode as PNG.
    EXPECT_EQ(occurrences(html, "<section class=\"view\""), 1u);
    for (const char* kind : {"target", "start", "current", "difference"}) {
        std::optional<Image> image = embeddedPng(html, kind, dir_);
        ASSERT_TRUE(image) << kind;
        EXPECT_EQ(image->width, kWidth) << kind;
        EXPECT_EQ(image->height, kHeight) << kind;
    }
    ASSERT_TRUE(embeddedPng(html, "colour-bar", dir_));
    EXPECT_EQ(between(html, "<div class=\"colour-bar\">", "</div>").size(), 1u);
    // The tone mapping and the difference's scale are stated.
    EXPECT_NE(html.find("sRGB"), std::string::npos);
    EXPECT_NE(html.find("exposure 0 EV"), std::string::npos);
    EXPECT_NE(html.find("99th percentile"), std::string::npos);
    // The target image shows the target file, as the run's PNGs would.
    Image target = readImage(dir_ / "target.exr");
    writePng(dir_ / "target-preview.png", target);
    Image preview = readImage(dir_ / "target-preview.png");
    EXPECT_EQ(embeddedPng(html, "target", dir_)->rgb, preview.rgb);

    // The loss curve and one trajectory per parameter, each a whole SVG.
    EXPECT_EQ(occurrences(html, "<svg"), 3u);
    EXPECT_EQ(occurrences(html, "</svg>"), 3u);
    EXPECT_EQ(occurrences(html, "<figure class=\"trajectory\">"), 2u);

    // The parameter table holds params.json's values, in the same shortest decimals.
    std::vector<std::string> fittedCells = between(html, "<td class=\"number fitted\">", "</td>");
    ASSERT_EQ(fittedCells.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        std::vector<double> shown = numbers(fittedCells[i]);
        const nlohmann::json& fitted = params[kParameters[i]];
        ASSERT_EQ(shown.size(), fitted.size()) << kParameters[i];
        for (size_t c = 0; c < shown.size(); ++c) {
            EXPECT_EQ(shown[c], fitted[c].get<double>()) << kParameters[i];
        }
    }
    // The command and settings.
    EXPECT_NE(html.find("optimize " + fog()), std::string::npos);
    EXPECT_NE(html.find("<th>iterations</th><td>3</td>"), std::string::npos);
    EXPECT_NE(html.find("<th>Adam epsilon</th><td>1e-06</td>"), std::string::npos);
    EXPECT_NE(html.find("<th>time taken</th>"), std::string::npos);
}

TEST_F(OptimizeReport, IsOneOfTheRunsFiles) {
    fs::path out = dir_ / "out";
    ASSERT_EQ(run(optimizeCommand(out)).exitCode, 0);
    for (const fs::directory_entry& entry : fs::directory_iterator(out)) {
        if (entry.path().filename() != "report.html") fs::remove(entry.path());
    }
    RunResult refused = run(optimizeCommand(out));
    EXPECT_EQ(refused.exitCode, 2);
    EXPECT_NE(refused.err.find("holds another run (report.html)"), std::string::npos) << refused.err;

    std::ofstream(out / "report.html") << "an old report";
    std::ofstream(out / "notes.txt") << "mine";
    RunResult replaced = run(optimizeCommand(out) + " --overwrite");
    ASSERT_EQ(replaced.exitCode, 0) << replaced.err;
    EXPECT_EQ(slurp(out / "report.html").rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_EQ(slurp(out / "notes.txt"), "mine");
}

}  // namespace
}  // namespace vkdr::test
