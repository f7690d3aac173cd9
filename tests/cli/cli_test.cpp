// The command line as a user meets it: help, bad input (one clear message, exit code 2,
// nothing written over a previous result), and a real render.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "image/image.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

class CliTest : public CliScratchTest {
protected:
    // A failed command must say "error:" once, name `what`, exit with 2, and leave
    // the previous output file as it was.
    void expectCleanFailure(const std::string& args, const std::string& what) {
        fs::path out = dir_ / "out.exr";
        std::ofstream(out) << "previous result";
        RunResult r = run(args + " -o " + out.string());
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("error: "), r.err.rfind("error: ")) << "more than one error message:\n" << r.err;
        EXPECT_NE(r.err.find(what), std::string::npos) << "message does not name " << what << ":\n" << r.err;
        EXPECT_EQ(slurp(out), "previous result");
    }

    std::string scene(const char* name) const { return std::string(VKDR_TEST_SCENES_DIR) + "/" + name; }

    // An 8x8 render of the fog Cornell box to differentiate against.
    fs::path fogTarget(int spp) {
        fs::path target = dir_ / "target.exr";
        EXPECT_EQ(run("render " + scene("cornell_fog.gltf") + " --width 8 --height 8 --spp " + std::to_string(spp) +
                      " -o " + target.string()).exitCode, 0);
        return target;
    }

};

TEST_F(CliTest, HelpDescribesEverySubcommand) {
    RunResult r = run("render --help");
    EXPECT_EQ(r.exitCode, 0);
    for (const char* option : {"--spp", "--max-depth", "--seed", "--width", "--height", "--set", "--png", "--camera"}) {
        EXPECT_NE(r.out.find(option), std::string::npos) << option;
    }
    EXPECT_EQ(run("info --help").exitCode, 0);
    RunResult bench = run("bench --help");
    EXPECT_EQ(bench.exitCode, 0);
    for (const char* option :
         {"--spp", "--max-depth", "--width", "--height", "--iters", "--gradient-seeds", "--json", "--device"}) {
        EXPECT_NE(bench.out.find(option), std::string::npos) << option;
    }
    EXPECT_EQ(bench.out.find("--seed"), std::string::npos);
    EXPECT_EQ(run("--help").exitCode, 0);
}

TEST_F(CliTest, HelpIsInWordsAndReachableByHelpCommand) {
    for (const char* command : {"render", "grad", "optimize", "bench", "info"}) {
        RunResult help = run(std::string(command) + " --help");
        EXPECT_EQ(help.exitCode, 0) << command;
        // CLI11's type and validator names ("UINT:UINT in [1 - 1048576]=16") never show.
        for (const char* internal : {"UINT", "INT:", "FLOAT", "TEXT:", "REQUIRED", "]="}) {
            EXPECT_EQ(help.out.find(internal), std::string::npos) << command << " shows " << internal;
        }
        RunResult viaHelp = run(std::string("help ") + command);
        EXPECT_EQ(viaHelp.exitCode, 0) << command;
        EXPECT_EQ(viaHelp.out, help.out) << command;
    }
    EXPECT_NE(run("render --help").out.find("--spp N"), std::string::npos);
    EXPECT_NE(run("render --help").out.find("an integer from 1 to 1048576; default 16"), std::string::npos);
    EXPECT_EQ(run("help").out, run("--help").out);
    RunResult unknown = run("help nope");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("error: help: no command 'nope'; the commands are render, grad"), std::string::npos)
        << unknown.err;
}

TEST_F(CliTest, VersionIsPrinted) {
    RunResult version = run("--version");
    EXPECT_EQ(version.exitCode, 0);
    EXPECT_EQ(version.out.rfind("vkdiffrender ", 0), 0u) << version.out;
}

