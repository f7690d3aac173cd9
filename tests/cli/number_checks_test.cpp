// Numbers on the command line: g at the ends of its range renders and differentiates
// without a NaN, the brightest accepted emission gives finite pixels, targets with NaN,
// infinite or unrepresentable pixels are refused naming the pixel, numeric options say
// what they must be, and surprises get one warning line each.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "image/image.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

class NumberChecksTest : public CliScratchTest {
protected:
    // A 16x16 render of the fog box, read back.
    Image render(const std::string& options, const std::string& name = "render.exr") {
        fs::path out = dir_ / name;
        RunResult r = run("render " + fog() + " --width 16 --height 16 " + options + " -o " + out.string());
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return r.exitCode == 0 ? readImage(out) : Image{};
    }

    // An 8x8 grey target with one pixel's channel set to `value`.
    fs::path targetWith(float value, int x, int y, int channel) {
        Image image{8, 8, std::vector<float>(8 * 8 * 3, 0.2f)};
        image.pixel(x, y)[channel] = value;
        fs::path file = dir_ / "target.exr";
        writeExr(file, image);
        return file;
    }

    // One error line naming every part, exit code 2.
    void expectError(const RunResult& r, const std::vector<std::string>& parts) {
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(r.err.find("error: "), r.err.rfind("error: ")) << r.err;
        EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
        for (const std::string& part : parts) {
            EXPECT_NE(r.err.find(part), std::string::npos) << "'" << part << "' not in:\n" << r.err;
        }
    }

};

void expectFinite(const Image& image) {
    ASSERT_FALSE(image.rgb.empty());
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        ASSERT_TRUE(std::isfinite(image.rgb[i])) << "pixel " << i / 3 << " channel " << i % 3;
    }
}

size_t count(const std::string& text, const std::string& part) {
    size_t n = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

TEST_F(NumberChecksTest, AnisotropyAtTheEndsOfItsRangeRendersAndDifferentiatesFinitely) {
    for (const char* g : {"0.99", "-0.99"}) {
        std::string set = std::string(" --set media/fog/g=") + g + " --set media/fog/sigma_s=2";
        Image image = render("--spp 16" + set);
        expectFinite(image);
        RunResult r = run("grad " + fog() + " --target " + (dir_ / "render.exr").string() + set +
                          " --set media/fog/sigma_a=0.05 --param media/fog/g --param media/fog/sigma_s --spp 4 --json");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        nlohmann::json out = nlohmann::json::parse(r.out);
        ASSERT_TRUE(out["loss"].is_number()) << r.out;
        EXPECT_TRUE(std::isfinite(out["loss"].get<double>()));
        for (const char* name : {"media/fog/g", "media/fog/sigma_s"}) {
            for (const nlohmann::json& value : out["gradients"][name]) {
                ASSERT_TRUE(value.is_number()) << name << ": " << r.out;
                EXPECT_TRUE(std::isfinite(value.get<double>())) << name;
            }
        }
    }
}

TEST_F(NumberChecksTest, TheBrightestAcceptedEmissionGivesFinitePixels) {
    expectFinite(render("--spp 16 --max-depth 20 --set lights/light/emission=1e12 --set media/fog/sigma_s=0"));
    // Its loss and gradients are finite too: the squared differences of a small image
    // (few pixels to average over) are far beyond 2^64 and within the fixed-point sums.
    fs::path dark = targetWith(0.0f, 0, 0, 0);
    RunResult bright = run("grad " + fog() + " --target " + dark.string() +
                           " --param lights/light/emission --param media/fog/sigma_a --set lights/light/emission=1e12"
                           " --spp 4 --json");
    ASSERT_EQ(bright.exitCode, 0) << bright.err;
    nlohmann::json result = nlohmann::json::parse(bright.out);
    EXPECT_TRUE(result["loss"].is_number() && result["loss"].get<double>() > 1e19) << bright.out;
    for (const auto& [name, gradient] : result["gradients"].items()) {
        for (const nlohmann::json& value : gradient) EXPECT_TRUE(value.is_number()) << name << ": " << bright.out;
    }
    RunResult r = run("render " + fog() + " --set lights/light/emission=1e38 -o " + (dir_ / "bright.exr").string());
    expectError(r, {"lights/light/emission", "must be in [0, 1e+12], got 1e+38"});
    EXPECT_FALSE(fs::exists(dir_ / "bright.exr"));
}

TEST_F(NumberChecksTest, ValuesInRangeWhoseProductOverflowsAreBlamedOnTheScene) {
    // An emission grid's voxels at 1e30 times the medium's emission at 1e12, each in its range.
    const std::string fire = std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fire.gltf" +
                             " --set media/fire/emission_grid=1e30 --set media/fire/emission=1e12";
    const std::string blame = "make more light than a float holds";
    fs::path target = targetWith(0.2f, 0, 0, 0);
    expectError(run("grad " + fire + " --target " + target.string() + " --param media/fire/g --spp 2"),
                {"grad: the render of view 0: pixel (", "is +infinity: the scene's values " + blame});
    fs::path out = dir_ / "fit";
    expectError(run("optimize " + fire + " --target camera=" + target.string() +
                    " --param media/fire/g --spp 2 --iters 1 --out " + out.string()),
                {"iteration 0: the loss is inf", "the render of view 0: pixel (", blame});
    EXPECT_FALSE(fs::exists(out / "params.json"));
}

TEST_F(NumberChecksTest, TargetsWithUnrepresentablePixelsAreRefusedNamingThePixel) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    struct Case {
        float value;
        int x, y, channel;
        std::string says;
    };
    for (const Case& c : {Case{nan, 7, 3, 1, "pixel (7, 3) channel G is NaN"},
                          Case{inf, 0, 5, 0, "pixel (0, 5) channel R is +infinity"},
                          Case{-inf, 2, 0, 2, "pixel (2, 0) channel B is -infinity"},
                          Case{1e30f, 1, 1, 0, "pixel (1, 1) channel R is 1e+30, beyond"}}) {
        fs::path target = targetWith(c.value, c.x, c.y, c.channel);
        expectError(run("grad " + fog() + " --target " + target.string() + " --param media/fog/g --spp 1"),
                    {"--target " + target.string() + ": " + c.says});
        fs::path out = dir_ / "fit";
        expectError(run("optimize " + fog() + " --target camera=" + target.string() +
                        " --param media/fog/g --spp 1 --iters 1 --out " + out.string()),
                    {"--target camera=" + target.string() + ": " + c.says});
        EXPECT_FALSE(fs::exists(out / "params.json"));
    }
}

