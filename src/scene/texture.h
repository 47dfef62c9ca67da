#pragma once

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace streak {

// A GPU's anisotropic limit: taps a lookup spends along its footprint's major axis at most.
inline constexpr int kDefaultMaxAnisotropy = 16;

// How uv outside [0,1] maps onto a texture axis (the glTF sampler modes).
enum class WrapMode : std::uint8_t { Repeat, ClampToEdge, MirroredRepeat };

// The area of a texture one lookup integrates: the uv change over one sample spacing right and
// down, and a level of detail not to go below (span shading's tap spacing along a uv path).
// Level 0 is the floor whatever minLod says: a tap narrower than a texel filters nothing more,
// and a span of a still point must shade as its instant does. The default, no area, is a
// bilinear tap of level 0.
//
// isBox asks for a different filter over the same two vectors: the mean of the texture over the
// parallelogram uv + u duvdx + v duvdy, u and v in [-1/2, 1/2]. That is the footprint of a whole
// region of the screen (a pixel's samples sharing one shading), whose texels all count alike, where
// the GPU's ellipse of one sample spacing is a smooth bell twice as wide: on a pixel-wide
// footprint, a trilinear tap at the level of its width reaches texels a box never sees (the
// neighbours in a texture atlas).
//
// A box may also be clipped to a uv triangle (clipTo, the corners of the triangle its samples
// see): only the part of the parallelogram inside it counts. Where a pixel straddles a triangle
// edge that is also a seam of the atlas, the box beyond the edge lies in another chart of the
// atlas, texels no sample of this triangle sees.
struct TextureFootprint {
    glm::vec2 duvdx{0.0f};
    glm::vec2 duvdy{0.0f};
    float minLod = 0.0f;
    bool isBox = false;
    const std::array<glm::vec2, 3>* clipTo = nullptr;
    // The footprint swept along a straight uv segment (span shading's motion): the lookup's
    // ellipse is the one of covariance J J^T + sweep sweep^T, J = [duvdx duvdy], the box of the
    // segment convolved with the footprint's taken as one of equal variance (Loviscach 2005's
    // motion-blurred lookup). Not for a box. Without a sweep the lookup is a GPU's, whatever the
    // two fields after this one say.
    glm::vec2 sweep{0.0f};
    // The most taps a swept lookup spends along its major axis, past which its taps widen: a
    // footprint swept along a uv path is as long as the path (an unswept one takes a GPU's
    // Texture::kMaxAnisotropy).
    int maxSweptTaps = kDefaultMaxAnisotropy;
    // Taps per tap width along the sweep: the taps must resolve the sweep's box (span shading's
    // taps per texel), where the footprint's own extent takes a GPU's one per width.
    float tapsPerWidth = 1.0f;
};

// Texture is a linear-light RGBA texture with its full mip chain, built once at load time.
// uv (0,0) is the top-left corner of the first row (glTF convention); texel centres sit at
// half-integer texel coordinates. Sampling is bilinear within a level and linear between levels.
class Texture {
public:
    // From 8-bit sRGB-encoded RGBA (row-major, top row first): colour is decoded to linear,
    // alpha is kept linear. Throws Error if the sizes do not match.
    static Texture fromSrgb8(int width, int height, std::span<const std::uint8_t> rgba,
                             WrapMode wrapU = WrapMode::Repeat, WrapMode wrapV = WrapMode::Repeat);
    static Texture fromLinear(int width, int height, std::vector<glm::vec4> texels,
                              WrapMode wrapU = WrapMode::Repeat, WrapMode wrapV = WrapMode::Repeat);

    int width(int level = 0) const { return (*m_levels)[level].width; }
    int height(int level = 0) const { return (*m_levels)[level].height; }
    int numLevels() const { return int(m_levels->size()); }
    WrapMode wrapU() const { return m_wrapU; }
    WrapMode wrapV() const { return m_wrapV; }
    const glm::vec4& texel(int level, int x, int y) const {
        const Level& l = (*m_levels)[level];
        return l.texels[std::size_t(y) * l.width + x];
    }

    glm::vec4 sampleBilinear(const glm::vec2& uv, int level) const;
    // Trilinear: lod 0 is the full-resolution level; clamped to the chain.
    glm::vec4 sample(const glm::vec2& uv, float lod) const;
    // Anisotropic: the footprint's ellipse (the singular vectors of [duvdx duvdy] in texels)
    // covered by up to kMaxAnisotropy (footprint.maxSweptTaps when swept) trilinear taps along its major axis, each at the level of
    // the minor axis, so a surface seen at a slant stays sharp across its compressed direction.
    static constexpr int kMaxAnisotropy = kDefaultMaxAnisotropy;
    glm::vec4 sample(const glm::vec2& uv, const TextureFootprint& footprint) const;
    // That lookup's plan, which depends on the footprint alone: its level and its taps along the
    // major axis (a step apart in uv). Samples that share a footprint (a still triangle's
    // samples in one pixel) plan once; sample(uv, lookupOf(f)) is sample(uv, f). Not for a box.
    struct Lookup {
        float lod = 0.0f;
        int taps = 1;
        glm::vec2 step{0.0f};
    };
    Lookup lookupOf(const TextureFootprint& footprint) const;
    glm::vec4 sample(const glm::vec2& uv, const Lookup& lookup) const;
    // The box filter (TextureFootprint::isBox): a grid of bilinear taps over the parallelogram,
    // at most kMaxBoxTaps, at the finest level whose texels are no narrower than the taps' spacing,
    // so each tap's texel covers the ground between taps and nothing is aliased (minLod, a
    // lookup's floor, does not apply). Its mean is the box's; its edges are soft by about one tap spacing. 64 taps
    // (8 x 8 on a square box) keep the mean within 0.02 of the exact box on a high-contrast atlas
    // where 16 are 0.06 off (texture_test); one shading per pixel affords them.
    static constexpr int kMaxBoxTaps = 64;
    // With inside set, it receives the fraction of the taps within footprint.clipTo (1 without
    // one): how much of the box the triangle covers, for a caller that weights boxes by it.
    glm::vec4 sampleBox(const glm::vec2& uv, const TextureFootprint& footprint, float* inside = nullptr) const;

    // A box swept along a uv path (a shared shading's pixel box over its span of time) is the
    // box at each of tapsAlong times along the path, on the box's own level (sampleBox's), the
    // path's taps tapsPerTexel a spacing of that level. Where the box's taps times the path's
    // would pass kMaxSweptBoxTaps, the path takes fewer, down to two a box width (the boxes at
    // consecutive times then overlap by half, and together cover the swept region): a box as
    // wide as many texels no longer takes 64 taps at each of 32 times. Fewer times than that
    // alias: 256 taps in all lost 0.7 dB against Cycles on builtin:cubes; raising the level
    // instead blurs across the motion (AnimatedCube at one shading a pixel: 2 dB). docs/BENCHMARKS.md.
    static constexpr int kMaxSweptBoxTaps = 256;
    static_assert(kMaxBoxTaps * 4 == kMaxSweptBoxTaps, "a box takes a quarter of its budget at one time");
    struct BoxGrid {
        int level = 0, tapsX = 1, tapsY = 1, tapsAlong = 1;
    };
    // The grid of a box lengthX x lengthY texels (level 0) swept along a path pathTexels long,
    // its times in [1, maxPathTaps]; without a path (pathTexels 0) the box's own. `budget` is the
    // most taps in all (kMaxSweptBoxTaps, or less where few samples share the box), a quarter of
    // it at one time (kMaxBoxTaps of kMaxSweptBoxTaps). On level 0 each
    // axis then takes at least fewestTaps of it, within that quarter: a box shared
    // by that many samples a side samples the bilinear surface no coarser than they did. Lengths
    // that are not finite take the coarsest level's texel.
    BoxGrid boxGrid(float lengthX, float lengthY, float pathTexels = 0.0f, float tapsPerTexel = 1.0f, int maxPathTaps = 1,
                    glm::ivec2 fewestTaps = glm::ivec2(1), int budget = kMaxSweptBoxTaps) const;
    // One time's box on `grid` (sampleBox is this on its own box's grid).
    glm::vec4 sampleBox(const glm::vec2& uv, const TextureFootprint& footprint, const BoxGrid& grid, float* inside = nullptr) const;
    // The level of the anisotropic taps for a footprint (minLod 0): the finest detail a lookup
    // keeps, so what taps along a uv path must be spaced by not to alias.
    float finestLodOfFootprint(const glm::vec2& duvdx, const glm::vec2& duvdy) const;
    // The level of detail for a uv footprint (the uv change over one pixel step in x and y):
    // log2 of the longer footprint axis in texels, as GPUs compute it.
    float lodFromFootprint(const glm::vec2& duvdx, const glm::vec2& duvdy) const;

private:
    struct Level {
        int width = 0;
        int height = 0;
        std::vector<glm::vec4> texels;
    };
    static void buildMipChain(std::vector<Level>& levels);
    // The bilinear tap and the trilinear one, inlined into the lookups (the hot loop of span
    // shading): the public sample functions are these with their checks.
    glm::vec4 bilinearAt(const Level& level, const glm::vec2& uv) const;
    glm::vec4 trilinearAt(const glm::vec2& uv, float lod) const;
    // A trilinear tap's levels at `lod` (clamped to the chain; not finite: the coarsest): the
    // finer one, the next where the blend towards it is worth a second tap (else null), and that
    // blend. A lookup's taps share one.
    struct LevelBlend {
        const Level* fine = nullptr;
        const Level* coarse = nullptr;
        float frac = 0.0f;
    };
    LevelBlend levelBlendOf(float lod) const;
    glm::vec4 trilinearAt(const glm::vec2& uv, const LevelBlend& blend) const;

    // Level 0 is full resolution, the last is 1x1. Immutable once built, so copies of a scene
    // (blur-shell's shell scene) share the texels.
    std::shared_ptr<const std::vector<Level>> m_levels;
    WrapMode m_wrapU = WrapMode::Repeat;
    WrapMode m_wrapV = WrapMode::Repeat;
};

}  // namespace streak