// A command line CLI11 refuses is one line: the reason and where to read more.
TEST_F(CliTest, UsageErrorsAreOneLineNamingTheHelpToRead) {
    auto expectOneLine = [&](const std::string& args, const std::string& message) {
        RunResult r = run(args);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(r.err, "error: " + message + "\n");
    };
    expectOneLine("frob", "unknown command 'frob'; the commands are render, grad, optimize, bench, info, help "
                          "(see 'vkdiffrender --help')");
    expectOneLine("", "A subcommand is required: one of render, grad, optimize, bench, info, help "
                      "(see 'vkdiffrender --help')");
    expectOneLine("render", "scene is required; see 'vkdiffrender render --help'");
    expectOneLine("info --frob", "unexpected argument --frob; see 'vkdiffrender info --help'");
    expectOneLine("help grad bench", "unexpected argument bench; see 'vkdiffrender help --help'");
    expectOneLine("render scene.gltf --spp 2 --spp 3", "--spp: given 2 times; give it once; see 'vkdiffrender render "
                                                       "--help'");
    expectOneLine("bench --spp", "--spp: no value given (expected an integer from 1 to 1048576); see 'vkdiffrender "
                                 "bench --help'");
    expectOneLine("render scene.gltf -o", "--output: no value given; see 'vkdiffrender render --help'");
}

// CLI11 would let a repeatable option take every word up to the next option: the scene
// after a --target would be a second target, and --set a=1 b=2 set both.
TEST_F(CliTest, ARepeatableOptionTakesOneValueEachTimeItIsGiven) {
    const fs::path target = dir_ / "target.exr";
    ASSERT_EQ(run("render " + scene("cornell_fog.gltf") + " --width 8 --height 8 --spp 1 -o " + target.string())
                  .exitCode,
              0);
    RunResult grad = run("grad --target " + target.string() + " " + scene("cornell_fog.gltf") +
                         " --param media/fog/g --spp 1");
    EXPECT_EQ(grad.exitCode, 0) << grad.err;
    EXPECT_NE(grad.out.find("d loss / d media/fog/g"), std::string::npos) << grad.out;
    RunResult set = run("render " + scene("cornell_fog.gltf") + " -o " + (dir_ / "x.exr").string() +
                        " --set media/fog/g=0.1 media/fog/sigma_a=0.2");
    EXPECT_EQ(set.exitCode, 2);
    EXPECT_EQ(set.err, "error: unexpected argument media/fog/sigma_a=0.2; an option takes one value each time it "
                       "is given (give it again for another); see 'vkdiffrender render --help'\n");
    EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
}

TEST_F(CliTest, MissingSceneFile) {
    expectCleanFailure("render " + (dir_ / "nowhere.gltf").string(), "nowhere.gltf");
}

TEST_F(CliTest, MalformedJson) {
    fs::path bad = dir_ / "broken.gltf";
    std::ofstream(bad) << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ ";
    expectCleanFailure("render " + bad.string(), "broken.gltf");
}

// A scene exported from Blender without its camera is the usual case: the message says
// how to export one.
TEST_F(CliTest, ASceneWithoutACameraSaysHowToGetOne) {
    nlohmann::json gltf = nlohmann::json::parse(slurp(scene("cornell_box.gltf")));
    gltf.erase("cameras");
    for (nlohmann::json& node : gltf["nodes"]) node.erase("camera");
    fs::path noCamera = dir_ / "no_camera.gltf";
    std::ofstream(noCamera) << gltf.dump();
    expectCleanFailure("render " + noCamera.string(), noCamera.string() + ": the scene has no camera");
    expectCleanFailure("render " + noCamera.string(), "tick Include > Cameras in the glTF exporter");
    expectCleanFailure("render " + noCamera.string(), "vkdiffrender Blender add-on");
}

