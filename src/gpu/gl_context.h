#pragma once

#include <memory>
#include <string>

namespace streak::gpu {

// GlContext is a headless desktop OpenGL 4.5 core context made current on the calling thread:
// no window and no display server. EGL comes first through its device platform (NVIDIA's
// driver, or Mesa with a render node), then Mesa's surfaceless platform (llvmpipe: what tests
// and CI use). Entry points come through libepoxy. Creating one throws Error, one line naming
// what was missing, where no such context can be made.
class GlContext {
public:
    GlContext();
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    // Makes the context current on this thread (a renderer may be called from any thread).
    void makeCurrent() const;

    const std::string& renderer() const { return m_renderer; }  ///< GL_RENDERER
    const std::string& version() const { return m_version; }    ///< GL_VERSION
    const std::string& platform() const { return m_platform; }  ///< "device" or "surfaceless"
    // A rasterizer running on the CPU (Mesa's llvmpipe or softpipe), whose work is deferred to
    // flushes, so a timestamp marks submission rather than completion.
    bool isSoftware() const { return m_renderer.find("llvmpipe") != std::string::npos || m_renderer.find("softpipe") != std::string::npos; }

private:
    struct Egl;
    std::unique_ptr<Egl> m_egl;
    std::string m_renderer, m_version, m_platform;
};

// The process's one context, created on first use and kept until exit: EGL setup costs tens of
// milliseconds, and GL objects of one render must not outlive their context.
GlContext& sharedContext();

}  // namespace streak::gpu
