#include "gpu/gl_context.h"

#include "util/error.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <mutex>
#include <vector>

namespace streak::gpu {

namespace {

bool hasExtension(const char* list, const std::string& name) {
    if (!list) return false;
    const std::string all = std::string(" ") + list + " ";
    return all.find(" " + name + " ") != std::string::npos;
}

}  // namespace

struct GlContext::Egl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
};

GlContext::GlContext() : m_egl(std::make_unique<Egl>()) {
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExtensions, "EGL_EXT_platform_base"))
        throw RenderFailure("no OpenGL context: EGL lacks EGL_EXT_platform_base (is libEGL with a driver installed?)");

    // eglGetPlatformDisplayEXT, not eglGetPlatformDisplay: epoxy aborts on the latter with
    // Debian 12's Mesa.
    auto tryInitialize = [&](EGLenum platform, void* nativeDisplay, const char* name) {
        EGLDisplay display = eglGetPlatformDisplayEXT(platform, nativeDisplay, nullptr);
        if (display == EGL_NO_DISPLAY) return false;
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) return false;
        m_egl->display = display;
        m_platform = name;
        return true;
    };
    bool isInitialized = false;
    if (hasExtension(clientExtensions, "EGL_EXT_platform_device") && hasExtension(clientExtensions, "EGL_EXT_device_enumeration")) {
        EGLint numDevices = 0;
        eglQueryDevicesEXT(0, nullptr, &numDevices);
        std::vector<EGLDeviceEXT> devices(std::size_t(std::max(numDevices, 0)));
        if (numDevices > 0 && eglQueryDevicesEXT(numDevices, devices.data(), &numDevices))
            for (EGLDeviceEXT device : devices) {
                // Mesa lists a software device too; take it only if nothing else works.
                const char* deviceExtensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
                if (hasExtension(deviceExtensions, "EGL_MESA_device_software")) continue;
                if (tryInitialize(EGL_PLATFORM_DEVICE_EXT, device, "device")) {
                    isInitialized = true;
                    break;
                }
            }
    }
    if (!isInitialized && hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
        isInitialized = tryInitialize(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, "surfaceless");
    if (!isInitialized) throw RenderFailure("no OpenGL context: no EGL device or surfaceless display could be initialized");

    if (!eglBindAPI(EGL_OPENGL_API)) throw RenderFailure("no OpenGL context: EGL cannot bind desktop OpenGL");
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint numConfigs = 0;
    const bool hasConfig = eglChooseConfig(m_egl->display, configAttributes, &config, 1, &numConfigs) && numConfigs > 0;
    if (!hasExtension(eglQueryString(m_egl->display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
        throw RenderFailure("no OpenGL context: EGL lacks EGL_KHR_surfaceless_context");
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    m_egl->context = eglCreateContext(m_egl->display, hasConfig ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, contextAttributes);
    if (m_egl->context == EGL_NO_CONTEXT) {
        eglTerminate(m_egl->display);
        throw RenderFailure("no OpenGL context: the " + m_platform + " EGL display cannot make an OpenGL 4.5 core context");
    }
    makeCurrent();
    m_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    m_version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

GlContext::~GlContext() {
    if (m_egl->display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(m_egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (m_egl->context != EGL_NO_CONTEXT) eglDestroyContext(m_egl->display, m_egl->context);
    eglTerminate(m_egl->display);
}

void GlContext::makeCurrent() const {
    if (!eglMakeCurrent(m_egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_egl->context))
        throw RenderFailure("OpenGL: cannot make the EGL context current");
}

GlContext& sharedContext() {
    // Never destroyed: GL objects held by static caches may outlive main().
    static GlContext* context = nullptr;
    static std::mutex mutex;
    const std::lock_guard lock(mutex);
    if (!context) context = new GlContext();
    context->makeCurrent();
    return *context;
}

}  // namespace streak::gpu
