#pragma once

#include <map>
#include <set>
#include <string>
#include <string_view>

namespace streak {

// OptionMap holds key=value options for a named thing (a built-in scene, a method) and parses
// them on request. Every getter records its key as known; rejectUnknown() then throws Error for
// any key the thing never asked for, listing the ones it takes. So a typo is an error, not a
// silently ignored setting.
class OptionMap {
public:
    explicit OptionMap(std::string owner = "options") : m_owner(std::move(owner)) {}

    // Parses "a=1&b=2" (the query part of "builtin:cubes?n=2000"); throws Error on a malformed pair.
    static OptionMap parseQuery(std::string_view query, std::string owner);

    void set(const std::string& key, const std::string& value) { m_values[key] = value; }
    bool has(const std::string& key) const { return m_values.count(key) != 0; }
    const std::string& owner() const { return m_owner; }
    void setOwner(std::string owner) { m_owner = std::move(owner); }

    // Each returns the value of key, or fallback when absent; Error when not a number in range.
    int getInt(const std::string& key, int fallback, int min, int max);
    double getDouble(const std::string& key, double fallback, double min, double max);
    std::string getString(const std::string& key, const std::string& fallback);

    void rejectUnknown() const;

private:
    std::string m_owner;                        ///< e.g. "scene 'cubes'", for error messages
    std::map<std::string, std::string> m_values;
    std::set<std::string> m_known;              ///< keys some getter asked for
};

}  // namespace streak
