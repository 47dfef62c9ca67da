// Adaptive antialiasing in the exact methods (RenderSettings::adaptiveThreshold): one centre
// sample per pixel, then the full pattern where the first pass shows an edge or missed a surface.
// Judged against the closed-form area coverage of still shapes, and against the full pattern's
// and one sample's renders, whose pixels each pixel must be.
#include "methods/registry.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace streak {

namespace {

const char* const kExactMethods[] = {"motion-path", "analytic", "higher-order"};

constexpr int kWidth = 32, kHeight = 24, kAa = 8;
constexpr float kThreshold = 0.02f;

// Raster rectangles and a convex quad, still, over black: their pixels' exact colour is their
// area in the pixel (unlit). A quad moving along x makes a motion-blurred ramp beside them.
struct Shape {
    std::vector<glm::vec2> corners;  ///< counter-clockwise on screen (raster y down)
    float value;
};
const Shape kShapes[] = {
    {{{3.3f, 2.7f}, {3.3f, 9.2f}, {17.6f, 9.2f}, {17.6f, 2.7f}}, 1.0f},
    {{{20.2f, 3.1f}, {22.9f, 13.8f}, {29.4f, 12.2f}, {27.1f, 2.4f}}, 0.7f},
    // A stroke 0.2 pixel tall between the rows of pixel centres (18.5 and 19.5): a centre sample
    // never sees it.
    {{{4.2f, 18.6f}, {4.2f, 18.8f}, {27.8f, 18.8f}, {27.8f, 18.6f}}, 0.8f},
};
constexpr int kStrokeRow = 18;
const raster::PixelBounds kMoving{6, 12, 20, 15};  ///< the pixels the moving quad sweeps

// withTexture adds a still quad over [23.5, 31] x [14.2, 17.9] under a 64 x 64 texture of
// scattered grey levels within 0.01 of 0.5, 8 texels a pixel: a textured inside too faint to
// refine.
// withWire adds a wire 0.15 pixel thick from (1, 21) to (30, 22.6): centre samples see it only
// near x 10 and x 28, in pieces of a cut tile, not in others.
Scene adaptiveScene(bool withTexture = false, bool withWire = false) {
    Scene scene = test::emptyScene();
    const test::PixelCamera cam{kWidth, kHeight, 2.0f};
    for (const Shape& s : kShapes) {
        const std::uint32_t material = test::addMaterial(scene, glm::vec3(s.value));
        const std::array<glm::vec3, 4> corners = {cam.at(s.corners[0].x, s.corners[0].y), cam.at(s.corners[1].x, s.corners[1].y),
                                                  cam.at(s.corners[2].x, s.corners[2].y), cam.at(s.corners[3].x, s.corners[3].y)};
        test::addMovingQuad(scene, material, corners, corners);
    }
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(0.5f, 0.9f, 0.3f)), 6.0f, 12.0f, 12.0f, 16.0f, 9.0f, 0.0f);
    if (withTexture) {
        std::vector<glm::vec4> texels;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) texels.emplace_back(glm::vec3(0.49f + 0.02f * float((x * 37 + y * 91) % 17) / 16.0f), 1.0f);
        scene.textures.push_back(Texture::fromLinear(64, 64, std::move(texels), WrapMode::ClampToEdge, WrapMode::ClampToEdge));
        const std::uint32_t faint = test::addMaterial(scene, glm::vec3(1.0f));
        scene.materials[faint].baseColorTexture = int(scene.textures.size()) - 1;
        test::addPixelQuad(scene, cam, faint, 23.5f, 14.2f, 31.0f, 17.9f);
        scene.meshes.back().uvs = {{0.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}};
    }
    if (withWire) {
        const std::uint32_t wire = test::addMaterial(scene, glm::vec3(0.6f));
        test::addMovingQuad(scene, wire, {cam.at(1.0f, 21.0f), cam.at(1.0f, 21.15f), cam.at(30.0f, 22.75f), cam.at(30.0f, 22.6f)},
                            {cam.at(1.0f, 21.0f), cam.at(1.0f, 21.15f), cam.at(30.0f, 22.75f), cam.at(30.0f, 22.6f)});
    }
    validateScene(scene);
    return scene;
}

