// vkdr-make-scene: writes a procedural room scene of about N triangles as .glb.
//   vkdr-make-scene --triangles N -o scene.glb [--fog SIGMA_A,SIGMA_S] [--scale S]
#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>

#include "core/error.h"
#include "procedural/room_scene.h"

namespace {

constexpr const char* kUsage =
    "usage: vkdr-make-scene --triangles N -o FILE.glb [--fog SIGMA_A,SIGMA_S] [--scale S]\n"
    "  A closed room (10 x 5 x 10 times S, default 1) with an area light and a camera,\n"
    "  filled with a grid of bumpy spheres totalling about N triangles; --fog adds the\n"
    "  scene-wide medium \"fog\".\n";

template <typename Number>
Number parseNumber(std::string_view text, std::string_view option) {
    Number value{};
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
        throw vkdr::Error(std::string(option) + ": '" + std::string(text) + "' is not a number");
    }
    return value;
}

vkdr::RoomSceneOptions parseArguments(int argc, char** argv) {
    vkdr::RoomSceneOptions options;
    bool haveOutput = false;
    for (int i = 1; i < argc; ++i) {
        std::string_view option = argv[i];
        if (i + 1 >= argc) {
            throw vkdr::Error(std::string(option) + ": missing value");
        }
        std::string_view value = argv[++i];
        if (option == "--triangles") {
            options.triangles = parseNumber<uint64_t>(value, option);
        } else if (option == "-o" || option == "--output") {
            options.output = std::string(value);
            haveOutput = true;
        } else if (option == "--fog") {
            size_t comma = value.find(',');
            if (comma == std::string_view::npos) {
                throw vkdr::Error("--fog: expected SIGMA_A,SIGMA_S");
            }
            vkdr::Fog fog{parseNumber<float>(value.substr(0, comma), option),
                          parseNumber<float>(value.substr(comma + 1), option)};
            if (!(fog.sigma_a >= 0.0f && fog.sigma_s >= 0.0f)) {
                throw vkdr::Error("--fog: sigma_a and sigma_s must be >= 0");
            }
            options.fog = fog;
        } else if (option == "--scale") {
            options.scale = parseNumber<float>(value, option);
            if (!(options.scale > 0.0f && options.scale <= 1e6f)) {
                throw vkdr::Error("--scale: expected a number in (0, 1e6]");
            }
        } else {
            throw vkdr::Error(std::string(option) + ": unknown option");
        }
    }
    if (!haveOutput) {
        throw vkdr::Error("-o FILE.glb is required");
    }
    if (options.output.extension() != ".glb") {
        throw vkdr::Error("-o " + options.output.string() + ": the scene is written as binary glTF; give a .glb name");
    }
    return options;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 1 || std::string_view(argv[1]) == "--help" || std::string_view(argv[1]) == "-h") {
        std::fputs(kUsage, argc == 1 ? stderr : stdout);
        return argc == 1 ? 2 : 0;
    }
    try {
        vkdr::RoomSceneOptions options = parseArguments(argc, argv);
        uint64_t triangles = vkdr::writeRoomScene(options);
        std::printf("%s: %llu triangles\n", options.output.string().c_str(),
                    static_cast<unsigned long long>(triangles));
        return 0;
    } catch (const vkdr::Error& error) {
        std::fprintf(stderr, "error: %s (see vkdr-make-scene --help)\n", error.what());
        return 2;
    }
}
