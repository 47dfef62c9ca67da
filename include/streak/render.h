#pragma once

// Rendering a scene with a method: the methods by name, how to render, the image and figures.

#include "streak/image.h"
#include "streak/scene.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace streak::api {

// The largest image width or height streak renders.
inline constexpr int kMaxImageSize = 16384;

// A method streak renders with (`streak methods`).
struct Method {
    std::string name;
    std::string description;
};
std::vector<Method> methods();

// The memory a render should stay within by default (MB): a third of a 24 GB machine.
inline constexpr int kDefaultMemoryBudgetMB = 8192;

// How to render: the method by name and its options (as --option KEY=VALUE: samples,
// max-intervals, ...), the image size, N x N anti-aliasing (n-rooks, or the regular grid),
// Phong or unlit shading, the seed, the worker threads (0: all cores), and the memory budget.
// The exact methods (motion-path, analytic, higher-order) keep their tile lists within what the
// budget leaves above the scene, splitting tiles that would pass it; the stats count the splits
// (memory_budget_splits) and, where a single pixel passed it, what was cut
// (memory_budget_pixels_cut, memory_budget_dropped).
// A rectangle of pixels of the image, [x0, x1) x [y0, y1) (Blender's border render).
struct Region {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct RenderSettings {
    std::string method = "motion-path";
    std::map<std::string, std::string> options;
    int width = 1024, height = 768;
    // Render only this rectangle of the width x height image: the result is its pixels, placed
    // in the frame (Image::isRegion), each bit for bit the whole frame's, so regions rendered
    // apart (on other machines) stitch() into the whole frame without seams. (Unless the
    // memory budget cuts a pixel's lists, memory_budget_pixels_cut: the cut depends on the
    // memory the process holds.)
    std::optional<Region> region;
    int aa = 1;
    // Adaptive antialiasing, 0 off (motion-path, analytic, higher-order): every pixel first takes
    // one sample at its centre, exact over the shutter; then the pixels where it or a neighbour
    // differs from the other by more than this, in sRGB-encoded colour (0..1) or coverage, are
    // rendered again from aa x aa samples (or half as many a side: adaptiveFull). A blurred edge ramps gently and mostly keeps one
    // sample; still edges and silhouettes across the motion are refined. 0.02 refines what
    // aliasing would show; lower refines more.
    float adaptive = 0.0f;
    // How many samples a refined pixel takes follows its contrast: where its largest difference
    // is at most this, half the samples a side (at least 2, so at aa 3 or more), else aa x aa.
    // 0 means three times `adaptive`; `adaptive` itself (or less) gives every refined pixel aa x aa.
    float adaptiveFull = 0.0f;
    // A transparent background (Blender's Film > Transparent): the image gets alpha, each pixel's
    // exact coverage over its samples and the shutter (a translucent surface covers by its
    // opacity), and its colour is what shows over a background of alpha 0, premultiplied.
    bool transparent = false;
    // Passes written beside the colour, as named channels of the image (EXR): "depth" (Z, the
    // coverage-weighted mean view depth of what shows over the pixel's samples and the shutter,
    // and Z.min, the nearest; 1e10 where nothing shows), "object_id" and "material_id"
    // (Cryptomatte 1.1 layers CryptoObject00... and CryptoMaterial00...: cryptomatteRanks ranked
    // (ID, coverage) pairs of the scene's object and material names, the coverages of a pixel
    // summing to its alpha): written by motion-path, analytic, higher-order and motion-path-gl
    // (exact), and by embree, accumulation and stochastic (sampled: their estimate at their
    // shutter times), refused by the others (post-filter, blur-shell, the other GL twins). "albedo" (albedo.R/G/B: the unlit colour of what shows,
    // premultiplied as the colour): every method, by one more render shaded unlit. "normal"
    // (normal.X/Y/Z: the world-space unit normal of what shows, averaged and premultiplied
    // likewise): every method, by one more render. "vector" (vector.X/Y/Z/W, Blender's Vector:
    // the screen motion in pixels, y up, of the surface point that shows from the frame to the
    // frame before and from the frame after to the frame, Cycles' signs, averaged as the
    // normal): the CPU methods on a scene with frames (Scene::load of a glTF, OBJ or PLY file),
    // by two more renders.
    std::vector<std::string> passes;
    int cryptomatteRanks = 6;
    // A deep image beside the colour (RenderResult::deep): per pixel, what shows as deep
    // samples, one per surface layer (the surfaces of one object over overlapping depths), from
    // the nearest depth at which it shows over the shutter to the farthest. A moving surface's
    // alpha is its exposure: the samples' alphas are chosen so that compositing them front to
    // back gives the render's colour and alpha exactly. At most deepSamples layers per pixel
    // (the closest in depth are joined past it; counted in the stats as deep_layers_merged),
    // and, without a transparent background, the background's sample behind them at z 1e10.
    // Written by the methods that write the depth and Cryptomatte passes, exact or sampled (a
    // sampled method's layers are the surfaces it hit at its times), refused by the others.
    bool deep = false;
    int deepSamples = 16;
    bool sampleGrid = false;
    bool unlit = false;
    std::uint64_t seed = 0;
    int threads = 0;
    int memoryBudgetMB = kDefaultMemoryBudgetMB;
};

// The figures of a render, as the command line's --stats writes them: wall time per phase (ms,
// in the order the phases first ran), counters, and facts (scene, method, camera, shutter).
struct Stats {
    std::vector<std::pair<std::string, double>> timesMs;
    std::map<std::string, double> counters;
    std::map<std::string, std::string> info;
    // {"info": {...}, "time_ms": {...}, "counters": {...}}
    std::string json() const;
};

struct RenderResult {
    Image image;
    Stats stats;
    std::optional<DeepImage> deep;  ///< with RenderSettings::deep
};

// A method set up for one kind of image, kept between renders: a sequence of frames, or the
// same frame again warm (GL programs built, caches filled).
class Renderer {
public:
    // Throws Error for an unknown method, an option it does not take, or bad settings.
    explicit Renderer(const RenderSettings& settings);
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;

    // The trail a trail method (blur-shell) shows instead of the shutter: load a glTF scene for
    // it with LoadOptions::trail. Empty for the shutter-average methods.
    std::optional<Trail> trail() const;

    // progress, if given, is called with the share done, from 0 to 1. cancel, if given, is asked
    // before the render and with every progress step (each tile of the exact methods, each
    // instant, each row of rays), on the thread that called render(); once it returns true the
    // render stops and throws Cancelled.
    RenderResult render(const Scene& scene, const std::function<void(double)>& progress = {}, const std::function<bool()>& cancel = {});

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

// One render with a Renderer made for it.
RenderResult render(const Scene& scene, const RenderSettings& settings);

}  // namespace streak::api
