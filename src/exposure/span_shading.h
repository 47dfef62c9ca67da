#pragma once

#include "scene/shading.h"
#include "scene/shutter.h"

#include <glm/vec2.hpp>

#include <array>

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

    // The uv corners of the triangle the point is held to, where a box footprint is clipped to
    // them (TextureFootprint::clipTo); null where the point is not held to one triangle.
    virtual const std::array<glm::vec2, 3>* uvTriangle() const { return nullptr; }
    // The point's footprint (SurfacePoint::duvdx, duvdy) is a region of the screen whose texels
    // count alike (TextureFootprint::isBox), not one sample's spacing: true where a pixel's
    // samples share the shading (ShadingSite::boxFootprint).
    virtual bool hasBoxFootprint() const { return false; }

    // True when nothing the point is shaded from changes over [t0, t1] (its position, normal,
    // uv and footprint, and the eye): one instant then shades the whole span. False where the
    // method does not know.
    virtual bool isStill(float /*t0*/, float /*t1*/) const { return false; }

protected:
    ~MovingSurfacePoint() = default;
};

// How finely a span is sampled.
struct SpanShadingSettings {
    int maxTextureTaps = 16;       ///< Hong & Oh's k: at most k texture taps along the span
    float tapsPerTexel = 2.0f;     ///< taps per texel of the footprint's mip level along the uv path
    float maxTurnPerTap = 0.4f;    ///< radians the reflected ray may turn between lighting taps
    int maxLightingTaps = 16;
    ShutterWindow window;          ///< the sample's row of the shutter: taps are even in its exposure
};

// The mean shaded colour (and opacity) of a point over [t0, t1] of the shutter: the colour of
// an interval in motion-path and analytic. Texture and lighting are averaged with their own
// taps, each at its own exact time, since they vary at different rates:
//
// - Texture (Hong & Oh 2017, section 4.4, made anisotropic): tapsPerTexel taps per texel of the
//   pixel footprint's mip level along the uv path, at most maxTextureTaps; past that the level
//   rises to (path length / k) as in the paper. Each tap's level follows the footprint over the
//   span (a quadratic through its ends and middle), so a face turning edge-on blurs as it does
//   under the reference.
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
