#pragma once

#include "exposure/shading_site.h"
#include "scene/shading.h"
#include "scene/shutter.h"
#include "util/options.h"
#include "util/stats.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <string>

namespace streak::exposure {

// A surface point that moves over the shutter as seen through one pixel sample: a method's
// geometry (a moving triangle under a sample) behind one interface, so the shading below is
// shared by every method that shades time spans rather than instants.
class MovingSurfacePoint {
public:
    // The point at shutter time t; duvdx/duvdy are filled only when withFootprint is set.
    // Returns false where it cannot be evaluated (the triangle seen edge-on).
    virtual bool at(float t, bool withFootprint, SurfacePoint& out) const = 0;
    // Only the texture coordinate at time t: the texture taps' hot path. Override where it is
    // cheaper than at().
    virtual bool uvAt(float t, glm::vec2& uv) const {
        SurfacePoint p;
        if (!at(t, false, p)) return false;
        uv = p.uv;
        return true;
    }

    // Only the vertex colour at time t: all an untextured unlit span needs. Override where it is
    // cheaper than at().
    virtual bool vertexColorAt(float t, glm::vec4& color) const {
        SurfacePoint p;
        if (!at(t, false, p)) return false;
        color = p.vertexColor;
        return true;
    }

    // The uv corners of the triangle the point is held to, where a box footprint is clipped to
    // them (TextureFootprint::clipTo); null where the point is not held to one triangle.
    virtual const std::array<glm::vec2, 3>* uvTriangle() const { return nullptr; }
    // The point's footprint (SurfacePoint::duvdx, duvdy) is a region of the screen whose texels
    // count alike (TextureFootprint::isBox), not one sample's spacing: true where a pixel's
    // samples share the shading (ShadingSite::boxFootprint).
    virtual bool hasBoxFootprint() const { return false; }
    // A box footprint's fewest taps a side (ShadingSite::boxTaps).
    virtual glm::ivec2 boxTaps() const { return glm::ivec2(1); }
    // A box footprint's budget of taps (ShadingSite::boxBudget).
    virtual int boxBudget() const { return Texture::kMaxSweptBoxTaps; }

    // True when nothing the point is shaded from changes over [t0, t1] (its position, normal,
    // uv and footprint, and the eye): one instant then shades the whole span. False where the
    // method does not know.
    virtual bool isStill(float /*t0*/, float /*t1*/) const { return false; }

    // The samples a still point's shading shades each at its own point (ShadingSite::samples),
    // and the still surface's point under one of them, `middle`'s texture footprint taken (a
    // still triangle's footprint barely changes across a pixel, and finding it is most of a
    // still point's cost): empty, and false, where the point is shaded at its own place alone.
    virtual std::span<const SiteSample> sharedSamples() const { return {}; }
    virtual bool atSample(const glm::dvec2& /*ndc*/, const SurfacePoint& /*middle*/, SurfacePoint& /*out*/) const { return false; }

    // The material of every point of the surface, or -1 where the method does not say (then
    // at() tells it). Knowing it first lets an untextured material skip the texture footprint,
    // and unlit, all but the span's middle.
    virtual int materialIndex() const { return -1; }

protected:
    ~MovingSurfacePoint() = default;
};

// How a span integrates its texture along the uv path the point sweeps.
enum class SpanTextureFilter {
    // Taps along the path, each its own lookup of the footprint at its own time: the footprint's
    // taps times the path's (Hong & Oh's k taps, made anisotropic).
    Taps,
    // One lookup per straight piece of the path, of the footprint swept along the piece: the
    // ellipse whose covariance is the footprint's plus the piece's (J J^T + d d^T; Loviscach
    // 2005's motion-blurred texture lookup), its taps along the major axis as any anisotropic
    // lookup's. A box along the path convolved with the footprint becomes a box of equal variance:
    // the same mean and spread, a softer shape; the cost is one lookup where Taps takes as many as
    // the path is texels long. Masked materials (AlphaMode::Mask) keep the taps: their cutoff
    // applies to each point's alpha, which one lookup would average first.
    Swept,
};
constexpr int kMaxSweptPieces = 8;  ///< straight pieces a Swept span's path is cut into at most

// How finely a span is sampled.
struct SpanShadingSettings {
    int maxTextureTaps = 16;       ///< Hong & Oh's k: at most k texture taps along the span
    float tapsPerTexel = 2.0f;     ///< taps per texel of the footprint's mip level along the uv path
    float maxTurnPerTap = 0.4f;    ///< radians the reflected ray may turn between lighting taps
    int maxLightingTaps = 16;
    SpanTextureFilter textureFilter = SpanTextureFilter::Swept;
    ShutterWindow window;          ///< the sample's row of the shutter: taps are even in its exposure
};

// The exact methods' span-shading options: `texture-samples` (32, Hong & Oh's k),
// `taps-per-texel` (2) and `texture-filter=swept|taps` (SpanTextureFilter; swept: against Cycles
// at 1024x768 it reaches each quality at the same --aa in less time, docs/BENCHMARKS.md).
SpanShadingSettings spanShadingSettings(OptionMap& options, const std::string& method);
// Records them: texture_samples, taps_per_texel and the texture_filter (info) in --stats.
void recordSpanShadingSettings(RenderStats& stats, const SpanShadingSettings& settings);

// The mean shaded colour (and opacity) of a point over [t0, t1] of the shutter: the colour of
// an interval in motion-path and analytic. Texture and lighting are averaged with their own
// taps, each at its own exact time, since they vary at different rates:
//
// - Texture (Hong & Oh 2017, section 4.4, made anisotropic): tapsPerTexel taps per texel of the
//   pixel footprint's mip level along the uv path, at most maxTextureTaps; past that the level
//   rises to (path length / k) as in the paper. Each tap's level follows the footprint over the
//   span (a quadratic through its ends and middle), so a face turning edge-on blurs as it does
//   under the reference.
//   With SpanTextureFilter::Swept the path is cut where it bends (its middle off the chord by more
//   than a quarter of the footprint's tap width; at most kMaxSweptPieces pieces) and each piece
//   takes one lookup of the footprint at its middle time, swept along it.
// - Lighting (Phong): Simpson's rule on the span's ends and middle, or more taps where the
//   reflected ray turns by more than maxTurnPerTap per tap; each texture tap's albedo is lit by
//   the lighting terms interpolated to its time.
//
// Under a shutter curve or a rolling window the mean is weighted by the row's exposure: taps
// sit at even steps of exposure (ShutterWindow::timeBetween), not of time.
//
// Returns black with alpha 0 when the point cannot be evaluated at the span's ends or middle.
ShadedColor shadeTimeSpan(const Scene& scene, ShadingMode mode, float t0, float t1, const MovingSurfacePoint& point,
                          const SpanShadingSettings& settings = {});

}  // namespace streak::exposure
