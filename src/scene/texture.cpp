#include "scene/texture.h"

#include "scene/barycentric.h"

#include "image/color.h"
#include "util/error.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace streak {

namespace {

int wrapCoordinate(int i, int size, WrapMode mode) {
    switch (mode) {
    case WrapMode::ClampToEdge:
        return std::clamp(i, 0, size - 1);
    case WrapMode::MirroredRepeat: {
        const int period = 2 * size;
        // (A power of two, as most textures are, wraps by a mask: the same index as the
        // remainder, without a division in a lookup's hot loop.)
        int m = (period & (period - 1)) == 0 ? i & (period - 1) : i % period;
        if (m < 0) m += period;
        return m < size ? m : period - 1 - m;
    }
    case WrapMode::Repeat:
    default: {
        if ((size & (size - 1)) == 0) return i & (size - 1);
        int m = i % size;
        return m < 0 ? m + size : m;
    }
    }
}

}  // namespace

Texture Texture::fromSrgb8(int width, int height, std::span<const std::uint8_t> rgba, WrapMode wrapU,
                           WrapMode wrapV) {
    if (width <= 0 || height <= 0 || rgba.size() != std::size_t(width) * height * 4)
        throw Error("texture data does not match its size " + std::to_string(width) + "x" +
                    std::to_string(height));
    std::vector<glm::vec4> texels(std::size_t(width) * height);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        texels[i] = glm::vec4(srgb8ToLinear(rgba[4 * i]), srgb8ToLinear(rgba[4 * i + 1]),
                              srgb8ToLinear(rgba[4 * i + 2]), float(rgba[4 * i + 3]) / 255.0f);
    }
    return fromLinear(width, height, std::move(texels), wrapU, wrapV);
}

Texture Texture::fromLinear(int width, int height, std::vector<glm::vec4> texels, WrapMode wrapU,
                            WrapMode wrapV) {
    if (width <= 0 || height <= 0 || texels.size() != std::size_t(width) * height)
        throw Error("texture data does not match its size " + std::to_string(width) + "x" +
                    std::to_string(height));
    Texture texture;
    texture.m_wrapU = wrapU;
    texture.m_wrapV = wrapV;
    std::vector<Level> levels;
    levels.push_back({width, height, std::move(texels)});
    buildMipChain(levels);
    texture.m_levels = std::make_shared<const std::vector<Level>>(std::move(levels));
    return texture;
}

void Texture::buildMipChain(std::vector<Level>& levels) {
    // Each level averages the 2x2 (or, for an odd size, up to 3x3-weighted) block under it; a
    // box filter in linear light, so averaging a mip texel equals averaging the texels it covers.
    while (levels.back().width > 1 || levels.back().height > 1) {
        const Level& src = levels.back();
        Level dst;
        dst.width = std::max(1, src.width / 2);
        dst.height = std::max(1, src.height / 2);
        dst.texels.resize(std::size_t(dst.width) * dst.height);
        const float sx = float(src.width) / float(dst.width);
        const float sy = float(src.height) / float(dst.height);
        for (int y = 0; y < dst.height; ++y) {
            for (int x = 0; x < dst.width; ++x) {
                // Area-weighted average of the source texels under [x*sx,(x+1)*sx) x [...].
                const float x0 = float(x) * sx, x1 = x0 + sx;
                const float y0 = float(y) * sy, y1 = y0 + sy;
                glm::vec4 sum(0.0f);
                float weightSum = 0.0f;
                for (int j = int(y0); j < int(std::ceil(y1)); ++j) {
                    const float wy = std::min(y1, float(j + 1)) - std::max(y0, float(j));
                    for (int i = int(x0); i < int(std::ceil(x1)); ++i) {
                        const float wx = std::min(x1, float(i + 1)) - std::max(x0, float(i));
                        sum += src.texels[std::size_t(j) * src.width + i] * (wx * wy);
                        weightSum += wx * wy;
                    }
                }
                dst.texels[std::size_t(y) * dst.width + x] = sum / weightSum;
            }
        }
        levels.push_back(std::move(dst));
    }
}

