#include "exposure/span_shading.h"

#include "util/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

namespace streak::exposure {

namespace {

// The angle between two directions, as the chord between their unit vectors (2 sin(angle / 2)):
// within 5% of the angle up to 1 radian, and never more than it.
float turnBetween(glm::vec3 a, glm::vec3 b) {
    const float la = glm::length(a), lb = glm::length(b);
    if (!(la > 0.0f) || !(lb > 0.0f)) return 0.0f;
    return glm::length(a / la - b / lb);
}

// A bound on turnBetween(a, b) for a quarter of its cost: |a/|a| - b/|b|| <= 2 |a - b| / max(|a|, |b|).
float turnBound(glm::vec3 a, glm::vec3 b) {
    const float longest = std::max(glm::dot(a, a), glm::dot(b, b));
    return longest > 0.0f ? 2.0f * std::sqrt(glm::dot(a - b, a - b) / longest) : 0.0f;
}

// The quadratic through (0, a), (1/2, m), (1, b), as coefficients: value(f) = c0 + f (c1 + f c2).
template <class T>
struct QuadraticThrough {
    QuadraticThrough() = default;
    QuadraticThrough(const T& a, const T& m, const T& b) : c0(a), c1(-3.0f * a + 4.0f * m - b), c2(2.0f * a - 4.0f * m + 2.0f * b) {}
    // The constant a, exactly (the three-point form rounds).
    static QuadraticThrough constant(const T& a) {
        QuadraticThrough q;
        q.c0 = a;
        return q;
    }
    T operator()(float f) const { return c0 + f * (c1 + f * c2); }
    T c0{}, c1{}, c2{};
};

// Lighting over a span: Simpson's three points (ends and middle), or n midpoint taps.
class SpanLighting {
public:
    SpanLighting(const Scene& scene, const Material& material, const ShutterWindow& window, float t0, float t1,
                 const std::array<float, 3>& times, const std::array<SurfacePoint, 3>& ends, int numTaps, const MovingSurfacePoint& point,
                 bool isStill) {
        auto light = [&](const SurfacePoint& p, float t) {
            return phongTerms(scene, material, p.position, p.normal, p.isFrontFacing, scene.camera.positionAt(t));
        };
        if (isStill) {  // one instant's terms all span long
            m_mean = light(ends[1], times[1]);
            m_diffuse = QuadraticThrough<glm::vec3>::constant(m_mean.diffuse);
            m_specular = QuadraticThrough<glm::vec3>::constant(m_mean.specular);
            return;
        }
        if (numTaps <= 3) {
            const std::array<PhongTerms, 3> s{light(ends[0], times[0]), light(ends[1], times[1]), light(ends[2], times[2])};
            m_diffuse = {s[0].diffuse, s[1].diffuse, s[2].diffuse};
            m_specular = {s[0].specular, s[1].specular, s[2].specular};
            m_mean.diffuse = (s[0].diffuse + 4.0f * s[1].diffuse + s[2].diffuse) / 6.0f;
            m_mean.specular = (s[0].specular + 4.0f * s[1].specular + s[2].specular) / 6.0f;
            return;
        }
        m_taps.reserve(std::size_t(numTaps));
        for (int i = 0; i < numTaps; ++i) {
            const float t = window.timeBetween(t0, t1, (float(i) + 0.5f) / float(numTaps));
            SurfacePoint p;
            if (point.at(t, false, p)) m_taps.push_back(light(p, t));
            else if (!m_taps.empty()) m_taps.push_back(m_taps.back());
        }
        if (m_taps.empty()) m_taps.push_back(light(ends[1], times[1]));
        for (const PhongTerms& tap : m_taps) m_mean.diffuse += tap.diffuse, m_mean.specular += tap.specular;
        m_mean.diffuse /= float(m_taps.size()), m_mean.specular /= float(m_taps.size());
    }

    const PhongTerms& mean() const { return m_mean; }

