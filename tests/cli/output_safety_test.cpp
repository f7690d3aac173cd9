// Where commands write: every output path is checked before any work, nothing but a
// regular file is replaced, two outputs never share a file, the file type follows the
// extension, an optimisation's directory holds one run, and numeric options are finite.
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"

namespace vkdr::test {
namespace {

namespace fs = std::filesystem;

class OutputSafety : public CliScratchTest {
protected:
    // A scene that does not exist: a command that names its output as the fault, not
    // this, checked the output before any other work.
    std::string noScene() const { return (dir_ / "no_such_scene.gltf").string(); }

    // One error line naming `what`, exit code 2.
    void expectRefused(const std::string& args, const std::string& what) {
        RunResult r = run(args);
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
        EXPECT_EQ(r.err.find("error: "), r.err.rfind("error: ")) << r.err;
        EXPECT_NE(r.err.find(what), std::string::npos) << "does not name " << what << ":\n" << r.err;
        EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    }

    std::string small() const { return " --width 8 --height 8 --spp 1 --max-depth 2"; }

    fs::path fogTarget() {
        fs::path target = dir_ / "target.exr";
        EXPECT_EQ(run("render " + fog() + small() + " -o " + target.string()).exitCode, 0);
        return target;
    }

    std::string optimizeCommand(const fs::path& target, int iterations = 2) const {
        return "optimize " + fog() + " --target " + target.string() + " --param media/fog/sigma_a --iters " +
               std::to_string(iterations) + " --spp 1 --max-depth 2";
    }

};

// A path of each kind that is not a regular file, each made in `directory`.
std::vector<fs::path> specialFiles(const fs::path& directory) {
    fs::path fifo = directory / "fifo.exr", folder = directory / "folder.exr", link = directory / "link.exr",
             socketPath = directory / "socket.exr";
    EXPECT_EQ(mkfifo(fifo.c_str(), 0644), 0);
    fs::create_directory(folder);
    std::ofstream(directory / "real.exr") << "previous result";
    fs::create_symlink(directory / "real.exr", link);
    int socketFd = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::snprintf(address.sun_path, sizeof(address.sun_path), "%s", socketPath.c_str());
    EXPECT_EQ(bind(socketFd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
    close(socketFd);
    return {fifo, folder, link, socketPath, "/dev/null"};
}

TEST_F(OutputSafety, RefusesToReplaceAnythingButARegularFileBeforeAnyWork) {
    for (const fs::path& special : specialFiles(dir_)) {
        fs::file_type before = fs::symlink_status(special).type();
        expectRefused("render " + noScene() + " -o " + special.string(), "-o " + special.string());
        expectRefused("render " + noScene() + " -o " + (dir_ / "new.exr").string() + " --png " + special.string(),
                      "--png " + special.string());
        expectRefused("bench " + noScene() + " --json " + special.string(), "--json " + special.string());
        EXPECT_EQ(fs::symlink_status(special).type(), before) << special;
    }
    EXPECT_EQ(slurp(dir_ / "real.exr"), "previous result");
    fs::path file = dir_ / "file";
    std::ofstream(file) << "not a directory";
    expectRefused(optimizeCommand(file) + " --out " + file.string(), "--out " + file.string());
    expectRefused(optimizeCommand(file) + " --out " + (file / "below").string(), "--out " + (file / "below").string());
    // A link to nothing: making the directory would fail only after the work.
    fs::create_symlink(dir_ / "nowhere", dir_ / "dangling");
    for (const char* below : {"", "/", "/.", "/sub"}) {
        const std::string out = (dir_ / "dangling").string() + below;
        expectRefused(optimizeCommand(file) + " --out " + out,
                      "--out " + out + ": " + (dir_ / "dangling").string() + " is a symbolic link to nothing");
    }
    expectRefused("render " + noScene() + " -o " + (dir_ / "missing" / "x.exr").string(), "-o ");
    expectRefused("render " + noScene() + " -o " + (dir_ / "x.exr").string() + " --png " +
                      (dir_ / "missing" / "x.png").string(),
                  "--png ");
    // A directory that takes no new files whatever its permission bits say (even to root).
    expectRefused("render " + noScene() + " -o /proc/x.exr", "-o /proc/x.exr: cannot");
    expectRefused(optimizeCommand(file) + " --out /proc/run", "--out /proc/run: cannot");
}

// An append-only directory (chattr +a) takes new files but renames and removes none:
// outputs, made under a temporary name and renamed, cannot be written there, and it is
// refused before anything is made in it. A new output directory made inside it works.
TEST_F(OutputSafety, RefusesADirectoryThatKeepsEveryFileButMakesANewOneInIt) {
    const fs::path keeps = dir_ / "keeps";
    fs::create_directory(keeps);
    if (std::system(("chattr +a '" + keeps.string() + "' 2> /dev/null").c_str()) != 0) {
        GTEST_SKIP() << "chattr +a needs root and a file system that has the attribute";
    }
    const fs::path target = fogTarget();
    RunResult refused = run("render " + noScene() + " -o " + (keeps / "x.exr").string());
    const bool leftNothing = fs::is_empty(keeps);
    RunResult made = run(optimizeCommand(target, 1) + " --out " + (keeps / "run" / "one").string());
    EXPECT_EQ(std::system(("chattr -a '" + keeps.string() + "'").c_str()), 0);
    EXPECT_EQ(refused.exitCode, 2) << refused.err;
    EXPECT_NE(refused.err.find("is append-only (chattr +a)"), std::string::npos) << refused.err;
    EXPECT_TRUE(leftNothing);
    EXPECT_EQ(made.exitCode, 0) << made.err;
    EXPECT_TRUE(fs::exists(keeps / "run" / "one" / "log.jsonl"));
    // An immutable directory (chattr +i) takes nothing, and says so.
    const fs::path frozen = dir_ / "frozen";
    fs::create_directory(frozen);
    ASSERT_EQ(std::system(("chattr +i '" + frozen.string() + "'").c_str()), 0);
    RunResult immutable = run("render " + noScene() + " -o " + (frozen / "x.exr").string());
    EXPECT_EQ(std::system(("chattr -i '" + frozen.string() + "'").c_str()), 0);
    EXPECT_EQ(immutable.exitCode, 2) << immutable.err;
    EXPECT_NE(immutable.err.find("is immutable (chattr +i)"), std::string::npos) << immutable.err;
}

TEST_F(OutputSafety, AnEmptyValueIsRefusedNotTakenForNone) {
    const std::string out = " -o " + (dir_ / "a.exr").string();
    expectRefused("render " + fog() + small() + out + " --png ''", "--png: give a file name");
    expectRefused("render " + fog() + small() + out + " --camera ''", "--camera: give a camera's name");
    expectRefused("render " + fog() + small() + out + " --device ''", "--device: give an index or part of a name");
    expectRefused("bench cornell_fog --json ''", "--json: give a file name");
    expectRefused("bench cornell_fog --scenes-dir ''", "--scenes-dir: give a directory");
    expectRefused(optimizeCommand(dir_ / "t.exr") + " --resume ''", "--resume: give a directory");
    expectRefused("optimize --experiment ''", "--experiment: give a file name");
    expectRefused("info --device ''", "--device: give an index or part of a name");
    EXPECT_FALSE(fs::exists(dir_ / "a.exr"));
}

TEST_F(OutputSafety, RefusesTwoOutputsThatAreOneFile) {
    fs::create_directory(dir_ / "sub");
    std::string png = (dir_ / "same.png").string();
    for (const std::string& other : {png, (dir_ / "." / "same.png").string(), (dir_ / "sub" / ".." / "same.png").string()}) {
        expectRefused("render " + noScene() + " -o " + png + " --png " + other, "the same file");
    }
    fs::create_directory_symlink(dir_ / "sub", dir_ / "alias");
    expectRefused("render " + noScene() + " -o " + (dir_ / "sub" / "a.png").string() + " --png " +
                      (dir_ / "alias" / "a.png").string(),
                  "the same file");
    EXPECT_FALSE(fs::exists(dir_ / "same.png"));
}

TEST_F(OutputSafety, TheExtensionOfTheOutputSetsItsType) {
    fs::path png = dir_ / "image.PNG", exr = dir_ / "image.Exr", preview = dir_ / "preview.png";
    RunResult r = run("render " + fog() + small() + " -o " + png.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(slurp(png).substr(0, 4), "\x89PNG");
    r = run("render " + fog() + small() + " -o " + exr.string() + " --png " + preview.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(slurp(exr).substr(0, 4), std::string("\x76\x2f\x31\x01"));
    EXPECT_EQ(slurp(preview).substr(0, 4), "\x89PNG");

    expectRefused("render " + noScene() + " -o " + (dir_ / "image.jpg").string(), ".exr");
    expectRefused("render " + noScene() + " -o " + (dir_ / "image").string(), ".png");
    expectRefused("render " + noScene() + " -o " + exr.string() + " --png " + (dir_ / "preview.exr").string(),
                  "--png " + (dir_ / "preview.exr").string() + ": must end in .png");
}

TEST_F(OutputSafety, AnOptimizeDirectoryHoldsOneRun) {
    fs::path target = fogTarget(), out = dir_ / "out";
    ASSERT_EQ(run(optimizeCommand(target) + " --checkpoint-every 1 --out " + out.string()).exitCode, 0);
    std::string log = slurp(out / "log.jsonl");
    ASSERT_TRUE(fs::exists(out / "checkpoint.json"));
    std::ofstream(out / "notes.txt") << "mine";

    expectRefused(optimizeCommand(target) + " --out " + out.string(), "--overwrite");
    EXPECT_EQ(slurp(out / "log.jsonl"), log);
    // Any one of a run's files marks the directory as a run's, what scene.gltf refers to
    // beside it included.
    for (const char* name : {"log.jsonl", "checkpoint.json", "params.json", "scene.gltf", "final.exr", "final.png",
                             "diff.png", "loss.svg", "report.html", "scene.bin", "scene.image0.png",
                             "scene.buffers2.bin", "scene.density.vdb", "scene.materials3.emission_grid.vdb",
                             "scene.materials0.albedo_grid.vdb"}) {
        fs::path other = dir_ / "other";
        fs::create_directories(other);
        std::ofstream(other / name) << "another run";
        expectRefused(optimizeCommand(target) + " --out " + other.string(), name);
        expectRefused("optimize --experiment " + noScene() + " --out " + other.string(), name);
        fs::remove_all(other);
    }

    RunResult replaced = run(optimizeCommand(target, 3) + " --checkpoint-every 0 --overwrite --out " + out.string());
    ASSERT_EQ(replaced.exitCode, 0) << replaced.err;
    EXPECT_FALSE(fs::exists(out / "checkpoint.json")) << "the old run's checkpoint is left to resume from";
    std::ifstream lines(out / "log.jsonl");
    size_t count = 0;
    for (std::string line; std::getline(lines, line);) ++count;
    EXPECT_EQ(count, 3u);
    EXPECT_EQ(slurp(out / "notes.txt"), "mine");

    // A run that fails before it writes anything leaves the run it was to replace whole.
    // Here its first step overflows: against a black target every path's gradient with
    // respect to sigma_a is <= 0 (absorption only darkens), so the step is +1e300 times
    // a positive number, whatever the samples.
    const std::string replacedLog = slurp(out / "log.jsonl"), replacedParams = slurp(out / "params.json");
    fs::path black = dir_ / "black.exr";
    ASSERT_EQ(run("render " + fog() + small() + " --set lights/light/emission=0 -o " + black.string()).exitCode, 0);
    RunResult failed = run(optimizeCommand(black) + " --optimizer sgd --lr 1e300 --overwrite --out " + out.string());
    EXPECT_EQ(failed.exitCode, 2) << failed.err;
    EXPECT_NE(failed.err.find("iteration 0"), std::string::npos) << failed.err;
    EXPECT_NE(failed.err.find("; the run " + out.string() + " held is left as it was\n"), std::string::npos)
        << failed.err;
    EXPECT_EQ(slurp(out / "log.jsonl"), replacedLog);
    EXPECT_EQ(slurp(out / "params.json"), replacedParams);

    // A run whose first write fails (no room for its log) leaves the run it was to
    // replace whole: the log is complete in its temporary before the old files go.
    // sh's own redirections are outside the limit, so its messages are kept.
    const std::string limited = "(trap '' XFSZ; ulimit -f 0; " + std::string(VKDR_CLI_PATH) + " " +
                                optimizeCommand(target) + " --overwrite --out " + out.string() +
                                " 2>&1; echo \"exit $?\") < /dev/null | cat > " + (dir_ / "limited").string();
    ASSERT_EQ(std::system(limited.c_str()), 0);
    const std::string limitedOutput = slurp(dir_ / "limited");
    EXPECT_NE(limitedOutput.find("error: cannot write"), std::string::npos) << limitedOutput;
    EXPECT_NE(limitedOutput.find("held is left as it was"), std::string::npos) << limitedOutput;
    EXPECT_NE(limitedOutput.find("exit 2"), std::string::npos) << limitedOutput;
    EXPECT_EQ(slurp(out / "log.jsonl"), replacedLog);
    EXPECT_EQ(slurp(out / "params.json"), replacedParams);

    // --overwrite removes only the run's files: a scene.blend or notes are the user's.
    std::ofstream(out / "scene.bin") << "old run";
    std::ofstream(out / "scene.materials1.emission_grid.vdb") << "old run";
    std::ofstream(out / "scene.blend") << "mine";
    ASSERT_EQ(run(optimizeCommand(target, 1) + " --overwrite --out " + out.string()).exitCode, 0);
    EXPECT_FALSE(fs::exists(out / "scene.bin"));
    EXPECT_FALSE(fs::exists(out / "scene.materials1.emission_grid.vdb"));
    EXPECT_EQ(slurp(out / "scene.blend"), "mine");
}

// The files a run writes must not be what it reads, --overwrite or not: the scene, a
// target, the experiment file.
TEST_F(OutputSafety, ARunNeverWritesOverItsOwnInputs) {
    fs::path target = fogTarget();
    fs::copy_file(fog(), dir_ / "scene.gltf");
    const std::string scene = slurp(dir_ / "scene.gltf");
    expectRefused("optimize " + (dir_ / "scene.gltf").string() + " --target " + target.string() +
                      " --param media/fog/sigma_a --iters 1 --spp 1 --overwrite --out " + dir_.string(),
                  "SCENE");
    // Without --overwrite too, and said as such: the scene is no other run to overwrite.
    const std::string plain = "optimize " + (dir_ / "scene.gltf").string() + " --target " + target.string() +
                              " --param media/fog/sigma_a --iters 1 --spp 1 --out " + dir_.string();
    expectRefused(plain, "the run writes scene.gltf there, which is SCENE");
    EXPECT_EQ(run(plain).err.find("--overwrite"), std::string::npos);
    EXPECT_EQ(slurp(dir_ / "scene.gltf"), scene);

    fs::path out = dir_ / "out";
    fs::create_directories(out);
    fs::copy_file(target, out / "final.exr");
    const std::string pixels = slurp(out / "final.exr");
    expectRefused(optimizeCommand(out / "final.exr") + " --overwrite --out " + out.string(), "--target");
    expectRefused(optimizeCommand("camera=" + (out / "final.exr").string()) + " --overwrite --out " + out.string(),
                  "--target");
    EXPECT_EQ(slurp(out / "final.exr"), pixels);

    std::ofstream(out / "params.json") << "{}";
    expectRefused("optimize --experiment " + (out / "params.json").string() + " --overwrite --out " + out.string(),
                  "--experiment");
    EXPECT_EQ(slurp(out / "params.json"), "{}");

    // Named through symbolic links outside the directory: the writes would replace the
    // files the links lead to (--overwrite removed the scene before it was read again).
    fs::copy_file(fog(), out / "scene.gltf");
    const std::string outScene = slurp(out / "scene.gltf");
    fs::create_symlink(out / "scene.gltf", dir_ / "linked.gltf");
    fs::create_symlink(out / "final.exr", dir_ / "linked.exr");
    fs::create_symlink(out / "params.json", dir_ / "linked.json");
    expectRefused("optimize " + (dir_ / "linked.gltf").string() + " --target " + target.string() +
                      " --param media/fog/sigma_a --iters 1 --spp 1 --overwrite --out " + out.string(),
                  "a link to");
    expectRefused(optimizeCommand(dir_ / "linked.exr") + " --overwrite --out " + out.string(), "a link to");
    expectRefused("optimize --experiment " + (dir_ / "linked.json").string() + " --overwrite --out " + out.string(),
                  "a link to");
    EXPECT_EQ(slurp(out / "scene.gltf"), outScene);
    EXPECT_EQ(slurp(out / "final.exr"), pixels);
    EXPECT_EQ(slurp(out / "params.json"), "{}");
}

// The fog box with its buffer in an external file of `bufferName` beside `directory/name`.
fs::path fogWithExternalBuffer(const fs::path& directory, const std::string& name, const std::string& bufferName) {
    nlohmann::json gltf = nlohmann::json::parse(slurp(std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fog.gltf"));
    const std::string uri = gltf["buffers"][0]["uri"];
    const std::string base64 = uri.substr(uri.find(',') + 1);
    std::string bytes;
    int value = 0, bits = -8;
    for (char c : base64) {
        const size_t digit = std::string("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/").find(c);
        if (digit == std::string::npos) break;
        value = (value << 6) | int(digit);
        bits += 6;
        if (bits >= 0) {
            bytes.push_back(char((value >> bits) & 0xff));
            bits -= 8;
        }
    }
    std::ofstream(directory / bufferName, std::ios::binary) << bytes;
    gltf["buffers"][0]["uri"] = bufferName;
    std::ofstream(directory / name) << gltf.dump();
    return directory / name;
}

// Nor over a file the scene reads.
TEST_F(OutputSafety, NoOutputIsAFileTheSceneReads) {
    fs::path target = fogTarget();
    fs::path scene = fogWithExternalBuffer(dir_, "model.gltf", "scene.bin");
    const std::string buffer = slurp(dir_ / "scene.bin");
    expectRefused("optimize " + scene.string() + " --target " + target.string() +
                      " --param media/fog/sigma_a --iters 1 --spp 1 --overwrite --out " + dir_.string(),
                  "a file the scene reads");
    EXPECT_EQ(slurp(dir_ / "scene.bin"), buffer);

    fs::path odd = fogWithExternalBuffer(dir_, "odd.gltf", "data.png");
    expectRefused("render " + odd.string() + small() + " -o " + (dir_ / "data.png").string(), "a file the scene reads");
    expectRefused("render " + odd.string() + small() + " -o " + (dir_ / "x.exr").string() + " --png " +
                      (dir_ / "data.png").string(),
                  "a file the scene reads");
    EXPECT_EQ(slurp(dir_ / "data.png"), buffer);
    EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
}

TEST_F(OutputSafety, BenchNeverWritesItsReportOverAScene) {
    const fs::path scene = dir_ / "scene.gltf";
    fs::copy_file(std::string(VKDR_TEST_SCENES_DIR) + "/cornell_fog.gltf", scene);
    const std::string before = slurp(scene);
    expectRefused("bench " + scene.string() + " --width 8 --spp 1 --iters 1 --gradient-seeds 0 --json " +
                      (dir_ / "." / "scene.gltf").string(),
                  "a scene bench reads");
    EXPECT_EQ(slurp(scene), before);

    // Nor over a file a scene reads: cornell_plume's density grid.
    const fs::path plume = dir_ / "cornell_plume.gltf", grid = dir_ / "cornell_plume.vdb";
    fs::copy_file(std::string(VKDR_TEST_SCENES_DIR) + "/cornell_plume.gltf", plume);
    fs::copy_file(std::string(VKDR_TEST_SCENES_DIR) + "/cornell_plume.vdb", grid);
    const std::string gridBefore = slurp(grid);
    expectRefused("bench " + plume.string() + " --width 8 --spp 1 --iters 1 --gradient-seeds 0 --json " + grid.string(),
                  "is a file that scene " + plume.string() + " reads");
    EXPECT_EQ(slurp(grid), gridBefore);
}

TEST_F(OutputSafety, NumericOptionsMustBeFiniteAndInRange) {
    fs::path out = dir_ / "out";
    const std::string command = "optimize " + noScene() + " --target t.exr --param media/fog/sigma_a --out " + out.string();
    for (const char* option : {"--lr", "--adam-epsilon", "--lr-decay"}) {
        // Hexadecimal and spaced numbers too, which the integer options and --set refuse.
        for (const char* value : {"nan", "inf", "-inf", "0", "-1", "1e999", "0x10", "0x1p-3", "' 0.5'", "'0.5 '"}) {
            expectRefused(command + " " + option + " " + value, option);
        }
    }
    for (const char* value : {"nan", "inf", "-0.5", "1"}) {
        expectRefused(command + " --lr-decay-start " + value, "--lr-decay-start");
    }
    EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace vkdr::test