TEST_F(NumberChecksTest, TwoTargetsOfOneCameraWarnOnce) {
    render("--spp 1", "target.exr");
    const std::string target = (dir_ / "target.exr").string();
    RunResult r = run("grad " + fog() + " --target " + target + " --target camera=" + target +
                      " --param media/fog/g --spp 1");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(count(r.err, "warning: "), 1u) << r.err;
    EXPECT_NE(r.err.find("both view camera 'camera'"), std::string::npos) << r.err;
}

TEST_F(NumberChecksTest, ATargetWithNegativePixelsIsWarnedOf) {
    const fs::path target = targetWith(-0.31f, 3, 4, 2);
    RunResult r = run("grad " + fog() + " --target " + target.string() + " --param media/fog/g --spp 1");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(count(r.err, "warning: "), 1u) << r.err;
    EXPECT_NE(r.err.find("--target " + target.string() + ": 1 channel value is below 0 (the least -0.31)"),
              std::string::npos)
        << r.err;
}

// A PNG render is clipped at 1: where the scene is brighter (the lamp), the target's 1
// is not what the render gives, and a fit would be biased there.
TEST_F(NumberChecksTest, AnEightBitTargetWithValuesAtItsMaximumIsWarnedOf) {
    render("--spp 4", "target.png");
    const std::string png = (dir_ / "target.png").string();
    RunResult r = run("grad " + fog() + " --target " + png + " --param media/fog/g --spp 1");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(count(r.err, "warning: "), 1u) << r.err;
    EXPECT_NE(r.err.find("channel values are 1, the most its format holds"), std::string::npos) << r.err;
    render("--spp 4", "target.exr");
    RunResult exr = run("grad " + fog() + " --target " + (dir_ / "target.exr").string() +
                        " --param media/fog/g --spp 1");
    EXPECT_EQ(exr.err.find("warning: "), std::string::npos) << exr.err;
}

TEST_F(NumberChecksTest, ATargetOfAnotherAspectThanItsCameraIsWarnedOf) {
    const fs::path wide = dir_ / "wide.exr";  // the fog box's camera is square
    writeExr(wide, Image{8, 4, std::vector<float>(8 * 4 * 3, 0.2f)});
    RunResult r = run("grad " + fog() + " --target " + wide.string() + " --param media/fog/g --spp 1");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(count(r.err, "warning: "), 1u) << r.err;
    EXPECT_NE(r.err.find("is 8x4 (aspect 2), but camera 'camera' has aspectRatio 1"), std::string::npos) << r.err;
}

TEST_F(NumberChecksTest, ASceneWithoutLightWarnsAfterTheOverrides) {
    RunResult dark = run("render " + fog() + " --width 8 --height 8 --spp 1 --set lights/light/emission=0 -o " +
                         (dir_ / "dark.exr").string());
    EXPECT_EQ(dark.exitCode, 0) << dark.err;
    EXPECT_EQ(count(dark.err, "warning: "), 1u) << dark.err;
    EXPECT_NE(dark.err.find("warning: " + fog() + ": the scene has no light"), std::string::npos) << dark.err;
    RunResult lit = run("render " + fog() + " --width 8 --height 8 --spp 1 -o " + (dir_ / "lit.exr").string());
    EXPECT_EQ(lit.err.find("warning: "), std::string::npos) << lit.err;
}

