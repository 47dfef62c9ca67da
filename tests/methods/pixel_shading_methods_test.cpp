// Shading once per pixel (exposure::PixelShading) in the exact methods, against per-sample
// shading where they must agree exactly and against independent references where they need not.
#include "image/metrics.h"
#include "raster/sample_pattern.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace streak {

namespace {

const char* const kExactMethods[] = {"motion-path", "analytic", "higher-order"};

OptionMap shadingOptions(const std::string& rate, int cells = 0) {
    OptionMap o = test::withOption("shading", rate);
    if (cells > 0) o.set("shading-cells", std::to_string(cells));
    return o;
}

// Constant-colour quads that translate, cross in depth, shrink and overlap: edges sweep every
// way across pixels, so samples of one pixel see a triangle over many different times.
Scene constantColourScene() {
    Scene scene = test::emptyScene(glm::vec3(0.1f, 0.2f, 0.3f));
    const test::PixelCamera c{32, 24, 3.0f};
    const std::uint32_t red = test::addMaterial(scene, {0.9f, 0.1f, 0.1f}), green = test::addMaterial(scene, {0.1f, 0.8f, 0.2f}),
                        blue = test::addMaterial(scene, {0.2f, 0.3f, 0.9f});
    test::addPixelQuad(scene, c, red, 2.3f, 3.1f, 13.7f, 19.4f, 11.2f, 1.7f);
    test::addPixelQuad(scene, c, blue, 20.5f, 2.2f, 20.9f, 21.6f, -14.3f, 0.0f);  // a thin fast sliver
    const test::PixelCamera far{32, 24, 5.0f};
    test::addMovingQuad(scene, green, {far.at(4, 4), far.at(4, 20), far.at(28, 20), far.at(28, 4)},
                        {c.at(10, 8), c.at(10, 16), c.at(22, 16), c.at(22, 8)});
    validateScene(scene);
    return scene;
}

// Scattered texel values (linear), `size` texels a side.
std::vector<glm::vec4> testTexels(int size) {
    std::vector<glm::vec4> texels(std::size_t(size) * std::size_t(size));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float a = float((x * 37 + y * 91) % 17) / 16.0f, b = float((x * 13 + y * 7) % 11) / 10.0f;
            texels[std::size_t(y) * std::size_t(size) + std::size_t(x)] = glm::vec4(a, b, 0.5f * (a + b), 1.0f);
        }
    return texels;
}