// An experiment's cameras are added to its scene, which then needs none of its own.
TEST_F(CliTest, AnExperimentMayBringTheOnlyCamera) {
    nlohmann::json gltf = nlohmann::json::parse(slurp(scene("cornell_fog.gltf")));
    gltf.erase("cameras");
    for (nlohmann::json& node : gltf["nodes"]) node.erase("camera");
    std::ofstream(dir_ / "no_camera.gltf") << gltf.dump();
    nlohmann::json experiment = {
        {"scene", "no_camera.gltf"}, {"width", 8}, {"height", 8}, {"spp", 1}, {"target_spp", 1}, {"max_depth", 2},
        {"iterations", 1}, {"parameters", {"media/fog/sigma_a"}}, {"true", {{"media/fog/sigma_a", 0.05}}},
        {"start", {{"media/fog/sigma_a", 0.2}}},
        {"cameras", {{{"name", "front"}, {"position", {0, 1, 4}}, {"look_at", {0, 1, 0}}, {"yfov_degrees", 40}}}},
        {"views", {"front"}}};
    std::ofstream(dir_ / "experiment.json") << experiment.dump();
    RunResult r = run("optimize --experiment " + (dir_ / "experiment.json").string() + " --out " +
                      (dir_ / "run").string());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    experiment.erase("cameras");
    std::ofstream(dir_ / "experiment.json") << experiment.dump();
    RunResult none = run("optimize --experiment " + (dir_ / "experiment.json").string() + " --out " +
                         (dir_ / "other").string());
    EXPECT_EQ(none.exitCode, 2);
    EXPECT_NE(none.err.find("the scene has no camera; add one under \"cameras\""), std::string::npos) << none.err;
}

TEST_F(CliTest, UnknownParameterListsTheValidNames) {
    expectCleanFailure("render " + scene("cornell_fog.gltf") + " --set media/smog/sigma_a=1", "media/fog/sigma_a");
}

TEST_F(CliTest, OutOfRangeAndNaNParameters) {
    expectCleanFailure("render " + scene("cornell_fog.gltf") + " --set media/fog/g=1.5", "media/fog/g");
    expectCleanFailure("render " + scene("cornell_fog.gltf") + " --set media/fog/sigma_s=-1", "media/fog/sigma_s");
    expectCleanFailure("render " + scene("cornell_fog.gltf") + " --set media/fog/sigma_a=nan", "media/fog/sigma_a");
}

TEST_F(CliTest, BadOptionValues) {
    expectCleanFailure("render " + scene("cornell_fog.gltf") + " --spp 0", "--spp");
    expectCleanFailure("render " + scene("cornell_fog.gltf") + " --camera nobody", "nobody");
}

TEST_F(CliTest, MissingOutputDirectory) {
    RunResult r = run("render " + scene("cornell_fog.gltf") + " -o " + (dir_ / "no/such/dir/out.exr").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("no/such/dir"), std::string::npos) << r.err;
}

// A test that sets VKDR_SIMULATE_DEVICE_LOST to something unreadable must not pass by
// never losing the device.
TEST_F(CliTest, AnUnreadableSimulatedDeviceLossIsRefused) {
    for (const char* value : {"abc", "-5", "0", "12x"}) {
        RunResult r = runCli("render " + scene("cornell_fog.gltf") + " --width 8 --spp 1 -o " +
                                 (dir_ / "out.exr").string(),
                             dir_, std::string("VKDR_SIMULATE_DEVICE_LOST=") + value);
        EXPECT_EQ(r.exitCode, 2) << value << ": " << r.err;
        EXPECT_NE(r.err.find("VKDR_SIMULATE_DEVICE_LOST=" + std::string(value) + ": expected a positive integer"),
                  std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
    }
}

TEST_F(CliTest, RendersExrAndPngDeterministically) {
    fs::path exr = dir_ / "fog.exr", png = dir_ / "fog.png";
    std::string args = "render " + scene("cornell_fog.gltf") + " --width 24 --height 24 --spp 2 --max-depth 3 -o ";
    RunResult r = run(args + exr.string() + " --png " + png.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("paths/s"), std::string::npos) << r.out;
    Image image = readImage(exr);
    EXPECT_EQ(image.width, 24);
    EXPECT_EQ(image.height, 24);
    EXPECT_EQ(readImage(png).width, 24);
    std::string first = slurp(exr);
    ASSERT_EQ(run(args + exr.string()).exitCode, 0);
    EXPECT_EQ(slurp(exr), first) << "the same seed must give the same file";
}

TEST_F(CliTest, GradPrintsOneJsonObject) {
    fs::path target = fogTarget(2);
    RunResult r = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                      " --param media/fog/sigma_a --param media/fog/g --set media/fog/sigma_a=0.05 --spp 2 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    nlohmann::json out = nlohmann::json::parse(r.out);
    EXPECT_TRUE(out["loss"].is_number());
    EXPECT_EQ(out["gradients"]["media/fog/sigma_a"].size(), 3u);
    EXPECT_EQ(out["gradients"]["media/fog/g"].size(), 1u);
    EXPECT_EQ(out.size(), 2u);
}

// --check-seeds says how many seeds --check averages over: alone it would do nothing.
TEST_F(CliTest, GradCheckSeedsWithoutCheckIsRefused) {
    fs::path target = fogTarget(2);
    RunResult r = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                      " --param media/fog/g --spp 2 --check-seeds 5");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("error: --check-seeds requires --check"), std::string::npos) << r.err;
}