// The area of a convex polygon inside the pixel square (Sutherland-Hodgman, then the shoelace):
// written here, apart from streak's rasterizer.
double areaInPixel(const std::vector<glm::vec2>& polygon, int px, int py) {
    std::vector<glm::dvec2> poly(polygon.begin(), polygon.end());
    auto clip = [&](auto inside, auto cross) {
        std::vector<glm::dvec2> out;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
            if (inside(a)) out.push_back(a);
            if (inside(a) != inside(b)) out.push_back(cross(a, b));
        }
        poly = out;
    };
    auto atX = [](double x) { return [x](glm::dvec2 a, glm::dvec2 b) { return glm::dvec2(x, a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x)); }; };
    auto atY = [](double y) { return [y](glm::dvec2 a, glm::dvec2 b) { return glm::dvec2(a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y), y); }; };
    clip([&](glm::dvec2 p) { return p.x >= px; }, atX(px));
    clip([&](glm::dvec2 p) { return p.x <= px + 1; }, atX(px + 1));
    clip([&](glm::dvec2 p) { return p.y >= py; }, atY(py));
    clip([&](glm::dvec2 p) { return p.y <= py + 1; }, atY(py + 1));
    double area = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        area += a.x * b.y - b.x * a.y;
    }
    return std::fabs(area) * 0.5;
}

bool isSwept(int x, int y) { return x >= kMoving.x0 && x <= kMoving.x1 && y >= kMoving.y0 && y <= kMoving.y1; }

Image renderWith(const std::string& method, const Scene& scene, int aa, float threshold, bool passes = false, RenderStats* stats = nullptr,
                 std::uint64_t tileShareBytes = 0, float fullContrast = 0.0f, bool lineSamples = false) {
    OptionMap options;
    if (lineSamples) options.set("line-samples", "1");
    std::unique_ptr<Renderer> renderer = createRenderer(method, options);
    RenderSettings settings;
    settings.width = kWidth, settings.height = kHeight, settings.shading = ShadingMode::Unlit, settings.aa = aa;
    settings.adaptiveThreshold = threshold, settings.adaptiveFullContrast = fullContrast;
    settings.tileShareBytes = tileShareBytes;
    if (passes) settings.passes.depth = settings.passes.objectId = true;
    RenderStats local;
    RenderContext context{stats ? *stats : local};
    return renderer->render(scene, settings, context);
}

// RMS of the still pixels' red against their closed-form colour.
double stillRms(const Image& image) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            if (isSwept(x, y)) continue;
            double expected = 0.0;
            for (const Shape& s : kShapes) expected += s.value * areaInPixel(s.corners, x, y);
            const double e = double(image.at(x, y).x) - expected;
            sum += e * e, ++n;
        }
    return std::sqrt(sum / n);
}

}  // namespace

TEST(AdaptiveSamplingMethods, AsCloseToTheExactCoverageAsTheFullPatternAtAFractionOfItsPixels) {
    const Scene scene = adaptiveScene();
    for (const char* method : kExactMethods) {
        SCOPED_TRACE(method);
        RenderStats stats;
        const Image adaptive = renderWith(method, scene, kAa, kThreshold, false, &stats);
        const double full = stillRms(renderWith(method, scene, kAa, 0.0f)), one = stillRms(renderWith(method, scene, 1, 0.0f));
        const double refined = stillRms(adaptive);
        EXPECT_LE(refined, full * 1.02 + 1e-6) << "full " << full << ", one sample " << one;
        EXPECT_GT(one, 3.0 * full);  // what refining nothing would score
        // Edges and the stroke, not the whole image.
        const double fraction = stats.counter("adaptive_refined_fraction");
        EXPECT_GT(fraction, 0.1);
        EXPECT_LT(fraction, 0.6);
        EXPECT_GT(stats.counter("adaptive_pixels_unseen_geometry"), 10.0);
        // The stroke no centre sample sees is there: about its 0.2 of a pixel's area.
        for (int x = 6; x <= 26; ++x) EXPECT_NEAR(adaptive.at(x, kStrokeRow).x, 0.8f * 0.2f, 0.8f * 0.126f) << x;
    }
}

