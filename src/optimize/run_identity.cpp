#include "optimize/run_identity.h"

#include <algorithm>
#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <map>

#include "core/error.h"
#include "image/regular_file.h"
#include "optimize/loss_kind_text.h"
#include "scene/parameters.h"

namespace vkdr {
namespace {

// The shortest text that reads back as `value`: 0.01 as typed, not its 17 digits.
std::string numberText(double value) {
    char text[32];
    const auto [end, ignored] = std::to_chars(text, text + sizeof(text), value);
    return std::string(text, end);
}

// `text` if it is not wholly a number, else numberText of it.
std::string shortestIfNumber(const std::string& text) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    return error == std::errc() && end == text.data() + text.size() ? numberText(value) : text;
}

// Checkpoints written before numberText wrote the shortest text hold 17 digits: the
// entries of numbers compare, and are printed, as the numbers they hold.
void shortenNumbers(RunIdentity& identity) {
    for (const char* name : {"learning_rate", "learning_rate_decay", "learning_rate_decay_start", "adam_epsilon",
                             "smoothness", "sparsity", "total_variation"}) {
        if (auto entry = identity.find(name); entry != identity.end()) entry->second = shortestIfNumber(entry->second);
    }
    // NAME=RATE NAME=RATE ...: a name may hold spaces, a rate none.
    if (auto rates = identity.find("learning_rates"); rates != identity.end()) {
        std::string& text = rates->second;
        for (size_t equals = text.find('='); equals != std::string::npos; equals = text.find('=', equals + 1)) {
            const size_t end = std::min(text.find(' ', equals), text.size());
            const std::string number = shortestIfNumber(text.substr(equals + 1, end - equals - 1));
            text.replace(equals + 1, end - equals - 1, number);
        }
    }
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
    std::string text;
    for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
    return text;
}

std::string fileIdentity(const std::filesystem::path& file) {
    return file.filename().string() + ", " + fileDigest(file);
}

// A target's file by digest, after its camera: "side=1234 bytes, fnv1a64 ...".
std::string targetIdentity(const TargetFile& target) {
    return (target.camera.empty() ? "" : target.camera + "=") + fileDigest(target.file);
}

// A checkpoint's "set" entry, its assignments joined by spaces, with each written as
// canonicalAssignment writes it (checkpoints written before the entry was canonical hold
// the values as typed), the last of each name only (as --set takes them), in the order
// of the names: assignments given in another order set the same values. A name may hold
// spaces, so words are joined until they make an assignment; text that makes none is
// left as it is.
std::string canonicalAssignments(const std::string& joinedAssignments) {
    std::map<std::string, std::string> assignments;  // by name
    std::string pending;
    size_t start = 0;
    while (start <= joinedAssignments.size()) {
        size_t space = joinedAssignments.find(' ', start);
        if (space == std::string::npos) space = joinedAssignments.size();
        pending += (pending.empty() ? "" : " ") + joinedAssignments.substr(start, space - start);
        try {
            std::string assignment = canonicalAssignment(pending);
            // The values are numbers: the name is what comes before the last '='.
            assignments[assignment.substr(0, assignment.rfind('='))] = assignment;
            pending.clear();
        } catch (const Error&) {
            // Not an assignment yet: the next word may go on with the name.
        }
        start = space + 1;
    }
    std::vector<std::string> ordered;
    for (const auto& [name, assignment] : assignments) ordered.push_back(assignment);
    return pending.empty() ? joined(ordered, " ") : joinedAssignments;
}

}  // namespace