[[gnu::always_inline]] inline glm::vec4 Texture::bilinearAt(const Level& l, const glm::vec2& uv) const {
    // Far-out coordinates are clamped so the texel index stays an int; wrapping cannot tell
    // them apart at float precision anyway.
    constexpr float kLimit = float(1 << 24);
    const float x = std::clamp(uv.x * float(l.width) - 0.5f, -kLimit, kLimit);
    const float y = std::clamp(uv.y * float(l.height) - 0.5f, -kLimit, kLimit);
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const int x0 = int(fx), y0 = int(fy);
    // Interior texels (the common case) need no wrapping.
    int xa = x0, xb = x0 + 1, ya = y0, yb = y0 + 1;
    if (x0 < 0 || xb >= l.width) xa = wrapCoordinate(x0, l.width, m_wrapU), xb = wrapCoordinate(x0 + 1, l.width, m_wrapU);
    if (y0 < 0 || yb >= l.height) ya = wrapCoordinate(y0, l.height, m_wrapV), yb = wrapCoordinate(y0 + 1, l.height, m_wrapV);
    const glm::vec4* rowA = l.texels.data() + std::size_t(ya) * l.width;
    const glm::vec4* rowB = l.texels.data() + std::size_t(yb) * l.width;
    const glm::vec4 top = rowA[xa] + (rowA[xb] - rowA[xa]) * ax;
    const glm::vec4 bottom = rowB[xa] + (rowB[xb] - rowB[xa]) * ax;
    return top + (bottom - top) * ay;
}

glm::vec4 Texture::sampleBilinear(const glm::vec2& uv, int level) const {
    return bilinearAt((*m_levels)[std::clamp(level, 0, numLevels() - 1)], uv);
}

[[gnu::always_inline]] inline Texture::LevelBlend Texture::levelBlendOf(float lod) const {
    const std::vector<Level>& levels = *m_levels;
    const float maxLod = float(levels.size() - 1);
    lod = std::clamp(std::isfinite(lod) ? lod : maxLod, 0.0f, maxLod);
    const int level = int(lod);
    const float frac = lod - float(level);
    const bool isBlended = !(frac < 1.0f / 512.0f || std::size_t(level) + 1 >= levels.size());
    return {&levels[std::size_t(level)], isBlended ? &levels[std::size_t(level) + 1] : nullptr, frac};
}

[[gnu::always_inline]] inline glm::vec4 Texture::trilinearAt(const glm::vec2& uv, const LevelBlend& blend) const {
    if (!(uv.x == uv.x) || !(uv.y == uv.y)) return glm::vec4(0.0f);  // NaN uv: no texel
    const glm::vec4 a = bilinearAt(*blend.fine, uv);
    return blend.coarse ? glm::mix(a, bilinearAt(*blend.coarse, uv), blend.frac) : a;
}

[[gnu::always_inline]] inline glm::vec4 Texture::trilinearAt(const glm::vec2& uv, float lod) const { return trilinearAt(uv, levelBlendOf(lod)); }

glm::vec4 Texture::sample(const glm::vec2& uv, float lod) const { return trilinearAt(uv, lod); }