TEST_F(NumberChecksTest, NumericOptionsSayWhatTheyMustBe) {
    const std::string render = "render " + fog() + " -o " + (dir_ / "out.exr").string();
    const std::string seed = "must be a 32-bit unsigned integer (0..4294967295)";
    expectError(run(render + " --seed 4294967296"), {"--seed", seed, "got 4294967296"});
    expectError(run(render + " --seed -1"), {"--seed", seed, "got -1"});
    expectError(run(render + " --spp 1.5"), {"--spp", "must be an integer from 1 to 1048576, got 1.5"});
    expectError(run(render + " --max-depth 1e3"), {"--max-depth", "must be an integer from 0 to 100000, got 1e3"});
    expectError(run(render + " --width abc"), {"--width", "must be an integer from 1 to 16384, got abc"});
    expectError(run(render + " --height 0"), {"--height", "must be an integer from 1 to 16384, got 0"});
    const std::string optimize = "optimize " + fog() + " --target t.exr --param media/fog/g --out " +
                                 (dir_ / "run").string();
    expectError(run(optimize + " --iters 1e3"), {"--iters", "must be an integer from 1 to 1000000, got 1e3"});
    expectError(run(optimize + " --checkpoint-every -1"),
                {"--checkpoint-every", "must be an integer from 0 to 1000000, got -1"});
    expectError(run("bench cornell_fog --iters 0"), {"--iters", "must be an integer from 1 to 1000, got 0"});
    expectError(run(optimize + " --optimizer sgd --adam-epsilon 1e-6"),
                {"--adam-epsilon: only Adam has an epsilon; the optimizer is sgd"});
    for (const char* value : {"1e-50", "1e50"}) {
        RunResult r = run(render + " --set media/fog/sigma_a=" + value);
        expectError(r, {std::string("'") + value + "' is out of float range"});
        EXPECT_EQ(r.err.find("not a number"), std::string::npos) << r.err;
    }
    // Set twice, a parameter would take the last value without a word.
    expectError(run(render + " --set media/fog/sigma_a=0.1 --set media/fog/sigma_a=0.2"),
                {"--set media/fog/sigma_a: given twice; set each parameter once"});
    EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
    EXPECT_FALSE(fs::exists(dir_ / "run"));
}

// Two materials that share a texture give two names of its texels: setting both would
// let the second silently win, as setting one name twice would.
TEST_F(NumberChecksTest, SettingTwoNamesOfOneTextureIsRefused) {
    writePng(dir_ / "checker.png", Image{2, 1, {0.2f, 0.4f, 0.6f, 0.8f, 0.6f, 0.4f}});
    const fs::path quad = fs::path(VKDR_TEST_DATA_DIR) / "malformed" / "valid_quad.gltf";
    nlohmann::json scene = nlohmann::json::parse(std::ifstream(quad));
    nlohmann::json textured = {{"baseColorTexture", {{"index", 0}}}};
    scene["materials"] = {{{"name", "lamp"}, {"emissiveFactor", {1, 1, 1}}, {"pbrMetallicRoughness", textured}},
                          {{"name", "poster"}, {"pbrMetallicRoughness", textured}}};
    scene["meshes"].push_back(scene["meshes"][0]);
    scene["meshes"][1]["primitives"][0]["material"] = 1;
    scene["nodes"].push_back({{"mesh", 1}, {"translation", {0, 0, -1}}});
    scene["scenes"][0]["nodes"].push_back(2);
    scene["textures"] = {{{"source", 0}}};
    scene["images"] = {{{"uri", "checker.png"}}};
    std::ofstream(dir_ / "shared.gltf") << scene.dump();
    const std::string render = "render " + (dir_ / "shared.gltf").string() + " --width 8 --height 8 --spp 1 -o " +
                               (dir_ / "out.exr").string();
    const std::string both =
        " --set materials/lamp/base_color_texture=0.1 --set materials/poster/base_color_texture=0.9";
    expectError(run(render + both),
                {"--set materials/poster/base_color_texture: names the same values as --set "
                 "materials/lamp/base_color_texture"});
    EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
    RunResult one = run(render + " --set materials/poster/base_color_texture=0.9");
    EXPECT_EQ(one.exitCode, 0) << one.err;
}

TEST_F(NumberChecksTest, IntegersAreDecimal) {
    // CLI11 alone reads a leading 0 as octal: --seed 010 would be seed 8.
    Image leadingZero = render("--spp 1 --seed 010", "a.exr");
    Image ten = render("--spp 1 --seed 10", "b.exr");
    Image eight = render("--spp 1 --seed 8", "c.exr");
    EXPECT_EQ(leadingZero.rgb, ten.rgb);
    EXPECT_NE(leadingZero.rgb, eight.rgb);
}

}  // namespace
}  // namespace vkdr::test
