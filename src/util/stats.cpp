#include "util/stats.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace streak {

void RenderStats::addTime(const std::string& phase, double seconds) {
    for (auto& [name, total] : m_phases) {
        if (name == phase) {
            total += seconds;
            return;
        }
    }
    m_phases.emplace_back(phase, seconds);
}

double RenderStats::time(const std::string& phase) const {
    for (const auto& [name, total] : m_phases)
        if (name == phase) return total;
    return 0.0;
}

double RenderStats::counter(const std::string& name) const {
    const auto it = m_counters.find(name);
    return it == m_counters.end() ? 0.0 : it->second;
}

std::string RenderStats::toJson() const {
    nlohmann::ordered_json json;
    json["info"] = nlohmann::ordered_json::object();
    for (const auto& [name, value] : m_info) json["info"][name] = value;
    json["time_ms"] = nlohmann::ordered_json::object();
    for (const auto& [name, seconds] : m_phases) json["time_ms"][name] = seconds * 1000.0;
    json["counters"] = nlohmann::ordered_json::object();
    for (const auto& [name, value] : m_counters) {
        // Whole numbers print as integers; NaN/Inf (not JSON) as null.
        if (!std::isfinite(value)) json["counters"][name] = nullptr;
        else if (value == std::floor(value) && std::fabs(value) < 9e15) json["counters"][name] = std::int64_t(value);
        else json["counters"][name] = value;
    }
    return json.dump(2) + "\n";
}

}  // namespace streak
