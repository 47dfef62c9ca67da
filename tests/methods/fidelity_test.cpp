// Fidelity against closed forms that no streak method computes: edge coverage under --aa N
// (n-rooks samples) and the box integral of a texture under a pixel (footprint of one sample
// spacing). Every CPU method is held to them, so a shared mistake cannot hide.

#include "image/metrics.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace streak {

namespace {

const char* const kMethods[] = {"accumulation", "stochastic", "motion-path", "analytic", "higher-order"};

OptionMap optionsFor(const std::string& method) {
    return method == "accumulation" || method == "stochastic" ? test::withOption("samples", "1") : OptionMap();
}

// A static white quad over the left of a 4x4 image whose right edge sits `fraction` of a pixel
// into column 2.
Scene edgeScene(float fraction) {
    Scene scene = test::emptyScene();
    const test::PixelCamera cam{4, 4, 2.0f};
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), -1.0f, -1.0f, 2.0f + fraction, 5.0f);
    validateScene(scene);
    return scene;
}

}  // namespace

class EdgeCoverage : public ::testing::TestWithParam<const char*> {};

// An axis-aligned edge a fraction f into a pixel covers f of it, to within one sample in N^2
// with n-rooks (every sample in its own column); the grid quantises it to 1/N and gives 0 for
// f = 3% at N = 8.
TEST_P(EdgeCoverage, AxisAlignedEdgeCoversItsFraction) {
    const std::string method = GetParam();
    for (int n : {4, 8}) {
        for (float f : {0.03f, 0.2f, 0.51f, 0.9f}) {
            const Image image = test::render(method, edgeScene(f), 4, 4, optionsFor(method), nullptr, ShadingMode::Unlit, n);
            const float coverage = image.at(2, 1).x;
            EXPECT_NEAR(coverage, f, 1.0f / float(n * n) + 1e-4f) << method << " aa " << n << " f " << f;
        }
    }
    const Image grid = test::render(method, edgeScene(0.03f), 4, 4, optionsFor(method), nullptr, ShadingMode::Unlit, 8, true);
    EXPECT_EQ(grid.at(2, 1).x, 0.0f) << "the grid's first column sits 1/16 pixel in";
}

INSTANTIATE_TEST_SUITE_P(CpuMethods, EdgeCoverage, ::testing::ValuesIn(kMethods));

namespace {

// A static quad filling an 8x6 image, textured with a 64x48 texture (8x8 texels per pixel, one
// random grey per pixel), and each pixel's box integral of the texture (its bilinear
// reconstruction).
struct TexturedQuad {
    Scene scene;
    std::vector<float> texelMean;  ///< per pixel, the red channel's box integral
};

TexturedQuad texturedQuad(int texelsPerPixel) {
    constexpr int kW = 8, kH = 6;
    const int tw = kW * texelsPerPixel, th = kH * texelsPerPixel;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    // Each pixel's block of texels is one random grey: a footprint wider than a sample spacing
    // blends neighbouring pixels' greys in.
    std::vector<float> blocks(std::size_t(kW) * kH);
    for (float& b : blocks) b = uniform(rng);
    std::vector<glm::vec4> texels(std::size_t(tw) * th);
    for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x)
            texels[std::size_t(y) * tw + x] = glm::vec4(glm::vec3(blocks[std::size_t(y / texelsPerPixel) * kW + std::size_t(x / texelsPerPixel)]), 1.0f);
    TexturedQuad out;
    out.scene = test::emptyScene();
    out.scene.textures.push_back(Texture::fromLinear(tw, th, texels, WrapMode::ClampToEdge, WrapMode::ClampToEdge));
    Material m;
    m.baseColorTexture = 0;
    m.doubleSided = true;
    out.scene.materials.push_back(m);
    const test::PixelCamera cam{kW, kH, 2.0f};
    test::addPixelQuad(out.scene, cam, 0, 0.0f, 0.0f, float(kW), float(kH));
    out.scene.meshes[0].uvs = {{0.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}};
    validateScene(out.scene);
    // The box integral of the level-0 bilinear reconstruction, by a 32 x 32 midpoint rule.
    const Texture& texture = out.scene.textures[0];
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            double sum = 0.0;
            for (int j = 0; j < 32; ++j)
                for (int i = 0; i < 32; ++i) {
                    const glm::vec2 uv((float(px) + (float(i) + 0.5f) / 32.0f) / float(kW), (float(py) + (float(j) + 0.5f) / 32.0f) / float(kH));
                    sum += texture.sampleBilinear(uv, 0).x;
                }
            out.texelMean.push_back(float(sum / 1024.0));
        }
    return out;
}

}  // namespace