// --check adds, per component, the adjoint and the finite difference with their
// standard errors and the step: relative for sigma, so a thin fog gets a thin step. Its
// seeds start at --seed.
TEST_F(CliTest, GradCheckPrintsAdjointAgainstFiniteDifferences) {
    fs::path target = fogTarget(2);
    RunResult r = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                      " --param media/fog/sigma_a --set media/fog/sigma_a=0.002 --spp 2 --check --check-seeds 2 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    nlohmann::json out = nlohmann::json::parse(r.out);
    ASSERT_EQ(out["check"].size(), 3u);
    for (const nlohmann::json& row : out["check"]) {
        EXPECT_EQ(row["parameter"], "media/fog/sigma_a");
        for (const char* key : {"adjoint", "adjoint_error", "finite_difference", "finite_difference_error"}) {
            EXPECT_TRUE(row[key].is_number()) << key;
        }
        EXPECT_EQ(row["finite_difference_resolved"], true);
        EXPECT_NEAR(row["step"].get<double>(), 0.15 * 0.002, 1e-9);
    }
    // A sigma_s so small that its steps change no pixel's float: the finite difference
    // is 0 whatever the gradient, and says it cannot see it.
    RunResult tiny = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                         " --param media/fog/sigma_s --set media/fog/sigma_s=1e-12 --spp 2 --check --check-seeds 2");
    ASSERT_EQ(tiny.exitCode, 0) << tiny.err;
    EXPECT_NE(tiny.out.find("unresolved (*)"), std::string::npos) << tiny.out;
    EXPECT_NE(tiny.out.find("the gradient is zero, or too small for a finite difference to see"), std::string::npos)
        << tiny.out;
    // The check's seeds start at --seed: another seed is another check, the same one the same.
    const std::string seeded = "grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                               " --param media/fog/g --spp 2 --check --check-seeds 2 --json --seed ";
    RunResult seed5 = run(seeded + "5");
    RunResult seed5Again = run(seeded + "5");
    RunResult seed6 = run(seeded + "6");
    ASSERT_EQ(seed5.exitCode, 0) << seed5.err;
    ASSERT_EQ(seed6.exitCode, 0) << seed6.err;
    const nlohmann::json row5 = nlohmann::json::parse(seed5.out)["check"][0];
    const nlohmann::json row6 = nlohmann::json::parse(seed6.out)["check"][0];
    EXPECT_EQ(nlohmann::json::parse(seed5Again.out)["check"][0], row5);
    EXPECT_NE(row5["adjoint"], row6["adjoint"]);
    EXPECT_NE(row5["finite_difference"], row6["finite_difference"]);
    // The seeds wrap past 2^32 - 1 (the largest --seed).
    RunResult wrapped = run(seeded + "4294967295");
    ASSERT_EQ(wrapped.exitCode, 0) << wrapped.err;
    EXPECT_EQ(nlohmann::json::parse(wrapped.out)["check"].size(), 1u);
    // Near the largest float the difference steps down only, not past float's range.
    RunResult huge = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                         " --param media/fog/sigma_s --set media/fog/sigma_s=3e38 --spp 1 --check --check-seeds 2");
    EXPECT_EQ(huge.exitCode, 0) << huge.err;
    // Within a step of the least sigma_a that keeps a scene-wide medium's emission
    // bounded (emission / 1e12), the difference steps up only, not past that bound.
    RunResult coupled = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                            " --param media/fog/sigma_a --set media/fog/sigma_s=0 --set media/fog/sigma_a=1.1e-12 "
                            "--set media/fog/emission=1 --spp 1 --check --check-seeds 2");
    EXPECT_EQ(coupled.exitCode, 0) << coupled.err;
    // An emission of 0.001 whose attenuation allows 0.0015 has room for neither its step
    // of 0.001 to each side nor 0.002 to one: the step shrinks to fit.
    RunResult narrow = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                           " --param media/fog/emission --set media/fog/sigma_s=0 --set media/fog/sigma_a=1.5e-15 "
                           "--set media/fog/emission=0.001 --spp 1 --check --check-seeds 2 --json");
    ASSERT_EQ(narrow.exitCode, 0) << narrow.err;
    const nlohmann::json narrowRows = nlohmann::json::parse(narrow.out)["check"];
    ASSERT_EQ(narrowRows.size(), 3u);
    for (const nlohmann::json& row : narrowRows) {
        EXPECT_NEAR(row["step"].get<double>(), 0.0005, 1e-9);  // half the 0.001 of room below
    }
}