RunIdentity runIdentity(const std::filesystem::path& sceneFile, const OptimizeOptions& options, LossKind loss,
                        const RunInputs& inputs) {
    RunIdentity identity;
    if (inputs.experiment.empty()) {
        std::vector<std::string> targets;
        for (const TargetFile& target : inputs.targets) targets.push_back(targetIdentity(target));
        identity["targets"] = joined(targets, "; ");
        // Split as an older checkpoint's entry is (canonicalAssignments), so that a name
        // holding a space and "=" compares alike on both sides.
        identity["set"] = canonicalAssignments(joined(inputs.assignments, " "));
    } else {
        identity["experiment"] = fileIdentity(inputs.experiment);
    }
    identity["spp"] = std::to_string(inputs.spp);
    identity["max_depth"] = std::to_string(inputs.maxDepth);
    // Only where off: the checkpoints written before it was recorded keep their identity,
    // and were written with it on or are refused.
    if (!inputs.equiangularSampling) identity["equiangular_sampling"] = "off";
    identity["scene"] = fileIdentity(sceneFile);
    identity["parameters"] = joined(options.parameters, " ");
    identity["optimizer"] = optimizerKindName(options.optimizer);
    identity["learning_rate"] = numberText(options.learningRate);
    std::vector<std::string> rates;
    for (const auto& [name, rate] : options.learningRates) rates.push_back(name + "=" + numberText(rate));
    identity["learning_rates"] = joined(rates, " ");
    identity["learning_rate_decay"] = numberText(options.learningRateDecay);
    identity["learning_rate_decay_start"] = numberText(options.learningRateDecayStart);
    identity["log_parameters"] = joined(options.logParameters, " ");
    identity["adam_epsilon"] = numberText(options.adamEpsilon);
    identity["smoothness"] = numberText(options.smoothness);
    identity["sparsity"] = numberText(options.sparsity);
    // Only where set, so that the runs of the versions before it keep their identity.
    if (options.totalVariation != 0.0) identity["total_variation"] = numberText(options.totalVariation);
    identity["grid_levels"] = std::to_string(options.gridLevels);
    identity["iterations"] = std::to_string(options.iterations);
    identity["seed"] = std::to_string(options.seed);
    identity["loss"] = lossKindName(loss);
    return identity;
}

void addSceneFiles(RunIdentity& identity, const Scene& scene) {
    std::vector<std::filesystem::path> files;
    for (size_t i = 1; i < scene.sourceFiles.size(); ++i) files.push_back(scene.sourceFiles[i].file);
    for (const SceneDensityGrid& grid : scene.densityGrids) files.push_back(grid.file);
    std::vector<std::string> identities;
    for (const std::filesystem::path& file : files) {
        const std::string text = fileIdentity(file);
        if (std::find(identities.begin(), identities.end(), text) == identities.end()) identities.push_back(text);
    }
    if (!identities.empty()) identity["scene_files"] = joined(identities, "; ");
}

std::string fileDigest(const std::filesystem::path& file) {
    RegularFile in(file);
    uint64_t hash = 0xcbf29ce484222325ull;  // FNV-1a offset basis and prime
    uint64_t size = 0;
    char buffer[1 << 16];
    while (size_t got = in.read(buffer, sizeof(buffer))) {
        for (size_t i = 0; i < got; ++i) {
            hash = (hash ^ uint64_t(static_cast<unsigned char>(buffer[i]))) * 0x100000001b3ull;
        }
        size += got;
    }
    char text[64];
    std::snprintf(text, sizeof(text), "%" PRIu64 " bytes, fnv1a64 %016" PRIx64, size, hash);
    return text;
}

void requireSameRun(const std::filesystem::path& checkpoint, const RunIdentity& writtenAsStored,
                    const RunIdentity& current) {
    auto valueIn = [](const RunIdentity& identity, const std::string& name) {
        auto found = identity.find(name);
        return found == identity.end() ? std::string("(none)") : "'" + found->second + "'";
    };
    RunIdentity written = writtenAsStored;
    if (auto set = written.find("set"); set != written.end()) set->second = canonicalAssignments(set->second);
    shortenNumbers(written);
    RunIdentity names = written;
    names.insert(current.begin(), current.end());
    for (const auto& [name, ignored] : names) {
        // Checkpoints written before the scene's own files were recorded can only be
        // taken at their word, as they were before.
        if (name == "scene_files" && !written.contains(name)) continue;
        std::string before = valueIn(written, name), now = valueIn(current, name);
        if (before != now) {
            throw Error(checkpoint.string() + ": written by a run with " + name + " " + before + ", but this run has " +
                        now + "; resume with the same scene, targets, parameters and options, or start afresh in "
                        "another --out directory");
        }
    }
}

}  // namespace vkdr
