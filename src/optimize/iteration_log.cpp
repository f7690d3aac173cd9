#include "optimize/iteration_log.h"

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "image/atomic_write.h"
#include "optimize/json_numbers.h"

namespace vkdr {

std::string iterationJsonLine(const IterationRecord& record) {
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    nlohmann::ordered_json gradients = nlohmann::ordered_json::object();
    for (const ParameterGradient& parameter : record.parameters) {
        values[parameter.name] = floatArray(parameter.value);
        gradients[parameter.name] = parameter.gradient;
    }
    nlohmann::ordered_json line = {{"iteration", record.iteration},
                                   {"loss", record.loss},
                                   {"parameters", values},
                                   {"gradients", gradients},
                                   {"forward_ms", record.forwardMs},
                                   {"adjoint_ms", record.adjointMs}};
    return line.dump();
}

IterationLog::IterationLog(std::filesystem::path file, uint32_t iterations) : file_(std::move(file)) {
    std::ifstream in(file_);
    for (std::string line; std::getline(in, line);) {
        nlohmann::json record = nlohmann::json::parse(line, nullptr, false);
        bool earlier = record.is_object() && record.contains("iteration") &&
                       record["iteration"].is_number_unsigned() && record["iteration"].get<uint64_t>() < iterations;
        if (earlier) text_ += line + "\n";
    }
    writeAtomically(file_, [&](std::ofstream& stream) { stream << text_; });
}

void IterationLog::append(const IterationRecord& record) {
    text_ += iterationJsonLine(record) + "\n";
    writeAtomically(file_, [&](std::ofstream& stream) { stream << text_; });
}

}  // namespace vkdr
