#include "cli/parse_error_text.h"

#include <regex>
#include <vector>

namespace vkdr {
namespace {

// Whether `word` follows an option's value on the command line (`--set a=1 b=2`): the
// option took one value, and the word is left over.
bool followsAnOptionsValue(const std::string& word, int argc, const char* const* argv) {
    for (int i = 2; i < argc; ++i) {
        if (argv[i] == word && argv[i - 1][0] != '-' && argv[i - 2][0] == '-') return true;
    }
    return false;
}

// CLI11's reason, in plain words where CLI11 gives its own terms: an option of one value
// given more than once ("--spp: At Most 1 required but received 2"), an option without
// its value ("--spp: 1 required UINT:an integer from 1 to 1048576 missing") and words no
// option or argument takes ("The following argument was not expected: b").
std::string reasonOf(const CLI::ParseError& error, int argc, const char* const* argv) {
    static const std::regex kRepeated("(.+): At Most 1 required but received ([0-9]+)");
    static const std::regex kMissing("(.+): 1 required ([A-Z]+)(:(.*))? missing");
    static const std::regex kUnexpected("The following arguments? (was|were) not expected: ([^ ]*)(.*)");
    std::cmatch match;
    if (std::regex_match(error.what(), match, kRepeated)) {
        return match[1].str() + ": given " + match[2].str() + " times; give it once";
    }
    if (std::regex_match(error.what(), match, kMissing)) {
        return match[1].str() + ": no value given" + (match[4].matched ? " (expected " + match[4].str() + ")" : "");
    }
    if (std::regex_match(error.what(), match, kUnexpected)) {
        const std::string first = match[2].str();
        return "unexpected argument" + std::string(match[1] == "were" ? "s " : " ") + first + match[3].str() +
               (followsAnOptionsValue(first, argc, argv)
                    ? "; an option takes one value each time it is given (give it again for another)"
                    : "");
    }
    return error.what();
}

}  // namespace

std::string parseErrorText(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv) {
    const std::string program = app.get_name();
    std::vector<CLI::App*> given = app.get_subcommands();
    if (!given.empty()) {
        return reasonOf(error, argc, argv) + "; see '" + program + " " + given.front()->get_name() + " --help'";
    }
    std::string commands;
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
        commands += (commands.empty() ? "" : ", ") + command->get_name();
    }
    if (argc > 1 && argv[1][0] != '-') {
        return "unknown command '" + std::string(argv[1]) + "'; the commands are " + commands + " (see '" + program +
               " --help')";
    }
    return reasonOf(error, argc, argv) + ": one of " + commands + " (see '" + program + " --help')";
}

}  // namespace vkdr
