#include "gpu/gpu_timer.h"

#include "gpu/gl_context.h"

namespace streak::gpu {

GpuTimer::GpuTimer() : m_finishFirst(sharedContext().isSoftware()) {}

void GpuTimer::begin(const std::string& pass) {
    if (m_isOpen) end();
    Pass& p = m_passes.emplace_back();
    p.name = pass;
    if (m_finishFirst) {
        glFinish();
        p.startClock = std::chrono::steady_clock::now();
    } else {
        glQueryCounter(p.start.id(), GL_TIMESTAMP);
    }
    m_isOpen = true;
}

void GpuTimer::end() {
    if (!m_isOpen) return;
    if (m_finishFirst) {
        glFinish();
        m_passes.back().stopClock = std::chrono::steady_clock::now();
    } else {
        glQueryCounter(m_passes.back().stop.id(), GL_TIMESTAMP);
    }
    m_isOpen = false;
}

void GpuTimer::report(RenderStats& stats) {
    end();
    double total = 0.0;
    for (const Pass& p : m_passes) {
        double seconds = std::chrono::duration<double>(p.stopClock - p.startClock).count();
        if (!m_finishFirst) {
            GLuint64 start = 0, stop = 0;
            glGetQueryObjectui64v(p.start.id(), GL_QUERY_RESULT, &start);
            glGetQueryObjectui64v(p.stop.id(), GL_QUERY_RESULT, &stop);
            seconds = double(stop > start ? stop - start : 0) * 1e-9;
        }
        stats.addTime("gpu " + p.name, seconds);
        total += seconds;
    }
    stats.addTime("gpu total", total);
    m_passes.clear();
}

}  // namespace streak::gpu
