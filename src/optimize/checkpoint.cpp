#include "optimize/checkpoint.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "image/atomic_write.h"
#include "image/regular_file.h"
#include "optimize/base64.h"
#include "scene/parse_json_text.h"

namespace vkdr {
namespace {

using Json = nlohmann::ordered_json;

constexpr double kFloatMax = double(std::numeric_limits<float>::max());
constexpr double kDoubleMax = std::numeric_limits<double>::max();

// `value` to `digits` significant digits: 6 say a range, 17 the exact double.
std::string text(double value, int digits = 6) {
    char number[40];
    std::snprintf(number, sizeof(number), "%.*g", digits, value);
    return number;
}

// Names the file format, so that another JSON file is not taken for a checkpoint and a
// later format can be told apart. Format 1 wrote every vector as an array; format 2
// writes long ones as base64 (numbersJson), and reads both.
constexpr const char* kFormat = "vkdiffrender optimize checkpoint 2";
constexpr const char* kFormatWithArraysOnly = "vkdiffrender optimize checkpoint 1";

// Beyond this many numbers a vector is written as the base64 of its little-endian
// binary64 values: 10.7 characters a number instead of about 25 in indented JSON, and no
// decimal conversion either way, which is what a checkpoint of a density grid's millions
// of voxels (values and Adam's two moments) spends its time on.
constexpr size_t kMostNumbersInAnArray = 1024;

Json numbersJson(const std::vector<double>& values) {
    if (values.size() <= kMostNumbersInAnArray) return values;
    std::vector<unsigned char> bytes;
    bytes.reserve(values.size() * 8);
    for (double value : values) {
        const uint64_t bits = std::bit_cast<uint64_t>(value);
        for (int k = 0; k < 8; ++k) bytes.push_back(static_cast<unsigned char>(bits >> (8 * k)));
    }
    return base64(bytes);
}

// The doubles numbersJson encoded as `text`; nothing if it is not base64 of whole doubles.
std::optional<std::vector<double>> numbersOfBase64(const std::string& text) {
    std::optional<std::vector<unsigned char>> bytes = decodeBase64(text);
    if (!bytes || bytes->size() % 8 != 0) return std::nullopt;
    std::vector<double> values(bytes->size() / 8);
    for (size_t i = 0; i < values.size(); ++i) {
        uint64_t bits = 0;
        for (int k = 0; k < 8; ++k) bits |= uint64_t((*bytes)[8 * i + k]) << (8 * k);
        values[i] = std::bit_cast<double>(bits);
    }
    return values;
}

class CheckpointReader {
public:
    explicit CheckpointReader(std::filesystem::path file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
        throw Error(file_.string() + ": " + (key.empty() ? "" : within_ + key + ": ") + problem);
    }

    // A reader of the object `key` holds, whose messages name its keys as "key.name".
    CheckpointReader inside(const std::string& key) const {
        CheckpointReader reader = *this;
        reader.within_ += key + ".";
        return reader;
    }

    Json parse() const {
        const std::string text = readRegularFile(file_);
        if (text.find_first_not_of(" \t\r\n") == std::string::npos) fail("", "empty");
        ParsedJsonText<Json> parsed;
        try {
            parsed = parseJsonText<Json>(text);
        } catch (const Json::exception& error) {  // parse_error, or out_of_range for 1e999
            fail("", "not valid JSON (damaged or cut short): " + jsonErrorText(error));
        }
        // A checkpoint is written once per key; a repeated one was edited by hand.
        if (parsed.repeatedKey) fail(*parsed.repeatedKey, kRepeatedKeyProblem);
        Json& document = parsed.document;
        if (!document.is_object()) fail("", std::string("expected a JSON object, got ") + document.type_name());
        if (!document.contains("format") ||
            (document["format"] != kFormat && document["format"] != kFormatWithArraysOnly)) {
            fail("format", std::string("not a checkpoint (expected \"") + kFormat + "\" or \"" +
                               kFormatWithArraysOnly + "\")");
        }
        return std::move(document);
    }

    const Json& member(const Json& object, const std::string& key) const {
        if (!object.is_object() || !object.contains(key)) fail(key, "missing");
        return object.at(key);
    }

    uint64_t count(const Json& object, const std::string& key) const {
        const Json& value = member(object, key);
        if (!value.is_number_unsigned()) fail(key, "expected an integer >= 0");
        return value.get<uint64_t>();
    }