class TextureBoxIntegral : public ::testing::TestWithParam<const char*> {};

// Under --aa N each sample's footprint is one sample spacing, so the N x N samples integrate
// the texture over the pixel: the image converges to the box integral as N grows. (A footprint
// of one pixel per sample filters twice: each sample already averages the pixel's texels and
// their neighbours, and the box filter blurs again.)
TEST_P(TextureBoxIntegral, ConvergesToThePixelsBoxIntegral) {
    const std::string method = GetParam();
    const TexturedQuad quad = texturedQuad(8);
    double previous = 1.0;
    for (int n : {2, 4, 8}) {
        const Image image = test::render(method, quad.scene, 8, 6, optionsFor(method), nullptr, ShadingMode::Unlit, n);
        double worst = 0.0;
        for (int py = 1; py < 5; ++py)  // border pixels: clamp-to-edge filtering differs there
            for (int px = 1; px < 7; ++px) worst = std::max(worst, double(std::abs(image.at(px, py).x - quad.texelMean[std::size_t(py * 8 + px)])));
        std::printf("%s aa %d: worst %.4f\n", method.c_str(), n, worst);
        EXPECT_LT(worst, 0.5 * previous) << method << " aa " << n << ": more samples must converge";
        previous = worst;
        if (n == 8) { EXPECT_LT(worst, 0.01) << method; }
    }
}

INSTANTIATE_TEST_SUITE_P(CpuMethods, TextureBoxIntegral, ::testing::ValuesIn(kMethods));

namespace {

// A floor (y = -1) seen from the origin at a grazing angle, textured with a checkerboard of long
// cells: 8 texels across the view (1 px at depth 8, 128 x 96 px), 128 texels along it. At
// depth 8 each of the 8 x 8 samples of a pixel covers about 1 texel across and 8 along.
struct SlantedCheckerboard {
    static constexpr int kW = 128, kH = 96;
    static constexpr float kTexelsPerUnit = 48.0f;
    Scene scene;

    SlantedCheckerboard() : scene(test::emptyScene()) {
        std::vector<glm::vec4> texels(32 * 256);
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 32; ++x) texels[std::size_t(y) * 32 + x] = glm::vec4(glm::vec3(isWhiteTexel(x, y) ? 1.0f : 0.0f), 1.0f);
        scene.textures.push_back(Texture::fromLinear(32, 256, texels));
        Material m;
        m.baseColorTexture = 0;
        m.doubleSided = true;
        scene.materials.push_back(m);
        const std::array<glm::vec3, 4> corners{glm::vec3(-16.0f, -1.0f, -2.0f), glm::vec3(16.0f, -1.0f, -2.0f),
                                               glm::vec3(16.0f, -1.0f, -40.0f), glm::vec3(-16.0f, -1.0f, -40.0f)};
        test::addMovingQuad(scene, 0, corners, corners);
        for (const glm::vec3& p : corners) scene.meshes[0].uvs.push_back(uvAt(p.x, p.z));
        validateScene(scene);
    }
    static glm::vec2 uvAt(float x, float z) { return {x * kTexelsPerUnit / 32.0f, -z * kTexelsPerUnit / 256.0f}; }
    static bool isWhiteTexel(int x, int y) { return (x / 8 + y / 128) % 2 == 0; }
    // The pixel's box integral of the texture (its level-0 bilinear reconstruction), by 16 x 16
    // rays meeting the floor.
    float boxIntegral(int px, int py) const {
        const float aspect = float(kW) / float(kH);  // 90-degree vertical field of view
        double sum = 0.0;
        for (int j = 0; j < 16; ++j)
            for (int i = 0; i < 16; ++i) {
                const float x = (2.0f * (float(px) + (float(i) + 0.5f) / 16.0f) / float(kW) - 1.0f) * aspect;
                const float y = 1.0f - 2.0f * (float(py) + (float(j) + 0.5f) / 16.0f) / float(kH);
                const float t = -1.0f / y;  // the ray (x, y, -1) t meets y = -1
                if (!(t >= 2.0f && t <= 40.0f) || std::abs(x * t) > 16.0f) continue;
                sum += scene.textures[0].sampleBilinear(uvAt(x * t, -t), 0).x;
            }
        return float(sum / 256.0);
    }
};

}  // namespace