TEST_F(CliTest, GradRejectsBadParametersAndTargets) {
    fs::path target = fogTarget(1);
    RunResult unknown = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() + " --param media/smog/g");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("media/fog/g"), std::string::npos) << unknown.err;
    RunResult wrongSize = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                              " --param media/fog/g --width 16 --height 16");
    EXPECT_EQ(wrongSize.exitCode, 2);
    EXPECT_NE(wrongSize.err.find("target.exr"), std::string::npos) << wrongSize.err;
    RunResult missing = run("grad " + scene("cornell_fog.gltf") + " --target " + (dir_ / "none.exr").string() +
                            " --param media/fog/g");
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_NE(missing.err.find("none.exr"), std::string::npos) << missing.err;
    // A scene-wide medium that neither absorbs nor scatters may not emit: its emission's
    // range is 0 to 0, which leaves a finite difference no room; refused before rendering.
    RunResult pinned = run("grad " + scene("cornell_fog.gltf") + " --target " + target.string() +
                           " --param media/fog/emission --set media/fog/sigma_a=0 --set media/fog/sigma_s=0 "
                           "--set media/fog/emission=0 --check");
    EXPECT_EQ(pinned.exitCode, 2);
    EXPECT_NE(pinned.err.find("error: --check: media/fog/emission[0] = 0 has no room for a finite difference"),
              std::string::npos)
        << pinned.err;
    EXPECT_EQ(pinned.out, "");
}

// --set may make the scene-wide fog emit where it does not attenuate (every ray leaving
// the scene infinitely bright) or too little: refused before rendering, naming it.
TEST_F(CliTest, SetRefusesASceneWideMediumThatEmitsWithoutBound) {
    const std::string render = "render " + scene("cornell_fog.gltf") + " --width 8 --height 8 --spp 1 -o " +
                               (dir_ / "never.exr").string() + " --set media/fog/emission=1e6 ";
    RunResult none = run(render + "--set media/fog/sigma_a=0 --set media/fog/sigma_s=0");
    EXPECT_EQ(none.exitCode, 2);
    EXPECT_NE(none.err.find("error: --set: the scene-wide medium emits media/fog/emission[0]"), std::string::npos)
        << none.err;
    RunResult little = run(render + "--set media/fog/sigma_a=1e-7 --set media/fog/sigma_s=0");
    EXPECT_EQ(little.exitCode, 2);
    EXPECT_NE(little.err.find("media/fog/emission / (sigma_a + sigma_s) = 1000000 / 1.00000001e-07"),
              std::string::npos)
        << little.err;
    EXPECT_FALSE(fs::exists(dir_ / "never.exr"));
}