// The bilinear lookup Cycles makes (texel centres at (i + 1/2) / size, clamped at the edges),
// written out here so the reference shares no code with streak's textures.
glm::vec3 bilinear(const std::vector<glm::vec4>& texels, int size, glm::vec2 uv) {
    const float x = uv.x * float(size) - 0.5f, y = uv.y * float(size) - 0.5f;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const float fx = x - float(x0), fy = y - float(y0);
    auto at = [&](int i, int j) {
        i = std::clamp(i, 0, size - 1), j = std::clamp(j, 0, size - 1);
        return glm::vec3(texels[std::size_t(j) * std::size_t(size) + std::size_t(i)]);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

// A magnified textured quad (4 pixels a texel) translating 7.3 pixels along x, and the worst
// channel error of an image of it against the texture's bilinear surface integrated over the
// pixel box and the shutter, here by brute-force quadrature of pixel and motion, over the
// pixels it covers all shutter long.
// `size` texels a side: 8 magnifies each texel to 4 pixels; 256 minifies 8 texels into a pixel,
// the motion then 58 texels long.
struct TranslatingQuad {
    static constexpr int w = 40, h = 24;
    static constexpr float x0 = 2.0f, y0 = -4.0f, side = 32.0f, dx = 7.3f;
    int size = 8;
    std::vector<glm::vec4> texels = testTexels(size);
    Scene scene = test::emptyScene();

    explicit TranslatingQuad(int textureSize = 8) : size(textureSize) {
        scene.textures.push_back(Texture::fromLinear(size, size, texels, WrapMode::ClampToEdge, WrapMode::ClampToEdge));
        const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
        scene.materials[m].baseColorTexture = 0;
        const test::PixelCamera c{w, h, 2.0f};
        test::addPixelQuad(scene, c, m, x0, y0, x0 + side, y0 + side, dx, 0.0f);
        scene.meshes.back().uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
        validateScene(scene);
    }

    // The pixels it covers all shutter long, and their integrals, computed once.
    static constexpr int px0 = int(x0 + dx) + 1, px1 = int(x0 + side) - 1;
    std::vector<glm::dvec3> reference;

    double worstError(const Image& image) {
        if (reference.empty())
            for (int py = 1; py < h - 1; ++py)
                for (int px = px0; px < px1; ++px) {
                    glm::dvec3 sum(0.0);
                    const int n = 24, steps = std::max(64, int(4.0f * dx / side * float(size)));  // 4 steps a texel of motion
                    for (int k = 0; k < steps; ++k) {
                        const float shift = dx * (float(k) + 0.5f) / float(steps);
                        for (int j = 0; j < n; ++j)
                            for (int i = 0; i < n; ++i) {
                                const float x = float(px) + (float(i) + 0.5f) / float(n), y = float(py) + (float(j) + 0.5f) / float(n);
                                sum += glm::dvec3(bilinear(texels, size, glm::vec2((x - x0 - shift) / side, (y - y0) / side)));
                            }
                    }
                    reference.push_back(sum / double(n * n * steps));
                }
        double worst = 0.0;
        std::size_t k = 0;
        for (int py = 1; py < h - 1; ++py)
            for (int px = px0; px < px1; ++px) {
                const glm::dvec3 want = reference[k++], got(image.at(px, py));
                worst = std::max({worst, std::abs(got.x - want.x), std::abs(got.y - want.y), std::abs(got.z - want.z)});
            }
        return worst;
    }
};

}  // namespace

TEST(PixelShadingMethods, ConstantColourTrianglesShadeExactlyAsPerSample) {
    // A colour that does not depend on where or when it is shaded: sharing it changes nothing,
    // to the bit, while each sample keeps its own exact exposure of every triangle.
    const Scene scene = constantColourScene();
    for (const char* method : kExactMethods)
        for (const int aa : {2, 4}) {
            RenderStats pixelStats, sampleStats;
            const Image pixel = test::render(method, scene, 32, 24, shadingOptions("pixel"), &pixelStats, ShadingMode::Unlit, aa);
            const Image sample = test::render(method, scene, 32, 24, shadingOptions("sample"), &sampleStats, ShadingMode::Unlit, aa);
            ASSERT_EQ(pixel.pixels().size(), sample.pixels().size());
            for (std::size_t i = 0; i < pixel.pixels().size(); ++i)
                ASSERT_EQ(pixel.pixels()[i], sample.pixels()[i]) << method << " --aa " << aa << " pixel " << i;
            EXPECT_EQ(pixelStats.counter("visible_pieces"), sampleStats.counter("visible_pieces")) << method;
            EXPECT_LT(pixelStats.counter("shaded_spans") * aa, sampleStats.counter("shaded_spans")) << method << " --aa " << aa;
        }
}

TEST(PixelShadingMethods, AnUnlitTriangleOfOneColourIsShadedOnceAPixel) {
    // Unlit, an untextured triangle whose vertex colours are one colour is that colour at every
    // point and time: each pixel shades each such triangle it sees once, the blue sliver too,
    // whose samples see it at disjoint times. Lit (its normal could turn), or with vertex colours
    // that blend, the sliver's disjoint times still split.
    Scene scene = constantColourScene();
    for (const char* method : kExactMethods) {
        RenderStats unlit, lit, blended;
        test::render(method, scene, 32, 24, shadingOptions("pixel"), &unlit, ShadingMode::Unlit, 4);
        test::render(method, scene, 32, 24, shadingOptions("pixel"), &lit, ShadingMode::Phong, 4);
        EXPECT_EQ(unlit.counter("shaded_spans_per_pixel"), unlit.counter("visible_triangles_per_pixel")) << method;
        EXPECT_GT(lit.counter("shaded_spans_per_pixel"), lit.counter("visible_triangles_per_pixel")) << method;
        Scene coloured = scene;
        Mesh& sliver = coloured.meshes[1];
        sliver.colors.assign(sliver.numVertices(), glm::vec4(1.0f));
        sliver.colors[0] = glm::vec4(0.5f, 1.0f, 1.0f, 1.0f);
        validateScene(coloured);
        test::render(method, coloured, 32, 24, shadingOptions("pixel"), &blended, ShadingMode::Unlit, 4);
        EXPECT_GT(blended.counter("shaded_spans_per_pixel"), blended.counter("visible_triangles_per_pixel")) << method;
    }
}

TEST(PixelShadingMethods, TexturedTranslatingQuadConvergesToTheBoxIntegralOverPixelAndShutter) {
    // The translating quad, per sample and per pixel in the default cells. (One cell per pixel
    // misses it by 0.042 and 2 x 2 cells by 0.015: one lookup at the pixel's centre is no box
    // filter over it; docs/BENCHMARKS.md, "Shading once per pixel".)
    TranslatingQuad quad;
    // Texture taps along the path as dense as the quadrature needs (the defaults, 2 per texel,
    // leave a few per cent on a texture this contrasty).
    for (const char* rate : {"sample", "pixel"})
    for (const char* method : kExactMethods) {
        OptionMap options = shadingOptions(rate);
        options.set("taps-per-texel", "16");
        options.set("texture-samples", "256");
        const Image image = test::render(method, quad.scene, quad.w, quad.h, options, nullptr, ShadingMode::Unlit, 4);
        EXPECT_LT(quad.worstError(image), 4e-3) << method << " shading=" << rate;
    }
}

TEST(PixelShadingMethods, AMinifiedTextureSweptUnderOnePixelBoxConvergesToTheBoxIntegral) {
    // The quad with 8 x 8 texels under each pixel, its uv sweeping 58 texels: one shading per
    // pixel (one cell) filters the pixel's box along the motion, 8 x 8 taps on level 0 at each of
    // 15 times, two a box width (Texture::boxGrid). 0.0032 off, where 32 times were 0.0020 off,
    // and one time's box (no path) is 0.014 off.
    TranslatingQuad quad(256);
    for (const char* method : kExactMethods) {
        const Image image = test::render(method, quad.scene, quad.w, quad.h, shadingOptions("pixel", 1), nullptr, ShadingMode::Unlit, 4);
        EXPECT_LT(quad.worstError(image), 5e-3) << method;
    }
}

TEST(SweptTextureMethods, TexturedTranslatingQuadConvergesToTheBoxIntegralOverPixelAndShutter) {
    // The same quad with texture-filter=swept: each sample's span is one lookup of its footprint
    // swept along the 1.8 texels its uv travels, its taps along the path as dense as asked, and
    // the N^2 samples make up the pixel box. With the taps the quadrature needs it converges to
    // the integral over pixel and shutter as the path taps do. (At the defaults, 2 taps per
    // texel, both filters are 0.0077 off.)
    TranslatingQuad quad;
    for (const char* method : kExactMethods) {
        OptionMap options = test::withOption("texture-filter", "swept");
        options.set("taps-per-texel", "16");
        options.set("texture-samples", "256");
        const Image image = test::render(method, quad.scene, quad.w, quad.h, options, nullptr, ShadingMode::Unlit, 4);
        EXPECT_LT(quad.worstError(image), 4e-3) << method;
    }
}

// A still textured quad under a still camera, every edge across pixels: its pixels share one
// shading each (Sharing::StillTextured), lit once and looked up at each sample. Each pixel is
// then the mean over its samples of the texture's bilinear surface at the samples the quad
// covers (the texture is magnified: a sample's footprint takes level 0), written out here from
// the sample pattern and the test's own bilinear lookup; and motion-path and analytic shade once
// a pixel and triangle, one lookup a covered sample.
TEST(PixelShadingMethods, AStillTexturedQuadIsEachSamplesOwnLookupShadedOnceAPixel) {
    constexpr int w = 40, h = 24, size = 8;
    constexpr float x0 = 2.29f, y0 = 3.71f, x1 = 33.79f, y1 = 20.21f;
    const std::vector<glm::vec4> texels = testTexels(size);
    Scene scene = test::emptyScene();
    scene.textures.push_back(Texture::fromLinear(size, size, texels, WrapMode::ClampToEdge, WrapMode::ClampToEdge));
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[m].baseColorTexture = 0;
    test::addPixelQuad(scene, test::PixelCamera{w, h, 2.0f}, m, x0, y0, x1, y1, 0.0f, 0.0f);
    scene.meshes.back().uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    validateScene(scene);
    for (const int aa : {1, 4, 8}) {
        const raster::SamplePattern pattern = raster::samplePatternFor(aa, false);
        std::vector<glm::dvec3> want(std::size_t(w * h));
        std::int64_t shadings = 0, lookups = 0;  // one a pixel and triangle; a lone sample looks up alone
        for (int py = 0; py < h; ++py)
            for (int px = 0; px < w; ++px) {
                glm::dvec3 sum(0.0);
                int covered[2] = {0, 0};  // by the quad's triangles either side of its diagonal
                for (int k = 0; k < pattern.count(); ++k) {
                    const glm::dvec2 ndc = pattern.ndcOf(px, py, k, w, h);
                    const double x = (ndc.x + 1.0) * 0.5 * w, y = (1.0 - ndc.y) * 0.5 * h;
                    const double u = (x - x0) / (x1 - x0), v = (y - y0) / (y1 - y0);
                    ASSERT_GT(std::min({std::abs(x - x0), std::abs(x - x1), std::abs(y - y0), std::abs(y - y1), std::abs(v - u) * h}), 1e-4);
                    if (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0) continue;
                    ++covered[v > u ? 0 : 1];
                    sum += glm::dvec3(bilinear(texels, size, glm::vec2(float(u), float(v))));
                }
                want[std::size_t(py * w + px)] = sum / double(pattern.count());
                for (const int n : covered) shadings += n > 0, lookups += n > 1 ? n : 0;
            }
        for (const char* method : kExactMethods) {
            // (higher-order's curved points shade each sample alone at --aa 1, and at --aa 4 share
            // a box over the pixel's samples, at --aa 8 over each cell's: 0.017 and 0.0048 off, its
            // taps clipped where the samples are not. So were the others before.)
            const bool isShared = std::string(method) != "higher-order";
            if (!isShared && aa > 1) continue;
            RenderStats stats;
            const Image image = test::render(method, scene, w, h, shadingOptions("pixel"), &stats, ShadingMode::Unlit, aa);
            double worst = 0.0;
            for (int py = 0; py < h; ++py)
                for (int px = 0; px < w; ++px) {
                    const glm::dvec3 d = glm::abs(glm::dvec3(image.at(px, py)) - want[std::size_t(py * w + px)]);
                    worst = std::max({worst, d.x, d.y, d.z});
                }
            EXPECT_LT(worst, 1e-5) << method << " --aa " << aa;
            if (!isShared) continue;
            EXPECT_EQ(stats.counter("shaded_spans"), double(shadings)) << method << " --aa " << aa;
            EXPECT_EQ(stats.counter("still_sample_lookups"), double(lookups)) << method << " --aa " << aa;
        }
    }
}

TEST(PixelShadingMethods, AThinFastSliverShadesOnlyItsOwnTexels) {
    // A sliver a quarter pixel wide crossing 20 pixels, its uvs in the middle of a texture that
    // is green there and magenta around it (as a texture atlas packs neighbours). Shared by
    // samples that see it at different times and places, its shading must stay on the sliver:
    // no magenta in any pixel.
    Scene scene = test::emptyScene();
    std::vector<glm::vec4> texels(8 * 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) texels[std::size_t(y) * 8 + x] = x >= 1 && x <= 6 ? glm::vec4(0, 1, 0, 1) : glm::vec4(1, 0, 1, 1);
    scene.textures.push_back(Texture::fromLinear(8, 8, std::move(texels), WrapMode::ClampToEdge, WrapMode::ClampToEdge));
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[m].baseColorTexture = 0;
    const test::PixelCamera c{32, 16, 2.0f};
    test::addPixelQuad(scene, c, m, 4.1f, 2.0f, 4.35f, 14.0f, 20.0f, 0.0f);
    scene.meshes.back().uvs = {{0.4375f, 0.375f}, {0.4375f, 0.625f}, {0.5625f, 0.625f}, {0.5625f, 0.375f}};
    validateScene(scene);
    for (const char* method : kExactMethods)
        for (const int cells : {1, 4}) {
            const Image image = test::render(method, scene, 32, 16, shadingOptions("pixel", cells), nullptr, ShadingMode::Unlit, 4);
            float green = 0.0f;
            for (int py = 0; py < 16; ++py)
                for (int px = 0; px < 32; ++px) {
                    const glm::vec3 p = image.at(px, py);
                    green = std::max(green, p.y);
                    EXPECT_LT(std::max(p.x, p.z), 1e-4f) << method << " cells " << cells << " at " << px << "," << py;
                }
            EXPECT_GT(green, 0.005f) << method;
        }
}

}  // namespace streak
