#pragma once

#include "gpu/gl_object.h"
#include "util/stats.h"

#include <chrono>
#include <string>
#include <vector>

namespace streak::gpu {

// GpuTimer measures GPU time per pass with GL timestamp queries: the GPU clock when the
// commands before begin() and before end() completed, so a pass's time is what the GPU spent
// on it, not the CPU's submission time. Passes run one after another. Results are read once,
// after the frame, so timing costs no pipeline stall mid-frame. A software rasterizer
// (llvmpipe) runs draws at the next flush and stamps queries as it bins them, so there each
// begin() and end() waits for the work before it (glFinish) and reads the CPU clock instead.
class GpuTimer {
public:
    GpuTimer();
    void begin(const std::string& pass);
    void end();
    // Adds "gpu <pass>" phases (seconds) to `stats`, summing passes of one name, and the total
    // as "gpu total".
    void report(RenderStats& stats);

private:
    struct Pass {
        std::string name;
        GlQuery start{GL_TIMESTAMP}, stop{GL_TIMESTAMP};
        std::chrono::steady_clock::time_point startClock, stopClock;  ///< software rasterizers
    };
    std::vector<Pass> m_passes;
    bool m_isOpen = false;
    bool m_finishFirst = false;
};

}  // namespace streak::gpu