namespace {

// The ellipse of a footprint in texels: the singular values of J = [a b] (the eigenvalues of
// J J^T are their squares) and the major axis, scaled to its length. Swept along d, the
// eigenvalues of J J^T + d d^T.
struct FootprintEllipse {
    float major = 0.0f, minor = 0.0f;
    glm::vec2 majorAxis{0.0f};
};

FootprintEllipse footprintEllipse(const glm::vec2& a, const glm::vec2& b, const glm::vec2& d = glm::vec2(0.0f)) {
    const float p = a.x * a.x + b.x * b.x + d.x * d.x, q = a.x * a.y + b.x * b.y + d.x * d.y, r = a.y * a.y + b.y * b.y + d.y * d.y;
    const float mean = 0.5f * (p + r), spread = std::sqrt(0.25f * (p - r) * (p - r) + q * q);
    FootprintEllipse e;
    e.major = std::sqrt(std::max(mean + spread, 0.0f));
    e.minor = std::sqrt(std::max(mean - spread, 0.0f));
    // An eigenvector of J J^T for mean + spread, from the better-conditioned row.
    const glm::vec2 axis = std::abs(p - r) + std::abs(q) == 0.0f ? glm::vec2(1.0f, 0.0f)
                           : p >= r                          ? glm::vec2(mean + spread - r, q)
                                                             : glm::vec2(q, mean + spread - p);
    e.majorAxis = axis * (e.major / glm::length(axis));
    return e;
}

// The width in texels each anisotropic tap filters: the minor axis, unless more than
// kMaxAnisotropy taps would be needed along the major one.
float tapWidth(const FootprintEllipse& e, int maxTaps) { return std::max(e.minor, e.major / float(maxTaps)); }

// Whether a tap lies inside a uv triangle, by its barycentrics (the inverse of the affine map
// from barycentrics to uv). Everything is inside when there is no triangle or it is degenerate
// in uv (no inverse).
class UvTriangleTest {
public:
    explicit UvTriangleTest(const std::array<glm::vec2, 3>* corners) {
        if (!corners) return;
        const glm::dvec2 a((*corners)[0]), e1 = glm::dvec2((*corners)[1]) - a, e2 = glm::dvec2((*corners)[2]) - a;
        const double det = e1.x * e2.y - e1.y * e2.x;
        if (!std::isfinite(det) || det == 0.0) return;
        m_origin = a, m_edges = {e1, e2}, m_rows = {glm::dvec2(e2.y, -e2.x) / det, glm::dvec2(-e1.y, e1.x) / det};
        m_isActive = true;
    }
    bool operator()(const glm::vec2& uv) const {
        if (!m_isActive) return true;
        const glm::dvec3 b = barycentrics(uv);
        constexpr double kEdge = -1e-6;  // a tap on an edge belongs to both triangles
        return b.x >= kEdge && b.y >= kEdge && b.z >= kEdge;
    }
    // uv held to the triangle (clampedBarycentrics).
    glm::vec2 held(const glm::vec2& uv) const {
        if (!m_isActive) return uv;
        const glm::dvec3 b = clampedBarycentrics(barycentrics(uv));
        return glm::vec2(m_origin + b.y * m_edges[0] + b.z * m_edges[1]);
    }

private:
    glm::dvec3 barycentrics(const glm::vec2& uv) const {
        const glm::dvec2 d = glm::dvec2(uv) - m_origin;
        const double b1 = glm::dot(m_rows[0], d), b2 = glm::dot(m_rows[1], d);
        return {1.0 - b1 - b2, b1, b2};
    }

    bool m_isActive = false;
    glm::dvec2 m_origin{0.0};
    std::array<glm::dvec2, 2> m_edges{};
    std::array<glm::dvec2, 2> m_rows{};
};

}  // namespace

glm::vec4 Texture::sample(const glm::vec2& uv, const TextureFootprint& footprint) const {
    if (footprint.isBox) return sampleBox(uv, footprint);
    return sample(uv, lookupOf(footprint));
}

