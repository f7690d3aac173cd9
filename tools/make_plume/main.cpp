// vkdr-make-plume: writes a procedural smoke plume density grid as .vdb or .nvdb.
//   vkdr-make-plume --resolution N --seed S [--flame] [--grid NAME] [--overwrite] OUTPUT.vdb|OUTPUT.nvdb
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <new>
#include <string>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "image/output_paths.h"
#include "volume/grid_file_type.h"
#include "volume/smoke_plume.h"
#include "volume/write_density_grid.h"

namespace {

struct PlumeOptions {
    int resolution = 0;
    uint32_t seed = 0;
    std::string grid;  // default: "density", or "flame" with --flame
    bool flame = false;  // write the plume's flame instead of its density
    std::filesystem::path output;
    bool overwrite = false;  // replace an existing OUTPUT
};

void checkOutput(const PlumeOptions& options) {
    if (!vkdr::gridFileTypeOf(options.output)) {
        throw vkdr::Error("OUTPUT '" + options.output.string() + "': expected a .vdb or .nvdb file name");
    }
    std::error_code error;
    if (std::filesystem::exists(std::filesystem::symlink_status(options.output, error)) && !options.overwrite) {
        throw vkdr::Error("OUTPUT '" + options.output.string() + "' exists; give --overwrite to replace it");
    }
    vkdr::requireOutputFile("OUTPUT", options.output);
}

int makePlume(const PlumeOptions& options) {
    checkOutput(options);
    vkdr::DensityGrid plume = vkdr::makeSmokePlume(options.resolution, options.seed);
    if (options.flame) plume = vkdr::flameOfPlume(plume);
    if (!options.grid.empty()) plume.name = options.grid;
    vkdr::writeDensityGrid(options.output, plume);
    const size_t aboveZero =
        size_t(std::count_if(plume.values.begin(), plume.values.end(), [](float v) { return v > 0.0f; }));
    std::printf("%s: grid '%s', %d x %d x %d voxels, %zu above 0 (%.1f %%)\n", options.output.string().c_str(),
                plume.name.c_str(), plume.size.x, plume.size.y, plume.size.z, aboveZero,
                100.0 * double(aboveZero) / double(plume.voxelCount()));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app(
        "vkdr-make-plume: writes a procedural smoke plume, a density grid rising along +y through the cube\n"
        "[-0.5, 0.5]^3, as OpenVDB (.vdb) or NanoVDB (.nvdb). Densities lie in [0, 1] and are 0 near the\n"
        "cube's faces; the same resolution and seed give the same grid. See docs/density-grids.md.",
        "vkdr-make-plume");
    PlumeOptions options;
    app.add_option("--resolution", options.resolution, "voxels along each axis, 2 to 1290")
        ->required()
        ->check(CLI::Validator(
            [](std::string& text) {
                int value = 0;
                const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
                const bool whole = error == std::errc() && end == text.data() + text.size();
                return whole && value >= 2 && value <= 1290 ? std::string()
                                                            : "expected an integer from 2 to 1290, got " + text;
            },
            ""));
    app.add_option("--seed", options.seed, "seed of the plume's noise, 0 to 4294967295")->required();
    app.add_option("--grid", options.grid, "name of the grid in the file (default: density, or flame with --flame)")
        ->check(CLI::Validator([](std::string& name) { return name.empty() ? std::string("give a name") : ""; }, ""));
    app.add_flag("--flame", options.flame,
                 "write the plume's flame instead: its density where it is hot, near the column's source, as the "
                 "emission strength of a fire (an emission grid)");
    app.add_flag("--overwrite", options.overwrite, "replace OUTPUT if it exists (refused otherwise)");
    app.add_option("OUTPUT", options.output, "the file to write: .vdb or .nvdb")->required();
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::fprintf(stderr, "error: %s (see vkdr-make-plume --help)\n", e.what());
        return 2;
    }
    try {
        return makePlume(options);
    } catch (const vkdr::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "error: out of host memory: the plume is too large for this machine\n");
        return 2;
    }
}