// A refined pixel is the full pattern's (aa 8) or, where its contrast is mild, the coarse one's
// (aa 4); with the full contrast at the threshold, every refined pixel is the full pattern's.
TEST(AdaptiveSamplingMethods, EachPixelIsTheFullOrCoarsePatternsOrTheCentreSamplesToTheBitPassesToo) {
    const Scene scene = adaptiveScene(/*withTexture=*/true);
    for (const char* method : kExactMethods)
        for (const float fullContrast : {0.0f, kThreshold}) {
            SCOPED_TRACE(std::string(method) + (fullContrast > 0.0f ? ", every refined pixel full" : ", graded"));
            RenderStats stats;
            const Image adaptive = renderWith(method, scene, kAa, kThreshold, true, &stats, 0, fullContrast);
            const Image full = renderWith(method, scene, kAa, 0.0f, true);
            const Image coarse = renderWith(method, scene, kAa / 2, 0.0f, true);
            const Image one = renderWith(method, scene, 1, 0.0f, true);
            ASSERT_EQ(adaptive.channels().size(), full.channels().size());
            int refined = 0, onlyCoarse = 0, visible = 0;
            auto same = [](const Image& a, const Image& b, int x, int y, std::size_t i) {
                return a.at(x, y) == b.at(x, y) && a.alpha()[i] == b.alpha()[i];
            };
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) {
                    const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
                    const bool isFull = same(adaptive, full, x, y, i), isOne = same(adaptive, one, x, y, i);
                    const bool isCoarse = fullContrast == 0.0f && same(adaptive, coarse, x, y, i);
                    ASSERT_TRUE(isFull || isCoarse || isOne) << x << "," << y;
                    refined += (isFull || isCoarse) && !isOne;
                    onlyCoarse += isCoarse && !isFull && !isOne;
                    // Every pixel that one sample gets visibly wrong is refined.
                    const float error = std::fabs(one.at(x, y).x - full.at(x, y).x);
                    if (error > 0.1f) {
                        ++visible;
                        EXPECT_TRUE(isFull || isCoarse) << x << "," << y << ": " << error;
                    }
                    for (std::size_t c = 0; c < adaptive.channels().size(); ++c) {
                        const float v = adaptive.channels()[c].values[i];
                        const float source = (isFull ? full : isCoarse ? coarse : one).channels()[c].values[i];
                        EXPECT_TRUE(v == source || (std::isnan(v) && std::isnan(source))) << adaptive.channels()[c].name << " " << x << "," << y;
                    }
                }
            EXPECT_GT(visible, 40);
            EXPECT_GE(refined, visible);
            // Graded, the mild steps (4 of the 319 refined pixels here) take the coarse pattern: each
            // of them is the coarse render's, and no other pixel is.
            EXPECT_EQ(double(onlyCoarse), stats.counter("adaptive_pixels_refined_coarse"));
            if (fullContrast == 0.0f) EXPECT_GT(onlyCoarse, 0);
            // The faint texture's inside stays at its centre sample (the full pattern's is another
            // colour there).
            EXPECT_EQ(adaptive.at(27, 16), one.at(27, 16));
            EXPECT_NE(full.at(27, 16), one.at(27, 16));
        }
}