    double number(const Json& object, const std::string& key) const {
        const Json& value = member(object, key);
        if (!value.is_number() || !std::isfinite(value.get<double>())) fail(key, "expected a finite number");
        return value.get<double>();
    }

    // Milliseconds spent: the report prints them and divides them by the iterations.
    // More than a run could have spent (about 32 years) is a damaged file.
    double duration(const Json& object, const std::string& key) const {
        constexpr double kMostMilliseconds = 1e12;
        const double milliseconds = number(object, key);
        if (milliseconds < 0.0 || milliseconds > kMostMilliseconds) {
            fail(key, "expected milliseconds from 0 to 1e12 (about 32 years)");
        }
        return milliseconds;
    }

    // Numbers within [minimum, maximum]: parameter values become floats (the default
    // range), and Adam takes the square root of its second moments.
    std::vector<double> numbers(const Json& object, const std::string& key, double minimum = -kFloatMax,
                                double maximum = kFloatMax) const {
        const Json& stored = member(object, key);
        const std::string expected = "expected numbers in [" + text(minimum) + ", " + text(maximum) + "]";
        if (stored.is_string()) {
            std::optional<std::vector<double>> values = numbersOfBase64(stored.get<std::string>());
            if (!values) fail(key, "expected an array of numbers or base64 of binary64 values");
            for (double value : *values) {
                if (!(value >= minimum && value <= maximum)) fail(key, expected + ", got " + text(value, 17));
            }
            return *values;
        }
        if (!stored.is_array()) fail(key, "expected an array of numbers or base64 of binary64 values");
        std::vector<double> values;
        for (const Json& value : stored) {
            if (!value.is_number() || !(value.get<double>() >= minimum && value.get<double>() <= maximum)) {
                fail(key, expected + (value.is_number() ? ", got " + value.dump() : ""));
            }
            values.push_back(value.get<double>());
        }
        return values;
    }

    RunIdentity run(const Json& object) const {
        const Json& entries = member(object, "run");
        if (!entries.is_object()) fail("run", "expected an object of strings");
        RunIdentity identity;
        for (const auto& [name, value] : entries.items()) {
            if (!value.is_string()) fail("run." + name, "expected a string");
            identity[name] = value.get<std::string>();
        }
        return identity;
    }

private:
    std::filesystem::path file_;
    std::string within_;  // "optimizer." inside that object
};

}  // namespace

void writeCheckpoint(const std::filesystem::path& file, const Checkpoint& checkpoint) {
    const LoopState& state = checkpoint.state;
    Json run = Json::object();
    for (const auto& [name, value] : checkpoint.run) run[name] = value;
    Json document = {{"format", kFormat},
                     {"run", run},
                     {"iteration", state.iteration},
                     {"values", numbersJson(state.values)},
                     {"optimizer",
                      {{"steps", state.optimizer.steps},
                       {"mean", numbersJson(state.optimizer.mean)},
                       {"mean_square", numbersJson(state.optimizer.meanSquare)}}},
                     {"losses", numbersJson(state.losses)},
                     {"forward_ms", state.forwardMs},
                     {"adjoint_ms", state.adjointMs}};
    writeAtomically(file, [&](std::ofstream& out) { out << document.dump(1) << "\n"; });
}

Checkpoint readCheckpoint(const std::filesystem::path& file) {
    CheckpointReader reader(file);
    Json document = reader.parse();
    Checkpoint checkpoint;
    checkpoint.run = reader.run(document);
    LoopState& state = checkpoint.state;
    uint64_t iteration = reader.count(document, "iteration");
    if (iteration > UINT32_MAX) reader.fail("iteration", "expected an integer in [0, 4294967295]");
    state.iteration = uint32_t(iteration);
    state.values = reader.numbers(document, "values");
    const Json& optimizer = reader.member(document, "optimizer");
    const CheckpointReader inOptimizer = reader.inside("optimizer");
    state.optimizer.steps = inOptimizer.count(optimizer, "steps");
    // Adam's moments and the losses are doubles: a gradient beyond 1.8e19 squares past
    // float range.
    state.optimizer.mean = inOptimizer.numbers(optimizer, "mean", -kDoubleMax, kDoubleMax);
    state.optimizer.meanSquare = inOptimizer.numbers(optimizer, "mean_square", 0.0, kDoubleMax);
    state.losses = reader.numbers(document, "losses", 0.0, kDoubleMax);
    state.forwardMs = reader.duration(document, "forward_ms");
    state.adjointMs = reader.duration(document, "adjoint_ms");
    return checkpoint;
}

}  // namespace vkdr
