#pragma once

#include "image/image.h"
#include "image/passes.h"
#include "raster/screen_triangle.h"
#include "scene/scene.h"
#include "scene/shading.h"
#include "util/progress.h"
#include "util/stats.h"

#include <cstdint>
#include <optional>

namespace streak {

// The default memory budget: a third of a 24 GB machine, leaving the rest to the system and the
// applications beside streak.
inline constexpr std::uint64_t kDefaultMemoryBudgetMB = 8192;

// Settings every method honours. Method-specific settings (sample counts, budgets) are options
// the method parses itself at creation (see registry.h).
struct RenderSettings {
    int width = 1024;                          ///< pixels
    int height = 768;                          ///< pixels
    int aa = 1;                                ///< N: N x N sub-pixel samples, box filter
    bool isGridPattern = false;                ///< the N x N grid of cell centres instead of n-rooks (raster::SamplePattern)
    // Adaptive antialiasing (exposure::AdaptiveSampling), 0 off: one sample per pixel first, then
    // more where a pixel's neighbourhood differs by more than this in sRGB colour or coverage
    // (the N x N pattern, or half its samples a side: adaptiveFullContrast). Only a method whose
    // refinesAdaptively() is true is given one.
    float adaptiveThreshold = 0.0f;
    // Of the pixels it refines, those whose largest difference is at most this take half the
    // samples a side (at least 2), the rest the full N x N (AdaptiveSampling::Level): 0 means
    // three times adaptiveThreshold; at most adaptiveThreshold, every refined pixel takes N x N.
    float adaptiveFullContrast = 0.0f;
    ShadingMode shading = ShadingMode::Phong;
    std::uint64_t seed = 0;                    ///< for methods that sample randomly
    // Memory: the process should hold at most memoryBudgetMB. The exact methods' tile lists take
    // what the budget leaves when their tile pass starts, split over the threads, and split a
    // tile that would pass it (exposure::TileBudget). tileShareBytes, when not 0, is one
    // thread's share itself, whatever is resident (tests make a scene overflow a known share).
    std::uint64_t memoryBudgetMB = kDefaultMemoryBudgetMB;
    std::uint64_t tileShareBytes = 0;
    // Only these pixels (inclusive bounds) are asked for: a method may leave the others
    // unrendered, but every pixel inside must be what the whole frame's render gives it, to the
    // bit (a region render; the caller crops). None: the whole image.
    std::optional<raster::PixelBounds> region;
    // Passes to write as channels of the image besides the colour (only a method whose
    // writesPasses() is true is asked for them).
    PassRequest passes;
};

// Where a render reports how it went.
struct RenderContext {
    RenderStats& stats;                        ///< phase times and method counters
    ProgressReporter* progress = nullptr;      ///< may be null
};

// The stretch of animation a method shows when it is not a shutter average: the trail of the
// lengthSeconds before the frame's time T, sampled by `keys` poses evenly spaced from T - length
// to T. The caller loads an animated scene (glTF) over that stretch, so the shutter is the trail.
struct AnimationTrail {
    double lengthSeconds = 0.0;
    int keys = 2;
};

// Renderer is one motion-blur method: it turns a validated scene into a linear-light image of
// the whole shutter interval [0, 1]. Implementations live in src/methods/<name>/, are created by
// name through the registry, and use only scene/, raster/, image/ and gpu/: never each other.
class Renderer {
public:
    virtual ~Renderer() = default;

    // Renders `scene` (already validated) at settings.width x settings.height. Throws Error
    // for settings the method cannot honour.
    virtual Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) = 0;

    // Whether the method writes the passes of RenderSettings::passes (depth, Cryptomatte).
    virtual bool writesPasses() const { return false; }

    // Whether the method honours RenderSettings::adaptiveThreshold.
    virtual bool refinesAdaptively() const { return false; }

    // The trail the method needs loaded instead of the shutter (blur-shell); none by default.
    virtual std::optional<AnimationTrail> animationTrail() const { return std::nullopt; }
};

}  // namespace streak