namespace {

// The cells' contrast across the view in rows at depth 5 to 12 (mean over rows of max - min),
// the image's and the box integral's, and the image's mean error against the box integral.
struct SlantedContrast {
    double contrast = 0.0, referenceContrast = 0.0, meanError = 0.0;
};

SlantedContrast measureSlantedContrast(const SlantedCheckerboard& board, const Image& image) {
    double errorSum = 0.0, contrast = 0.0, referenceContrast = 0.0;
    int count = 0, rows = 0;
    for (int py = 52; py <= 57; ++py) {
        float lo = 1.0f, hi = 0.0f, refLo = 1.0f, refHi = 0.0f;
        for (int px = 16; px < board.kW - 16; ++px) {
            const float value = image.at(px, py).x, reference = board.boxIntegral(px, py);
            errorSum += std::abs(value - reference);
            ++count;
            lo = std::min(lo, value), hi = std::max(hi, value);
            refLo = std::min(refLo, reference), refHi = std::max(refHi, reference);
        }
        contrast += hi - lo, referenceContrast += refHi - refLo, ++rows;
    }
    return {contrast / rows, referenceContrast / rows, errorSum / count};
}

}  // namespace

class SlantedTexture : public ::testing::TestWithParam<const char*> {};

// Rows at depth 5 to 12, where the samples' footprints are 1 by 5-12 texels: anisotropic taps
// keep the cells' contrast across the view (0.96 of the box integral's); one tap at the longer
// axis' level (what GPUs do without anisotropy) blurs each sample over a pixel (0.68).
TEST_P(SlantedTexture, CheckerboardKeepsItsContrastAlongTheMinorAxis) {
    const std::string method = GetParam();
    const SlantedCheckerboard board;
    const Image image = test::render(method, board.scene, board.kW, board.kH, optionsFor(method), nullptr, ShadingMode::Unlit, 8);
    const SlantedContrast m = measureSlantedContrast(board, image);
    std::printf("%s: mean error %.4f, contrast %.3f of the box integral's %.3f\n", method.c_str(), m.meanError, m.contrast,
                m.referenceContrast);
    EXPECT_GT(m.referenceContrast, 0.8) << "the scene must show cells a pixel resolves";
    EXPECT_GT(m.contrast / m.referenceContrast, 0.9) << method;
    // What is left is the 1/8-px prefilter of each sample's footprint (0.0175 here; 0.025 with one tap).
    EXPECT_LT(m.meanError, 0.021) << method;
}

