#include "util/options.h"

#include "util/error.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace streak {

OptionMap OptionMap::parseQuery(std::string_view query, std::string owner) {
    OptionMap map(std::move(owner));
    while (!query.empty()) {
        const std::size_t amp = query.find('&');
        const std::string_view pair = query.substr(0, amp);
        const std::size_t eq = pair.find('=');
        if (eq == std::string_view::npos || eq == 0)
            throw Error(map.m_owner + ": expected key=value, got '" + std::string(pair) + "'");
        map.set(std::string(pair.substr(0, eq)), std::string(pair.substr(eq + 1)));
        if (amp == std::string_view::npos) break;
        query.remove_prefix(amp + 1);
    }
    return map;
}

int OptionMap::getInt(const std::string& key, int fallback, int min, int max) {
    m_known.insert(key);
    const auto it = m_values.find(key);
    if (it == m_values.end()) return fallback;
    const std::string& text = it->second;
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < min || value > max)
        throw Error(m_owner + ": " + key + " must be an integer in [" + std::to_string(min) + ", " +
                    std::to_string(max) + "], got '" + text + "'");
    return value;
}

double OptionMap::getDouble(const std::string& key, double fallback, double min, double max) {
    m_known.insert(key);
    const auto it = m_values.find(key);
    if (it == m_values.end()) return fallback;
    const std::string& text = it->second;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value) || value < min || value > max)
        throw Error(m_owner + ": " + key + " must be a number in [" + std::to_string(min) + ", " +
                    std::to_string(max) + "], got '" + text + "'");
    return value;
}

std::string OptionMap::getString(const std::string& key, const std::string& fallback) {
    m_known.insert(key);
    const auto it = m_values.find(key);
    return it == m_values.end() ? fallback : it->second;
}

void OptionMap::rejectUnknown() const {
    for (const auto& [key, value] : m_values) {
        if (m_known.count(key)) continue;
        std::string known;
        for (const std::string& k : m_known) known += (known.empty() ? "" : ", ") + k;
        throw Error(m_owner + " does not take option '" + key + "'" +
                    (known.empty() ? " (it takes none)" : " (it takes: " + known + ")"));
    }
}

}  // namespace streak
