#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace streak {

// RenderStats collects the figures of one render: wall time per phase (in the order phases
// first ran) and named counters (fragments, overflows, skipped triangles...). Methods fill it
// from the thread that called render(); the command line writes it as JSON with --stats.
class RenderStats {
public:
    void addTime(const std::string& phase, double seconds);
    void setCounter(const std::string& name, double value) { m_counters[name] = value; }
    void addCounter(const std::string& name, double delta) { m_counters[name] += delta; }
    void setInfo(const std::string& name, const std::string& value) { m_info[name] = value; }

    double time(const std::string& phase) const;
    double counter(const std::string& name) const;
    bool hasCounter(const std::string& name) const { return m_counters.count(name) != 0; }
    const std::vector<std::pair<std::string, double>>& phases() const { return m_phases; }
    const std::map<std::string, double>& counters() const { return m_counters; }
    const std::map<std::string, std::string>& info() const { return m_info; }

    // {"info": {...}, "time_ms": {phase: ms, ...}, "counters": {...}}, pretty-printed.
    std::string toJson() const;

private:
    std::vector<std::pair<std::string, double>> m_phases;  ///< phase, seconds
    std::map<std::string, double> m_counters;
    std::map<std::string, std::string> m_info;             ///< scene, method, sizes...
};

// Adds the wall time of its scope to one phase of a RenderStats.
class PhaseTimer {
public:
    PhaseTimer(RenderStats& stats, std::string phase)
        : m_stats(stats), m_phase(std::move(phase)), m_start(std::chrono::steady_clock::now()) {}
    ~PhaseTimer() { m_stats.addTime(m_phase, seconds()); }
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    }
    PhaseTimer(const PhaseTimer&) = delete;
    PhaseTimer& operator=(const PhaseTimer&) = delete;

private:
    RenderStats& m_stats;
    std::string m_phase;
    std::chrono::steady_clock::time_point m_start;
};

}  // namespace streak
