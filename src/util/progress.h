#pragma once

#include <atomic>
#include <cstddef>
#include <thread>

namespace streak {

// ProgressReporter hears how far a long render is (0..1). Methods call update() from the thread
// that called render(); the command line draws a bar on stderr when it is a terminal.
class ProgressReporter {
public:
    virtual ~ProgressReporter() = default;
    virtual void update(double fraction) = 0;
};

// Progress over the parts of a parallel pass (tiles), told from whichever thread finishes one
// and reported only from the thread that made it, the one that called render() (the contract
// above: a Python callback, for one, must not run on a worker). That thread runs parts of the
// pass too, so the fraction advances as it finishes each of its own.
class PartsProgress {
public:
    PartsProgress(ProgressReporter* reporter, std::size_t numParts)
        : m_reporter(reporter), m_numParts(numParts), m_caller(std::this_thread::get_id()) {}
    void partDone() {
        const std::size_t done = m_done.fetch_add(1, std::memory_order_relaxed) + 1;
        if (m_reporter && m_numParts > 0 && std::this_thread::get_id() == m_caller) m_reporter->update(double(done) / double(m_numParts));
    }

private:
    ProgressReporter* m_reporter;
    std::size_t m_numParts;
    std::thread::id m_caller;
    std::atomic<std::size_t> m_done{0};
};

}  // namespace streak
