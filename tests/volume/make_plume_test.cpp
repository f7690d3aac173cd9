// vkdr-make-plume writes the plume makeSmokePlume makes, refuses bad arguments with
// one error line and exit code 2, and replaces an existing file only with --overwrite.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include <gtest/gtest.h>

#include "../image/scratch_directory.h"
#include "volume/read_density_grid.h"
#include "volume/smoke_plume.h"

namespace vkdr::test {
namespace {

struct PlumeRun {
    int exitCode;  // -1 when the process did not exit normally
    std::string out;
    std::string err;
};

PlumeRun makePlume(const ScratchDirectory& directory, const std::string& arguments) {
    const std::string command = std::string(VKDR_MAKE_PLUME_PATH) + " " + arguments + " > " +
                                (directory / "stdout").string() + " 2> " + (directory / "stderr").string();
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readBytes(directory / "stdout"),
            readBytes(directory / "stderr")};
}

// The plume in the file, voxel for voxel (the file holds the active box; the plume's
// zero border lies outside it), with its transform.
void expectPlume(const DensityGrid& read, const DensityGrid& expected) {
    for (int k = 0; k < expected.size.z; ++k) {
        for (int j = 0; j < expected.size.y; ++j) {
            for (int i = 0; i < expected.size.x; ++i) ASSERT_EQ(read.at({i, j, k}), expected.at({i, j, k}));
        }
    }
    EXPECT_EQ(read.indexToLocal, expected.indexToLocal);
}

void expectRefused(const PlumeRun& run, const std::string& mentioning) {
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_EQ(run.err.rfind("error: ", 0), 0u) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << "one line: " << run.err;
    EXPECT_NE(run.err.find(mentioning), std::string::npos) << run.err;
    EXPECT_TRUE(run.out.empty()) << run.out;
}

TEST(MakePlume, WritesTheGeneratedPlume) {
    ScratchDirectory directory;
    const DensityGrid expected = makeSmokePlume(24, 5);
    for (const char* name : {"plume.vdb", "plume.nvdb"}) {
        const PlumeRun run = makePlume(directory, "--resolution 24 --seed 5 --grid smoke " + (directory / name).string());
        ASSERT_EQ(run.exitCode, 0) << run.err;
        EXPECT_NE(run.out.find(name), std::string::npos) << run.out;
        EXPECT_NE(run.out.find("grid 'smoke', 24 x 24 x 24 voxels"), std::string::npos) << run.out;
        const size_t aboveZero = size_t(std::count_if(expected.values.begin(), expected.values.end(),
                                                       [](float v) { return v > 0.0f; }));
        EXPECT_NE(run.out.find(", " + std::to_string(aboveZero) + " above 0 ("), std::string::npos) << run.out;
        SCOPED_TRACE(name);
        expectPlume(readDensityGrid(directory / name, "smoke"), expected);
    }
}

TEST(MakePlume, FlameWritesTheFlameGrid) {
    ScratchDirectory directory;
    const PlumeRun run = makePlume(directory, "--resolution 24 --seed 5 --flame " + (directory / "fire.vdb").string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("grid 'flame'"), std::string::npos) << run.out;
    expectPlume(readDensityGrid(directory / "fire.vdb", "flame"), flameOfPlume(makeSmokePlume(24, 5)));
}

TEST(MakePlume, RefusesBadArguments) {
    ScratchDirectory directory;
    const std::string output = (directory / "plume.vdb").string();
    expectRefused(makePlume(directory, "--resolution 1 --seed 1 " + output), "--resolution");
    expectRefused(makePlume(directory, "--resolution many --seed 1 " + output), "--resolution");
    expectRefused(makePlume(directory, "--resolution 8.5 --seed 1 " + output),
                  "--resolution: expected an integer from 2 to 1290, got 8.5");
    expectRefused(makePlume(directory, "--resolution 8 --seed -1 " + output), "--seed");
    expectRefused(makePlume(directory, "--resolution 8 " + output), "--seed");
    expectRefused(makePlume(directory, "--resolution 8 --seed 1"), "OUTPUT");
    expectRefused(makePlume(directory, "--resolution 8 --seed 1 --grid '' " + output), "--grid: give a name");
    expectRefused(makePlume(directory, "--resolution 8 --seed 1 " + (directory / "plume.exr").string()),
                  ".vdb or .nvdb");
    expectRefused(makePlume(directory, "--resolution 8 --seed 1 " + (directory / "no/such/plume.vdb").string()),
                  "no/such");
    EXPECT_EQ(directory.fileCount(), 2u);  // stdout and stderr only
}

TEST(MakePlume, ReplacesAnExistingFileOnlyWithForce) {
    ScratchDirectory directory;
    const std::string output = (directory / "plume.nvdb").string();
    writeBytes(directory / "plume.nvdb", "keep me");
    expectRefused(makePlume(directory, "--resolution 8 --seed 1 " + output), "--overwrite");
    EXPECT_EQ(readBytes(directory / "plume.nvdb"), "keep me");
    ASSERT_EQ(makePlume(directory, "--resolution 8 --seed 1 --overwrite " + output).exitCode, 0);
    expectPlume(readDensityGrid(output, "density"), makeSmokePlume(8, 1));
}

TEST(MakePlume, HelpDescribesEveryOption) {
    ScratchDirectory directory;
    const PlumeRun run = makePlume(directory, "--help");
    EXPECT_EQ(run.exitCode, 0);
    for (const char* option : {"--resolution", "--seed", "--grid", "--overwrite", "OUTPUT", ".nvdb"}) {
        EXPECT_NE(run.out.find(option), std::string::npos) << option << " in\n" << run.out;
    }
}

}  // namespace
}  // namespace vkdr::test
