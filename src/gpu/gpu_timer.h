#pragma once

#include "gpu/gl_object.h"
#include "util/stats.h"

#include <string>
#include <vector>

namespace streak::gpu {

// GpuTimer measures GPU time per pass with GL timestamp queries: the GPU clock when the
// commands before begin() and before end() completed, so a pass's time is what the GPU spent
// on it, not the CPU's submission time. Passes run one after another. Results are read once, after the frame, so timing costs no
// pipeline stall mid-frame.
class GpuTimer {
public:
    void begin(const std::string& pass);
    void end();
    // Adds "gpu <pass>" phases (seconds) to `stats`, summing passes of one name, and the total
    // as "gpu total".
    void report(RenderStats& stats);

private:
    struct Pass {
        std::string name;
        GlQuery start{GL_TIMESTAMP}, stop{GL_TIMESTAMP};
    };
    std::vector<Pass> m_passes;
    bool m_isOpen = false;
};

}  // namespace streak::gpu