// "CAMERA=FILE" names a camera only where CAMERA is one of the scene's: a file whose path
// holds '=' is a plain FILE, and with a camera's name before it the camera's FILE.
TEST_F(CliTest, TargetPathsMayHoldEquals) {
    const fs::path dir = dir_ / "run=1";
    fs::create_directories(dir);
    const fs::path target = dir / "target.exr";
    fs::copy_file(fogTarget(1), target);
    const std::string grad = "grad " + scene("cornell_fog.gltf") + " --param media/fog/g --spp 1 --target ";
    for (const std::string& argument : {target.string(), "camera=" + target.string()}) {
        RunResult r = run(grad + argument);
        EXPECT_EQ(r.exitCode, 0) << argument << ": " << r.err;
    }
    RunResult unknown = run(grad + "side=" + target.string());
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("no camera 'side' and no file"), std::string::npos) << unknown.err;
    EXPECT_NE(unknown.err.find("cameras: camera"), std::string::npos) << unknown.err;
    RunResult noFile = run(grad + "camera=");
    EXPECT_EQ(noFile.exitCode, 2);
    EXPECT_NE(noFile.err.find("--target camera=: no file after 'camera='; give CAMERA=FILE"), std::string::npos)
        << noFile.err;
    RunResult empty = run(grad + "''");
    EXPECT_EQ(empty.exitCode, 2);
    EXPECT_NE(empty.err.find("--target: give an image file"), std::string::npos) << empty.err;

    // A file whose whole name starts with a camera's name and '=' is that file, unless
    // the part after '=' is a file too: then the argument is refused as ambiguous.
    fs::copy_file(target, dir_ / "camera=t.exr");
    const std::string inScratch = "cd '" + dir_.string() + "' &&";
    RunResult whole = runCli(grad + "camera=t.exr", dir_, inScratch);
    EXPECT_EQ(whole.exitCode, 0) << whole.err;
    fs::copy_file(target, dir_ / "t.exr");
    RunResult ambiguous = runCli(grad + "camera=t.exr", dir_, inScratch);
    EXPECT_EQ(ambiguous.exitCode, 2);
    EXPECT_NE(ambiguous.err.find("both the file 'camera=t.exr' and camera 'camera' with file 't.exr'"),
              std::string::npos)
        << ambiguous.err;
    for (const char* unambiguous : {"./camera=t.exr", "camera=./t.exr"}) {
        RunResult r = runCli(grad + unambiguous, dir_, inScratch);
        EXPECT_EQ(r.exitCode, 0) << unambiguous << ": " << r.err;
    }
}

// A density grid's gradient has a value per voxel: the text output summarises it, --json
// has them all, and --check (two renders per value and seed) is refused.
TEST_F(CliTest, GradOfADensityGridSummarisesItsVoxels) {
    fs::path target = dir_ / "plume.exr";
    ASSERT_EQ(run("render " + scene("cornell_plume.gltf") + " --width 8 --height 8 --spp 1 -o " + target.string())
                  .exitCode,
              0);
    const std::string grad = "grad " + scene("cornell_plume.gltf") + " --target " + target.string() +
                             " --param media/plume/density --spp 1";
    RunResult text = run(grad);
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_NE(text.out.find("d loss / d media/plume/density = 262144 values, L2 norm"), std::string::npos) << text.out;
    RunResult json = run(grad + " --json");
    ASSERT_EQ(json.exitCode, 0) << json.err;
    EXPECT_EQ(nlohmann::json::parse(json.out)["gradients"]["media/plume/density"].size(), 262144u);
    RunResult check = run(grad + " --check");
    EXPECT_EQ(check.exitCode, 2);
    EXPECT_NE(check.err.find("error: --check: media/plume/density has 262144 values"), std::string::npos) << check.err;
}