Texture::Lookup Texture::lookupOf(const TextureFootprint& footprint) const {
    const glm::vec2 size{float(width()), float(height())};
    const FootprintEllipse e = footprintEllipse(footprint.duvdx * size, footprint.duvdy * size, footprint.sweep * size);
    // (A footprint that is not finite takes the coarsest level, as sample(uv, lod) clamps it.)
    if (!std::isfinite(e.major)) return {float(numLevels() - 1), 1, glm::vec2(0.0f)};
    const bool isSwept = footprint.sweep != glm::vec2(0.0f);
    const int maxTaps = isSwept ? std::max(footprint.maxSweptTaps, 1) : kMaxAnisotropy;
    const float width = std::max(tapWidth(e, maxTaps), std::exp2(std::max(footprint.minLod, 0.0f)));
    // The sweep's share of the major axis takes tapsPerWidth taps per width, the rest one.
    const float extraTaps = (std::max(footprint.tapsPerWidth, 1.0f) - 1.0f) * glm::length(footprint.sweep * size);
    const int taps = std::clamp(int(std::ceil((e.major + extraTaps) / width - 1e-3f)), 1, maxTaps);
    const float lod = width > 0.0f ? std::log2(width) : 0.0f;
    return {lod, taps, taps == 1 ? glm::vec2(0.0f) : e.majorAxis / size / float(taps)};  // step: uv between taps
}

glm::vec4 Texture::sample(const glm::vec2& uv, const Lookup& lookup) const {
    if (lookup.taps == 1) return trilinearAt(uv, lookup.lod);
    // The taps share a level and blend, found once.
    const LevelBlend blend = levelBlendOf(lookup.lod);
    glm::vec4 sum(0.0f);
    for (int i = 0; i < lookup.taps; ++i) sum += trilinearAt(uv + lookup.step * (float(i) + 0.5f - 0.5f * float(lookup.taps)), blend);
    return sum / float(lookup.taps);
}

Texture::BoxGrid Texture::boxGrid(float lengthX, float lengthY, float pathTexels, float tapsPerTexel, int maxPathTaps,
                                  glm::ivec2 fewestTaps, int budget) const {
    // A quarter of the budget at one time: kMaxBoxTaps of kMaxSweptBoxTaps.
    budget = std::clamp(budget, 4, kMaxSweptBoxTaps);
    const int mostAtOnce = budget / 4;
    const int maxLevel = numLevels() - 1;
    if (!std::isfinite(lengthX) || !std::isfinite(lengthY) || !std::isfinite(pathTexels)) return {maxLevel, 1, 1, 1};
    // (At most mostAtOnce + 1 an axis, which is as good as any more for the test below: an edge-on
    // triangle's footprint can be a million texels long, whose taps overflow an int.)
    auto tapsAlong = [&](float length, float spacing) {
        return std::max(1, int(std::min(std::ceil(length / spacing - 1e-3f), float(mostAtOnce + 1))));
    };
    maxPathTaps = std::max(maxPathTaps, 1);
    BoxGrid grid;
    auto at = [&](int level) {
        const float spacing = std::exp2(float(level));
        grid.level = level;
        grid.tapsX = tapsAlong(lengthX, spacing), grid.tapsY = tapsAlong(lengthY, spacing);
        grid.tapsAlong = std::clamp(int(std::ceil(std::min(tapsPerTexel * pathTexels / spacing, float(maxPathTaps)))), 1, maxPathTaps);
    };
    // The box's own level: the finest (spacing 2^level texels) at which both axes take at most
    // mostAtOnce taps in all, each axis as many taps as it is spacings long, at least one.
    for (at(0); grid.tapsX * grid.tapsY > mostAtOnce && grid.level < maxLevel;) at(grid.level + 1);
    grid.tapsX = std::min(grid.tapsX, mostAtOnce), grid.tapsY = std::min(grid.tapsY, mostAtOnce / grid.tapsX);
    // On level 0 the fewest taps a side, within mostAtOnce: there a box narrower than the taps'
    // count of texels takes more taps of the bilinear surface than texels. On a coarser level the
    // box's longer axis set the level, and more taps across the shorter one on its wide texels
    // would only widen the filter (never a coarser level for them either).
    if (grid.level == 0) {
        grid.tapsX = std::max(grid.tapsX, std::min(fewestTaps.x, mostAtOnce / grid.tapsY));
        grid.tapsY = std::max(grid.tapsY, std::min(fewestTaps.y, mostAtOnce / grid.tapsX));
    }
    // Fewer times past the budget, but at least two a width of the box's narrower side.
    const int covering = int(std::ceil(std::min(2.0f * pathTexels / std::max(std::min(lengthX, lengthY), 1e-6f), float(maxPathTaps))));
    grid.tapsAlong = std::min(grid.tapsAlong, std::max({1, covering, budget / (grid.tapsX * grid.tapsY)}));
    return grid;
}