    // The terms at fraction f of the span: the Simpson quadratic, or linear between taps.
    PhongTerms at(float f) const {
        if (m_taps.empty()) return {m_diffuse(f), m_specular(f)};
        const float x = std::clamp(f * float(m_taps.size()) - 0.5f, 0.0f, float(m_taps.size() - 1));
        const std::size_t i = std::min(std::size_t(x), m_taps.size() - 1), j = std::min(i + 1, m_taps.size() - 1);
        const float w = x - float(i);
        return {glm::mix(m_taps[i].diffuse, m_taps[j].diffuse, w), glm::mix(m_taps[i].specular, m_taps[j].specular, w)};
    }

private:
    QuadraticThrough<glm::vec3> m_diffuse{}, m_specular{};  ///< Simpson's case (no taps)
    std::vector<PhongTerms> m_taps;
    PhongTerms m_mean;
};

}  // namespace

SpanShadingSettings spanShadingSettings(OptionMap& options, const std::string& method) {
    SpanShadingSettings s;
    s.maxTextureTaps = options.getInt("texture-samples", 32, 1, 1024);
    s.tapsPerTexel = float(options.getInt("taps-per-texel", 2, 1, 16));
    const std::string filter = options.getString("texture-filter", "swept");
    if (filter == "taps") s.textureFilter = SpanTextureFilter::Taps;
    else if (filter == "swept") s.textureFilter = SpanTextureFilter::Swept;
    else throw Error("method '" + method + "': texture-filter must be taps or swept, got '" + filter + "'");
    return s;
}

void recordSpanShadingSettings(RenderStats& stats, const SpanShadingSettings& settings) {
    stats.setCounter("texture_samples", settings.maxTextureTaps);
    stats.setCounter("taps_per_texel", settings.tapsPerTexel);
    stats.setInfo("texture_filter", settings.textureFilter == SpanTextureFilter::Swept ? "swept" : "taps");
}

namespace {

// A still textured point shared by several samples (ShadingSite::samples): the mean of its
// shadings at each sample's own point with the middle's footprint, weighted by their exposures.
// Nothing moves, so each is what that sample shades alone but for the footprint, whose lookup
// is planned once.
ShadedColor shadeStillSamples(const Scene& scene, ShadingMode mode, const SurfacePoint& middle, std::span<const SiteSample> samples,
                              const MovingSurfacePoint& point, const glm::vec3& eye) {
    const int texture = scene.materials[middle.material].baseColorTexture;
    const Texture::Lookup lookup = texture >= 0 ? scene.textures[std::size_t(texture)].lookupOf({middle.duvdx, middle.duvdy}) : Texture::Lookup{};
    ShadedColor sum{glm::vec3(0.0f), 0.0f};
    float weight = 0.0f;
    for (const SiteSample& sample : samples) {
        SurfacePoint p;
        if (!point.atSample(sample.ndc, middle, p)) continue;
        const ShadedColor c = shadeSurfaceWithAlbedo(scene, mode, p, materialAlbedoWith(scene, p.material, p.uv, lookup, p.vertexColor), eye);
        sum.color += sample.weight * c.color, sum.alpha += sample.weight * c.alpha, weight += sample.weight;
    }
    if (!(weight > 0.0f)) return shadeSurface(scene, mode, middle, eye);
    return {sum.color / weight, sum.alpha / weight};
}

}  // namespace

ShadedColor shadeTimeSpan(const Scene& scene, ShadingMode mode, float t0, float t1, const MovingSurfacePoint& point,
                          const SpanShadingSettings& settings) {
    const ShutterWindow& window = settings.window;
    const std::array<float, 3> times = window.isIdentity() ? std::array<float, 3>{t0, 0.5f * (t0 + t1), t1}
                                                           : std::array<float, 3>{window.timeBetween(t0, t1, 0.0f), window.timeBetween(t0, t1, 0.5f),
                                                                                  window.timeBetween(t0, t1, 1.0f)};
    // An untextured material's colour is its base colour times the vertex colour, which changes
    // slowly across a triangle: unlit, the middle's serves the whole span (as below), and lit or
    // as a pass, no texture footprint is needed. Where the method does not say the material
    // (-1), every point takes its footprint.
    const int knownMaterial = point.materialIndex();
    const bool isUntextured = knownMaterial >= 0 && scene.materials[std::size_t(knownMaterial)].baseColorTexture < 0;
    if (isUntextured && mode == ShadingMode::Unlit) {
        glm::vec4 vertexColor;
        if (!point.vertexColorAt(times[1], vertexColor)) return {glm::vec3(0.0f), 0.0f};
        return materialAlbedo(scene, std::uint32_t(knownMaterial), glm::vec2(0.0f), {}, vertexColor);
    }
    const bool isDataPass = mode == ShadingMode::Normal || isVectorPass(mode);
    const bool withFootprint = !isUntextured && !isDataPass;
    // A still point is the same at every time: its middle serves as both ends.
    const bool isStill = point.isStill(t0, t1);
    if (isStill && !isDataPass && !point.hasBoxFootprint()) {
        // Nothing the point is shaded from moves: the span is one instant, shaded as a
        // rasterizer shades a sample (the unswept lookup below is a GPU's either way), at a
        // rasterizer's cost. A box counts the triangle's texels and keeps its own filter; a data
        // pass takes its alpha from the unlit shading below, with its footprint. (Before the
        // three ends below are made: a still frame shades every sample here.)
        SurfacePoint middle;
        if (!point.at(times[1], withFootprint, middle)) return {glm::vec3(0.0f), 0.0f};
        const std::span<const SiteSample> samples = point.sharedSamples();
        if (samples.empty() || !withFootprint) return shadeSurface(scene, mode, middle, scene.camera.positionAt(times[1]));
        return shadeStillSamples(scene, mode, middle, samples, point, scene.camera.positionAt(times[1]));
    }
    std::array<SurfacePoint, 3> ends;
    if (isStill) {
        if (!point.at(times[1], withFootprint, ends[1])) return {glm::vec3(0.0f), 0.0f};
        ends[0] = ends[2] = ends[1];
    } else {
        for (int i = 0; i < 3; ++i)
            if (!point.at(times[i], withFootprint, ends[i])) return {glm::vec3(0.0f), 0.0f};
    }
    if (mode == ShadingMode::Normal || isVectorPass(mode)) {
        // The normal and vector passes: the span's mean (Simpson's weights over its ends and
        // middle), with the alpha unlit shading gives the span, so translucent coverage is the
        // beauty's.
        ShadedColor result = shadeTimeSpan(scene, ShadingMode::Unlit, t0, t1, point, settings);
        auto value = [&](const SurfacePoint& p) { return mode == ShadingMode::Normal ? shadingNormal(p) : vectorOf(mode, p); };
        result.color = (value(ends[0]) + 4.0f * value(ends[1]) + value(ends[2])) / 6.0f;
        return result;
    }
    const std::uint32_t materialIndex = ends[1].material;
    const Material& material = scene.materials[materialIndex];
    const bool isLit = mode == ShadingMode::Phong;

    int lightingTaps = 0;
    if (isLit && !isStill) {
        // Each half of the span turns by these angles; the reflected ray turns by twice the
        // normal's turn, plus the view direction's. Up to 3 taps are all Simpson's three points
        // (SpanLighting): where the turns' bounds keep the count there (a short span, as a dense
        // mesh's slivers are), the turns themselves are not needed. (A margin below 3 covers the
        // rounding of both.)
        const std::array<glm::vec3, 3> toEye{scene.camera.positionAt(times[0]) - ends[0].position,
                                             scene.camera.positionAt(times[1]) - ends[1].position,
                                             scene.camera.positionAt(times[2]) - ends[2].position};
        auto taps = [&](auto&& turn) {
            const float normalTurn = std::max(turn(ends[0].normal, ends[1].normal), turn(ends[1].normal, ends[2].normal));
            const float viewTurn = std::max(turn(toEye[0], toEye[1]), turn(toEye[1], toEye[2]));
            return 2.0f * (2.0f * normalTurn + viewTurn) / settings.maxTurnPerTap;
        };
        lightingTaps = taps(turnBound) <= 2.99f ? 1 : std::clamp(int(std::ceil(taps(turnBetween))), 1, settings.maxLightingTaps);
    }
    std::optional<SpanLighting> lighting;
    if (isLit) lighting.emplace(scene, material, window, t0, t1, times, ends, lightingTaps, point, isStill);

    // Vertex colours change slowly across a triangle: the one at mid-span serves the whole span.
    const glm::vec4 vertexColor = ends[1].vertexColor;
    if (material.baseColorTexture < 0) {
        const ShadedColor albedo = materialAlbedo(scene, materialIndex, ends[1].uv, {}, vertexColor);
        if (!isLit) return albedo;
        return {albedo.color * lighting->mean().diffuse + lighting->mean().specular, albedo.alpha};
    }

    const Texture& texture = scene.textures[std::size_t(material.baseColorTexture)];
    const glm::vec2 size(float(texture.width()), float(texture.height()));
    std::array<float, 3> footprintLod{};
    footprintLod[0] = texture.finestLodOfFootprint(ends[0].duvdx, ends[0].duvdy);
    for (int i = 1; i < 3; ++i) footprintLod[i] = isStill ? footprintLod[0] : texture.finestLodOfFootprint(ends[i].duvdx, ends[i].duvdy);
    const float spacing = std::exp2(std::max(0.0f, *std::min_element(footprintLod.begin(), footprintLod.end())));
    // The footprint moves along the span with the surface: quadratic through its three ends.
    const QuadraticThrough<glm::vec2> duvdxAt(ends[0].duvdx, ends[1].duvdx, ends[2].duvdx);
    const QuadraticThrough<glm::vec2> duvdyAt(ends[0].duvdy, ends[1].duvdy, ends[2].duvdy);

    // Texel sums; the base colour and the vertex colour multiply them once at the end.
    glm::vec3 sum(0.0f), specularSum(0.0f);
    float alphaSum = 0.0f, weightSum = 0.0f;
    auto accumulate = [&](const glm::vec4& texel, float f, float weight) {
        if (isLit) {
            const PhongTerms terms = lighting->at(f);
            sum += glm::vec3(texel) * terms.diffuse * weight;
            specularSum += terms.specular * weight;
        } else {
            sum += glm::vec3(texel) * weight;
        }
        // Each tap's alpha goes through the alpha mode: Mask taps are 0 or 1, their mean coverage.
        alphaSum += material.alphaOf(texel.w * vertexColor.w) * weight;
        weightSum += weight;
    };
    auto result = [&]() -> ShadedColor {
        if (weightSum == 0.0f) return {glm::vec3(0.0f), 0.0f};
        const float scale = 1.0f / weightSum;
        return {material.baseColor * glm::vec3(vertexColor) * sum * scale + specularSum * scale, alphaSum * scale};
    };

    const bool isBox = point.hasBoxFootprint();
    // A mask's cutoff applies to each texel's alpha, before any mean (a point is in or out): a
    // swept lookup averages alpha over the path first, so masked materials keep the taps.
    if (settings.textureFilter == SpanTextureFilter::Swept && !isBox && material.alphaMode != AlphaMode::Mask) {
        // Straight pieces: a quadratic's middle lies off its chord by (its bend), and by a
        // quarter of that per halving of the pieces.
        const float bend = glm::length((ends[1].uv - 0.5f * (ends[0].uv + ends[2].uv)) * size);
        int pieces = 1;
        while (pieces < kMaxSweptPieces && bend > 0.25f * spacing * float(pieces * pieces)) pieces *= 2;
        glm::vec2 from = ends[0].uv;
        bool hasFrom = true;
        for (int k = 1; k <= pieces; ++k) {
            glm::vec2 to = ends[2].uv;
            bool hasTo = true;
            if (2 * k == pieces) to = ends[1].uv;
            else if (k < pieces) hasTo = point.uvAt(window.timeBetween(t0, t1, float(k) / float(pieces)), to);
            if (hasFrom && hasTo) {
                const float f = (float(k) - 0.5f) / float(pieces);
                TextureFootprint footprint{duvdxAt(f), duvdyAt(f)};
                footprint.sweep = to - from;
                footprint.tapsPerWidth = settings.tapsPerTexel;
                footprint.maxSweptTaps = std::max(Texture::kMaxAnisotropy, settings.maxTextureTaps);
                accumulate(texture.sample(0.5f * (from + to), footprint), f, 1.0f);
            }
            from = to, hasFrom = hasTo;
        }
        return result();
    }

    // A shared shading's box counts only the texels of the triangle its samples see, and each
    // time as much as the triangle covers of the box then: the pixel sees the triangle's colour
    // over time in proportion to its coverage. A time at which no tap is inside still counts a
    // little, so a span never loses all its weight.
    // The uv path's length in texels along its longer axis, through the middle.
    const glm::vec2 a = glm::abs(ends[1].uv - ends[0].uv) * size, b = glm::abs(ends[2].uv - ends[1].uv) * size;
    const float pathTexels = std::max(a.x + b.x, a.y + b.y);
    // A box takes one grid for the whole span (Texture::boxGrid): the box's level and taps at the
    // widest it is at the span's ends and middle, and the times along the path.
    Texture::BoxGrid boxGrid;
    if (isBox) {
        float lengthX = 0.0f, lengthY = 0.0f;
        for (const SurfacePoint& end : ends)
            lengthX = std::max(lengthX, glm::length(end.duvdx * size)), lengthY = std::max(lengthY, glm::length(end.duvdy * size));
        boxGrid = texture.boxGrid(lengthX, lengthY, pathTexels, settings.tapsPerTexel, settings.maxTextureTaps, point.boxTaps(), point.boxBudget());
    }
    const int taps = isBox ? boxGrid.tapsAlong : std::clamp(int(std::ceil(settings.tapsPerTexel * pathTexels / spacing)), 1, settings.maxTextureTaps);
    // The level the path's length asks for (k taps along it; the lookup keeps level 0 as floor).
    const float pathLod = std::log2(std::max(pathTexels / float(settings.maxTextureTaps), 1e-8f));
    const std::array<glm::vec2, 3>* clipTo = isBox ? point.uvTriangle() : nullptr;
    constexpr float kLeastCoverage = 1e-3f;
    for (int i = 0; i < taps; ++i) {
        const float f = (float(i) + 0.5f) / float(taps);
        glm::vec2 uv = ends[1].uv;
        // (The middle tap's uv is the middle end's, unless a box wants it not held.)
        if ((isBox || 2 * i + 1 != taps) && !point.uvAt(window.timeBetween(t0, t1, f), uv)) continue;
        const TextureFootprint footprint{duvdxAt(f), duvdyAt(f), pathLod, isBox, clipTo};
        float weight = 1.0f;
        const glm::vec4 texel = isBox ? texture.sampleBox(uv, footprint, boxGrid, &weight) : texture.sample(uv, footprint);
        accumulate(texel, f, std::max(weight, kLeastCoverage));
    }
    return result();
}

}  // namespace streak::exposure
