#pragma once

namespace streak {

// ProgressReporter hears how far a long render is (0..1). Methods call update() from the thread
// that called render(); the command line draws a bar on stderr when it is a terminal.
class ProgressReporter {
public:
    virtual ~ProgressReporter() = default;
    virtual void update(double fraction) = 0;
};

}  // namespace streak