// optimize fits a grid with smoothness and total variation terms, summarises its voxels
// in what it prints and writes the fitted grid as a .vdb that the written scene loads; a
// smoothness or total variation weight or grid levels without a grid are refused before
// anything renders or is removed.
TEST_F(CliTest, OptimizeFitsADensityGridAndWritesItBesideTheScene) {
    fs::path target = dir_ / "plume.exr";
    ASSERT_EQ(run("render " + scene("cornell_plume.gltf") + " --width 8 --height 8 --spp 1 -o " + target.string())
                  .exitCode,
              0);
    const fs::path out = dir_ / "fit";
    const std::string optimize = "optimize " + scene("cornell_plume.gltf") + " --target " + target.string() +
                                 " --iters 2 --spp 2 --lr 0.001 --smoothness 0.5 --out " + out.string();
    RunResult fit = run(optimize + " --total-variation 0.25 --param media/plume/density");
    ASSERT_EQ(fit.exitCode, 0) << fit.err;
    EXPECT_NE(fit.out.find("over 262144 values"), std::string::npos) << fit.out;
    EXPECT_EQ(nlohmann::json::parse(slurp(out / "params.json"))["media/plume/density"]["count"], 262144);
    ASSERT_TRUE(fs::is_regular_file(out / "scene.materials4.density.vdb"));
    RunResult rendered = run("render " + (out / "scene.gltf").string() + " --width 8 --height 8 --spp 1 -o " +
                             (dir_ / "fitted.exr").string());
    EXPECT_EQ(rendered.exitCode, 0) << rendered.err;
    // A step to a grid too dense to track, the last one, is refused, not written as the fit.
    const fs::path diverged = dir_ / "diverged";
    RunResult tooDense = run("optimize " + scene("cornell_plume.gltf") + " --target " + target.string() +
                             " --iters 1 --spp 2 --lr 1e6 --param media/plume/density --out " + diverged.string());
    EXPECT_EQ(tooDense.exitCode, 2);
    EXPECT_NE(tooDense.err.find("error: the values of the last step (iteration 0) do not render: "), std::string::npos)
        << tooDense.err;
    EXPECT_FALSE(fs::exists(diverged / "scene.gltf"));

    // The fit's options with its smoothness replaced by `option`, on a parameter that is no grid.
    auto expectRefused = [&](const std::string& option, const std::string& message) {
        std::string command = optimize;
        command.replace(command.find(" --smoothness 0.5"), 17, option);
        RunResult refused = run(command + " --param media/plume/sigma_s --overwrite");
        EXPECT_EQ(refused.exitCode, 2) << option;
        EXPECT_NE(refused.err.find("error: " + message + " given, but no grid (media/<medium>/density or"),
                  std::string::npos)
            << refused.err;
    };
    expectRefused(" --smoothness 0.5", "a smoothness weight is");
    expectRefused(" --total-variation 0.5", "a total_variation weight is");
    expectRefused(" --grid-levels 2", "coarse-to-fine grid levels are");
    EXPECT_TRUE(fs::is_regular_file(out / "params.json")) << "the refused run left the earlier one as it was";
    // In an experiment that fits no grid, such an option given on the command line is
    // named as the option, not as a key of the file, which has none.
    const std::string experiment = std::string(VKDR_TEST_SCENES_DIR) + "/experiments/cornell_absorption.json";
    for (const std::string option : {"--smoothness 0.5", "--grid-levels 2"}) {
        RunResult refused = run("optimize --experiment " + experiment + " " + option + " --out " +
                                (dir_ / "experiment").string());
        EXPECT_EQ(refused.exitCode, 2) << refused.err;
        EXPECT_EQ(refused.err.rfind("error: " + option.substr(0, option.find(' ')) + ": ", 0), 0u) << refused.err;
    }
}