glm::vec4 Texture::sampleBox(const glm::vec2& uv, const TextureFootprint& footprint, float* inside) const {
    const glm::vec2 size{float(width()), float(height())};
    return sampleBox(uv, footprint, boxGrid(glm::length(footprint.duvdx * size), glm::length(footprint.duvdy * size)), inside);
}

glm::vec4 Texture::sampleBox(const glm::vec2& uv, const TextureFootprint& footprint, const BoxGrid& grid, float* inside) const {
    if (inside) *inside = 1.0f;
    if (!(uv.x == uv.x) || !(uv.y == uv.y)) return glm::vec4(0.0f);  // NaN uv: no texel
    const glm::vec2 size{float(width()), float(height())};
    if (!std::isfinite(glm::length(footprint.duvdx * size)) || !std::isfinite(glm::length(footprint.duvdy * size)))
        return trilinearAt(uv, float(numLevels() - 1));
    // minLod is not a box's floor: it widens a lookup for the spacing of the taps along a uv path,
    // and in every direction, which blurs a box across the motion too (AnimatedCube against
    // Cycles: 47.6 dB with it, 52.3 dB without).
    const int tapsX = grid.tapsX, tapsY = grid.tapsY;
    const Level& l = (*m_levels)[std::size_t(grid.level)];
    const UvTriangleTest isInside(footprint.clipTo);
    if (tapsX * tapsY == 1) {
        // One tap: the centre, held to the triangle when it falls outside (as the caller's uv
        // is not held for a box), and its coverage all or nothing like any other tap.
        const bool isCentreInside = isInside(uv);
        if (inside) *inside = isCentreInside ? 1.0f : 0.0f;
        return bilinearAt(l, isCentreInside ? uv : isInside.held(uv));
    }
    const glm::vec2 stepX = footprint.duvdx / float(tapsX), stepY = footprint.duvdy / float(tapsY);
    const glm::vec2 origin = uv - 0.5f * (footprint.duvdx + footprint.duvdy) + 0.5f * (stepX + stepY);
    glm::vec4 sum(0.0f);
    int used = 0;
    for (int j = 0; j < tapsY; ++j)
        for (int i = 0; i < tapsX; ++i) {
            const glm::vec2 tap = origin + stepX * float(i) + stepY * float(j);
            if (!isInside(tap)) continue;
            sum += bilinearAt(l, tap);
            ++used;
        }
    if (inside) *inside = float(used) / float(tapsX * tapsY);
    // No tap inside (a triangle smaller than their spacing): the centre, which the caller holds to it.
    return used > 0 ? sum / float(used) : bilinearAt(l, isInside.held(uv));
}

float Texture::finestLodOfFootprint(const glm::vec2& duvdx, const glm::vec2& duvdy) const {
    const glm::vec2 size{float(width()), float(height())};
    const FootprintEllipse e = footprintEllipse(duvdx * size, duvdy * size);
    const float width = tapWidth(e, kMaxAnisotropy);
    return width > 0.0f ? std::log2(width) : 0.0f;
}

float Texture::lodFromFootprint(const glm::vec2& duvdx, const glm::vec2& duvdy) const {
    const glm::vec2 size{float(width()), float(height())};
    const float lengthSquared = std::max(glm::dot(duvdx * size, duvdx * size), glm::dot(duvdy * size, duvdy * size));
    if (!(lengthSquared > 0.0f)) return 0.0f;
    return 0.5f * std::log2(lengthSquared);
}

}  // namespace streak