// Shaded once per pixel cell (shading=pixel), the samples of a cell share one footprint over
// their bounds: 1/4 by 1/4 px in the default 4 x 4 cells, here 1 by 5-12 texels, and the whole
// pixel in one cell, 4 by 20-48. Either filter (the box, and the anisotropic lookup of
// shading-filter=lookup) keeps the cells' contrast across the view: measured 0.98 and 0.99 of
// the box integral's at 4 x 4 cells (mean error 0.016 and 0.013), 0.95 and 0.94 at one cell
// (0.025 both: a box 48 texels long takes its taps from the level of 2-texel spacing).
TEST(SlantedTexturePixelShading, CheckerboardKeepsItsContrastAlongTheMinorAxis) {
    const SlantedCheckerboard board;
    for (const char* method : {"motion-path", "analytic", "higher-order"})
        for (const char* filter : {"box", "lookup"})
            for (const int cells : {1, 4}) {
                OptionMap options = test::withOption("shading", "pixel");
                options.set("shading-cells", std::to_string(cells));
                options.set("shading-filter", filter);
                const Image image = test::render(method, board.scene, board.kW, board.kH, options, nullptr, ShadingMode::Unlit, 8);
                const SlantedContrast m = measureSlantedContrast(board, image);
                std::printf("%s, %s, %d cells: mean error %.4f, contrast %.3f of the box integral's %.3f\n", method, filter, cells,
                            m.meanError, m.contrast, m.referenceContrast);
                EXPECT_GT(m.contrast / m.referenceContrast, 0.9) << method << " " << filter << " cells " << cells;
                EXPECT_LT(m.meanError, cells == 1 ? 0.03 : 0.021) << method << " " << filter << " cells " << cells;
            }
}

INSTANTIATE_TEST_SUITE_P(CpuMethods, SlantedTexture, ::testing::ValuesIn(kMethods));

}  // namespace streak

namespace streak {

namespace {

// A far quad textured with a ramp along u (red = u) slides right 16 pixels over the shutter
// at depth 4, so the texture under pixel (4, 4)'s centre runs red(t) = (44.5 - 16 t) / 88; a
// near black quad at depth 2 covers that centre until its right edge, sliding left from x = 12
// by 16 pixels, passes it at t = 7.5 / 16.
Scene partlyHiddenScene() {
    Scene scene = test::emptyScene();
    const std::uint32_t ramp = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[ramp].baseColorTexture = test::addRampTexture(scene);
    test::addPixelQuad(scene, test::PixelCamera{8, 8, 4.0f}, ramp, -40.0f, -1.0f, 48.0f, 9.0f, 16.0f, 0.0f);
    scene.meshes.back().uvs = {{0.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}};
    test::addPixelQuad(scene, test::PixelCamera{8, 8, 2.0f}, test::addMaterial(scene, glm::vec3(0.0f)), -20.0f, -1.0f, 12.0f, 9.0f, -16.0f, 0.0f);
    validateScene(scene);
    return scene;
}

}  // namespace

class PartlyHiddenSurface : public ::testing::TestWithParam<const char*> {};

// A surface hidden for part of the shutter shows the mean of its colour over the time it shows,
// not over its whole span: the pixel is the integral of red(t) over [7.5/16, 1], 0.1977, where
// the whole span's mean times the share it shows gives 0.2203.
TEST_P(PartlyHiddenSurface, ShowsTheColourOfTheTimeItShows) {
    const std::string method = GetParam();
    const double hidden = 7.5 / 16.0;
    auto integral = [](double t) { return (44.5 * t - 8.0 * t * t) / 88.0; };
    const double expected = integral(1.0) - integral(hidden);
    OptionMap options = method == "accumulation" ? test::withOption("samples", "4096") : OptionMap();
    const Image image = test::render(method, partlyHiddenScene(), 8, 8, options, nullptr, ShadingMode::Unlit, 1);
    EXPECT_NEAR(image.at(4, 4).x, expected, 2e-3) << method;
}

INSTANTIATE_TEST_SUITE_P(CpuMethods, PartlyHiddenSurface, ::testing::Values("accumulation", "motion-path", "analytic", "higher-order"));

}  // namespace streak
