#include "methods/registry.h"

#include "methods/accumulation/accumulation_renderer.h"
#include "methods/accumulation_gl/accumulation_gl_renderer.h"
#include "methods/analytic/analytic_renderer.h"
#include "methods/blur_shell/blur_shell_renderer.h"
#include "methods/blur_shell_gl/blur_shell_gl_renderer.h"
#include "methods/embree/embree_renderer.h"
#include "methods/post_filter/post_filter_renderer.h"
#include "methods/post_filter_gl/post_filter_gl_renderer.h"
#include "methods/higher_order/higher_order_renderer.h"
#include "methods/motion_path/motion_path_renderer.h"
#include "methods/motion_path_gl/motion_path_gl_renderer.h"
#include "methods/stochastic/stochastic_renderer.h"
#include "methods/stochastic_gl/stochastic_gl_renderer.h"
#include "util/error.h"

#include <array>

namespace streak {

namespace {

// One line per method. Registration is explicit (no static self-registration, which the
// linker may drop along with an unreferenced method library).
const std::array kMethods{
    MethodInfo{"motion-path", "motion paths (Hong & Oh 2017): analytic time intervals per pixel, depth-time sort, time masks",
               createMotionPathRenderer},
    MethodInfo{"analytic", "analytic edge equations (Gribel et al. 2010): exact exposure intervals, exact resolve, compression",
               createAnalyticRenderer},
    MethodInfo{"higher-order", "higher-order motion (Gribel et al. 2013): Bezier vertex paths, edge equations of degree 2n solved exactly, INTERVAL traversal",
               createHigherOrderRenderer},
    MethodInfo{"blur-shell", "blur shell (Jones 2004): silhouette-of-motion trails as alpha-faded quad strips, geometry drawn over the mesh at the trail's end",
               createBlurShellRenderer},
    MethodInfo{"accumulation", "reference: averages depth-buffered renders at S stratified shutter times (samples=256)",
               createAccumulationRenderer},
    MethodInfo{"stochastic", "stochastic rasterization: each pixel sample has its own time (samples=8 per pixel)",
               createStochasticRenderer},
    MethodInfo{"embree", "ray-traced motion blur with Embree 3 (as CPU path tracers do it): S stratified ray times per pixel sample, stochastic's times (samples=8)",
               createEmbreeRenderer},
    MethodInfo{"post-filter", "the games' post-process blur (McGuire et al. 2012, Guertin et al. 2014): one frame at shutter centre with velocities, TileMax, NeighborMax, gather",
               createPostFilterRenderer},
    MethodInfo{"motion-path-gl", "motion paths on the GPU (OpenGL 4.5, headless EGL): paths rasterized into per-sample lists, exact spans, compute resolve",
               createMotionPathGlRenderer},
    MethodInfo{"accumulation-gl", "accumulation on the GPU (OpenGL 4.5, headless EGL): S depth-tested passes (samples=256)",
               createAccumulationGlRenderer},
    MethodInfo{"stochastic-gl", "stochastic rasterization on the GPU (OpenGL 4.5): per-sample times, space-time bounds (samples=8)",
               createStochasticGlRenderer},
    MethodInfo{"blur-shell-gl", "blur shell on the GPU (OpenGL 4.5): the shell built on the CPU, drawn over the mesh by the blender in submission order",
               createBlurShellGlRenderer},
    MethodInfo{"post-filter-gl", "the games' post-process blur on the GPU (OpenGL 4.5): centre frame and velocities, then TileMax, NeighborMax and gather as compute passes",
               createPostFilterGlRenderer},
};

}  // namespace

std::span<const MethodInfo> registeredMethods() { return kMethods; }

std::unique_ptr<Renderer> createRenderer(std::string_view name, OptionMap options) {
    for (const MethodInfo& method : kMethods) {
        if (method.name != name) continue;
        options.setOwner("method '" + std::string(name) + "'");
        std::unique_ptr<Renderer> renderer = method.create(options);
        options.rejectUnknown();
        return renderer;
    }
    std::string known;
    for (const MethodInfo& method : kMethods) known += (known.empty() ? "" : ", ") + std::string(method.name);
    throw Error("unknown method '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace streak