TEST_F(CliTest, BenchWritesATableAndJsonWithEveryField) {
    fs::path json = dir_ / "bench.json";
    RunResult r = run("bench cornell_fog room_2k --width 16 --height 16 --spp 1 --max-depth 3 --iters 1 "
                      "--gradient-seeds 2 --json " + json.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("| cornell_fog |"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("| room_2k |"), std::string::npos) << r.out;
    nlohmann::json out = nlohmann::json::parse(slurp(json));
    EXPECT_FALSE(out["device"].get<std::string>().empty());
    EXPECT_FALSE(out["driver"].get<std::string>().empty());
    ASSERT_EQ(out["scenes"].size(), 2u);
    for (const auto& scene : out["scenes"]) {
        for (const char* key : {"name", "triangles", "width", "height", "spp", "max_depth", "bvh_build_ms",
                                "stages_ms", "forward_ms", "gradient_ms", "gradient_to_forward", "paths_per_s",
                                "rays_per_s", "peak_device_bytes", "peak_host_bytes"}) {
            EXPECT_TRUE(scene.contains(key)) << key;
        }
        for (const char* stage : {"generate", "intersect", "medium_sample", "shade", "shadow", "loss", "adjoint"}) {
            EXPECT_TRUE(scene["stages_ms"][stage].is_number()) << stage;
        }
        EXPECT_EQ(scene["width"], 16);
        EXPECT_EQ(scene["spp"], 1);
        EXPECT_EQ(scene["max_depth"], 3);
        // Both scenes have a fog: its gradient over two seeds.
        EXPECT_EQ(scene["gradient_parameter"], "media/fog/sigma_s");
        EXPECT_EQ(scene["gradient_seeds"], 2);
        for (const char* key : {"gradient_mean", "gradient_standard_error", "gradient_relative_noise",
                                "gradient_evaluation_ms", "gradient_efficiency"}) {
            EXPECT_TRUE(scene.contains(key)) << key;
        }
    }
    for (const char* key : {"gradient_mean", "gradient_standard_error", "gradient_relative_noise",
                            "gradient_evaluation_ms", "gradient_efficiency"}) {
        EXPECT_TRUE(out["scenes"][0][key].is_number()) << key;
    }
    EXPECT_NE(r.out.find("| cornell_fog | media/fog/sigma_s | 2 |"), std::string::npos) << r.out;
    EXPECT_EQ(out["scenes"][0]["name"], "cornell_fog");
}

// A scene's memory figures are its own renderers': the same scene measured before and
// after a larger one (whose staging buffers the device context would keep) gives the same.
TEST_F(CliTest, BenchMemoryOfASceneDoesNotDependOnTheScenesBeforeIt) {
    fs::path json = dir_ / "bench.json";
    RunResult r = run("bench room_10 plume_16 room_10 --width 4 --spp 1 --max-depth 2 --iters 1 --gradient-seeds 0 "
                      "--json " + json.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    nlohmann::json out = nlohmann::json::parse(slurp(json));
    ASSERT_EQ(out["scenes"].size(), 3u);
    EXPECT_EQ(out["scenes"][2]["peak_allocated_device_bytes"], out["scenes"][0]["peak_allocated_device_bytes"]);
    EXPECT_EQ(out["scenes"][2]["peak_device_bytes"], out["scenes"][0]["peak_device_bytes"]);
}

// A failure in one of several scenes names it.
TEST_F(CliTest, BenchNamesTheSceneAFailureIsIn) {
    RunResult r = run("bench room_10 --height 12000 --iters 1 --gradient-seeds 0");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err.rfind("error: scene room_10: camera camera: its aspect ratio 1.5", 0), 0u) << r.err;
}

TEST_F(CliTest, BenchRejectsUnknownScenesBeforeRunning) {
    fs::path json = dir_ / "bench.json";
    std::ofstream(json) << "previous result";
    RunResult r = run("bench cornell_fog cornell_fgo --width 16 --iters 1 --json " + json.string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err.find("error: "), r.err.rfind("error: ")) << r.err;
    EXPECT_NE(r.err.find("error: unknown scene 'cornell_fgo'"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(slurp(json), "previous result");
    EXPECT_EQ(run("bench room_ --iters 1").exitCode, 2);
    RunResult plume = run("bench plume_0 --iters 1");
    EXPECT_EQ(plume.exitCode, 2);
    EXPECT_NE(plume.err.find("error: scene plume_0: expected plume_<N>"), std::string::npos) << plume.err;
    EXPECT_EQ(run("bench cornell_fog --iters 0").exitCode, 2);
}

TEST_F(CliTest, InfoNamesTheChosenDevice) {
    RunResult r = run("info");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("Chosen:"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("shaderBufferInt64Atomics"), std::string::npos) << r.out;
}

// Without a driver the loader's "incompatible driver" becomes what to install.
TEST_F(CliTest, InfoWithoutADriverSaysWhatToInstall) {
    RunResult r = runCli("info", dir_, "VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/nonexistent.json");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "error: no Vulkan driver found (install mesa-vulkan-drivers for the CPU device lavapipe)\n");
}

TEST_F(CliTest, DeviceIndexOutOfRangeNamesTheDevices) {
    RunResult r = run("info --device 99");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err.rfind("error: --device 99: no device has that index; the devices are: [0] ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.find(";\n"), std::string::npos) << r.err;  // the list ends with its last device
}

}  // namespace
}  // namespace vkdr::test
