// vkdiffrender: a differentiable Monte Carlo path tracer for participating media.
#include <cstdio>
#include <exception>
#include <new>

#include "cli/command_line_text.h"
#include "cli/commands.h"
#include "cli/help_formatter.h"
#include "cli/parse_error_text.h"
#include "core/error.h"
#include "core/interrupt.h"

namespace {

// A repeatable option takes one value each time it is given (CLI11 lets a vector option
// take every word up to the next option): `grad --target t.exr scene.gltf` would take the
// scene for a second target, and `--set a=1 b=2` set both.
void takeOneValuePerOccurrence(CLI::App& app) {
    for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
        for (CLI::Option* option : command->get_options()) {
            if (option->nonpositional()) option->allow_extra_args(false);
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app("vkdiffrender: a differentiable volumetric path tracer on Vulkan", "vkdiffrender");
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("vkdiffrender ") + VKDR_VERSION);
    app.formatter(std::make_shared<vkdr::HelpFormatter>());  // before the subcommands, which inherit it
    std::vector<vkdr::CommandAction> actions = {vkdr::addRenderCommand(app), vkdr::addGradCommand(app),
                                                vkdr::addOptimizeCommand(app, vkdr::commandLineText(argc, argv)), vkdr::addBenchCommand(app),
                                                vkdr::addInfoCommand(app), vkdr::addHelpCommand(app)};
    takeOneValuePerOccurrence(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) {
            return app.exit(e);  // --help, --version
        }
        std::fprintf(stderr, "error: %s\n", vkdr::parseErrorText(app, e, argc, argv).c_str());
        return 2;
    }
    vkdr::stopOnInterruptSignals();
    try {
        for (const vkdr::CommandAction& action : actions) {
            int code = action();
            if (code >= 0) {
                return code;
            }
        }
    } catch (const vkdr::Interrupted& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return e.exitCode();
    } catch (const vkdr::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        // An input too large for this machine's memory (a huge file, image or scene).
        std::fprintf(stderr, "error: out of host memory: the inputs are too large for this machine\n");
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "internal error: %s\n", e.what());
        return 1;
    }
    return 0;
}
