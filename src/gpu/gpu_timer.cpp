#include "gpu/gpu_timer.h"

namespace streak::gpu {

void GpuTimer::begin(const std::string& pass) {
    if (m_isOpen) end();
    Pass& p = m_passes.emplace_back();
    p.name = pass;
    glQueryCounter(p.start.id(), GL_TIMESTAMP);
    m_isOpen = true;
}

void GpuTimer::end() {
    if (!m_isOpen) return;
    glQueryCounter(m_passes.back().stop.id(), GL_TIMESTAMP);
    m_isOpen = false;
}

void GpuTimer::report(RenderStats& stats) {
    end();
    double total = 0.0;
    for (const Pass& p : m_passes) {
        GLuint64 start = 0, stop = 0;
        glGetQueryObjectui64v(p.start.id(), GL_QUERY_RESULT, &start);
        glGetQueryObjectui64v(p.stop.id(), GL_QUERY_RESULT, &stop);
        const GLuint64 nanoseconds = stop > start ? stop - start : 0;
        stats.addTime("gpu " + p.name, double(nanoseconds) * 1e-9);
        total += double(nanoseconds) * 1e-9;
    }
    stats.addTime("gpu total", total);
    m_passes.clear();
}

}  // namespace streak::gpu
