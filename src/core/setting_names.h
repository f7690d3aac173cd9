#pragma once
#include <string>

namespace vkdr {

// The settings that errors from shared code name, and how the front end in use spells
// them: as the command line's options (the default) or as the Python module's keywords,
// so that a message tells its reader what to change in the terms they typed.
enum class Setting { Spp, Width, Height, Camera, Device, PathsPerPass, AllowOutsideFiles };
enum class SettingSpelling { CommandLineOptions, PythonKeywords };

// The spelling for this process; the Python module sets it once, when it is imported.
inline SettingSpelling& settingSpelling() {
    static SettingSpelling spelling = SettingSpelling::CommandLineOptions;
    return spelling;
}

// A setting as a message names it; a flag as the way to turn it on.
inline std::string settingName(Setting setting) {
    const bool python = settingSpelling() == SettingSpelling::PythonKeywords;
    switch (setting) {
    case Setting::Spp: return python ? "spp" : "--spp";
    case Setting::Width: return python ? "width" : "--width";
    case Setting::Height: return python ? "height" : "--height";
    case Setting::Camera: return python ? "camera" : "--camera";
    case Setting::Device: return python ? "device" : "--device";
    case Setting::PathsPerPass: return python ? "paths_per_pass" : "--paths-per-pass";
    case Setting::AllowOutsideFiles: return python ? "allow_outside_files=True" : "--allow-outside-files";
    }
    return "";
}

// "--width/--height" or "width/height".
inline std::string imageSizeSettingNames() {
    return settingName(Setting::Width) + "/" + settingName(Setting::Height);
}

}  // namespace vkdr