// With line samples, a still tile's samples are lines: a coarse pixel there takes the coarse
// pattern's lines (4 rows at --aa 8, where the full pattern has 16), and is that render's.
TEST(AdaptiveSamplingMethods, WithLineSamplesACoarsePixelTakesTheCoarsePatternsLines) {
    // Nothing moves, so every tile takes lines: over a black wall that covers the frame, a
    // bright quad (strong edges) and a dark one of 0.003 (0.039 in sRGB, the same coverage: mild
    // at threshold 0.02, within 3 x 0.02).
    Scene scene = test::emptyScene();
    const test::PixelCamera cam{kWidth, kHeight, 2.0f};
    test::addPixelQuad(scene, test::PixelCamera{kWidth, kHeight, 3.0f}, test::addMaterial(scene, glm::vec3(0.0f)), -2.0f, -2.0f,
                       float(kWidth) + 2.0f, float(kHeight) + 2.0f);
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(0.9f)), 3.3f, 2.7f, 17.6f, 9.2f);
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(0.003f)), 4.4f, 13.3f, 27.7f, 20.8f);
    validateScene(scene);
    for (const char* method : {"motion-path", "analytic"}) {
        SCOPED_TRACE(method);
        RenderStats stats, fullStats;
        const Image adaptive = renderWith(method, scene, kAa, kThreshold, false, &stats, 0, 0.0f, true);
        const Image full = renderWith(method, scene, kAa, 0.0f, false, &fullStats, 0, 0.0f, true);
        const Image coarse = renderWith(method, scene, kAa / 2, 0.0f, false, nullptr, 0, 0.0f, true);
        // (The first pass takes points, not lines: its pixels are the point render's.)
        const Image one = renderWith(method, scene, 1, 0.0f);
        ASSERT_EQ(fullStats.counter("line_samples"), 1.0);
        int onlyCoarse = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
                auto same = [&](const Image& other) { return adaptive.at(x, y) == other.at(x, y) && adaptive.alpha()[i] == other.alpha()[i]; };
                ASSERT_TRUE(same(full) || same(coarse) || same(one)) << x << "," << y;
                onlyCoarse += same(coarse) && !same(full) && !same(one);
            }
        // (Pixels flat themselves beside a mild edge are refined too, to what all three give.)
        EXPECT_GT(onlyCoarse, 0);
        EXPECT_LE(double(onlyCoarse), stats.counter("adaptive_pixels_refined_coarse"));
    }
}

// The memory budget halves a tile whose lists would pass its share, and the image must not
// change: what the first pass saw of a segment is gathered over the whole tile, not per half
// (where a segment seen in one half would be unseen in the other, and refine it).
TEST(AdaptiveSamplingMethods, ABudgetThatCutsTilesChangesNoBit) {
    const Scene scene = adaptiveScene(/*withTexture=*/true, /*withWire=*/true);
    for (const char* method : kExactMethods) {
        SCOPED_TRACE(method);
        RenderStats whole, cut;
        const Image a = renderWith(method, scene, kAa, kThreshold, true, &whole);
        const Image b = renderWith(method, scene, kAa, kThreshold, true, &cut, 128 << 10);
        EXPECT_GT(cut.counter("memory_budget_splits"), 0.0);
        EXPECT_EQ(cut.counter("memory_budget_pixels_cut"), 0.0);
        EXPECT_EQ(cut.counter("adaptive_pixels_refined"), whole.counter("adaptive_pixels_refined"));
        EXPECT_EQ(a.pixels().size(), b.pixels().size());
        EXPECT_TRUE(std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin()));
        for (std::size_t c = 0; c < a.channels().size(); ++c) {
            const std::vector<float>& x = a.channels()[c].values;
            const std::vector<float>& y = b.channels()[c].values;
            for (std::size_t i = 0; i < x.size(); ++i) EXPECT_TRUE(x[i] == y[i] || (std::isnan(x[i]) && std::isnan(y[i]))) << a.channels()[c].name;
        }
    }
}

}  // namespace streak
