// The GL methods against their CPU twins, on Mesa's llvmpipe in CI (or any GL 4.5 driver).

#include "gpu/gl_context.h"
#include "image/cryptomatte.h"
#include "image/deep_image.h"
#include "image/metrics.h"
#include "util/error.h"
#include "scene/builtin_scenes.h"
#include "scene/scene.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace streak {
namespace {

Scene builtin(const std::string& name, OptionMap options = OptionMap()) { return test::validBuiltin(name, std::move(options)); }

TEST(GlContext, NamesItsRendererAndVersion) {
    const gpu::GlContext& gl = gpu::sharedContext();
    EXPECT_FALSE(gl.renderer().empty());
    EXPECT_NE(gl.version().find("4."), std::string::npos) << gl.version();
}

class AccumulationGlAgreement : public testing::TestWithParam<std::string> {};

// Same shutter times, shading and blending as the CPU accumulation: only rasterization
// details (fill rule ties, derivative-based texture lod) may differ.
TEST_P(AccumulationGlAgreement, MatchesCpuAccumulationAtTheSameSamples) {
    const Scene scene = builtin(GetParam());
    RenderStats stats;
    const Image gl = test::render("accumulation-gl", scene, 96, 72, test::withOption("samples", "16"), &stats, ShadingMode::Phong);
    const Image cpu = test::render("accumulation", scene, 96, 72, test::withOption("samples", "16"), nullptr, ShadingMode::Phong);
    EXPECT_GE(psnr(gl, cpu), 45.0);
    EXPECT_EQ(stats.counter("translucent_layer_overflow_samples"), 0.0);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, AccumulationGlAgreement,
                         testing::Values("rotating-cube", "crossing", "twist", "fence", "pan", "translucent", "cubes"));

// Hardware rasterization puts accumulation-gl's samples on the grid's texel centres: it agrees
// with the CPU on the grid, and says so in its stats.
TEST(AccumulationGl, MatchesCpuWithSubpixelSamples) {
    const Scene scene = builtin("translucent");
    RenderStats stats;
    const Image gl = test::render("accumulation-gl", scene, 64, 48, test::withOption("samples", "8"), &stats, ShadingMode::Phong, 2);
    const Image cpu = test::render("accumulation", scene, 64, 48, test::withOption("samples", "8"), nullptr, ShadingMode::Phong, 2, true);
    EXPECT_GE(psnr(gl, cpu), 45.0);
    EXPECT_EQ(stats.counter("samples_on_grid"), 1.0);
}

// A translucent layer budget of 1 keeps only the nearest pane: the overflow is counted and the
// image changes, where the full budget agrees with the CPU.
TEST(AccumulationGl, CountsTranslucentLayerOverflow) {
    const Scene scene = builtin("translucent");
    OptionMap options = test::withOption("samples", "4");
    options.set("layers", "1");
    RenderStats stats;
    const Image clipped = test::render("accumulation-gl", scene, 64, 48, options, &stats);
    const Image cpu = test::render("accumulation", scene, 64, 48, test::withOption("samples", "4"));
    EXPECT_GT(stats.counter("translucent_layer_overflow_samples"), 0.0);
    EXPECT_LT(psnr(clipped, cpu), 40.0);
}

class MotionPathGlAgreement : public testing::TestWithParam<std::string> {};

// The same method on the GPU: the same exact spans (pass 1), intervals, depth-time sort, resolve
// and span shading (pass 2), so the images agree to float rounding and the counts of intervals,
// splits and shaded spans agree too (a span may differ where a root sits on a float boundary).
// Both resolve opaque lists exactly in time by default, and count mask slices as the paper does
// with exact-weights=0. The GPU keeps one interval per segment in its lists: the CPU does too
// with merge-segments=0 (cpuTwin), which counts as the GPU does and renders as the CPU's default.
OptionMap cpuTwin(OptionMap options = OptionMap()) {
    options.set("merge-segments", "0");
    return options;
}

TEST_P(MotionPathGlAgreement, MatchesCpuMotionPath) {
    const Scene scene = builtin(GetParam());
    for (const char* exact : {"1", "0"}) {
        RenderStats gpuStats, cpuStats;
        const Image gl = test::render("motion-path-gl", scene, 96, 72, test::withOption("exact-weights", exact), &gpuStats, ShadingMode::Phong);
        const Image cpu = test::render("motion-path", scene, 96, 72, cpuTwin(test::withOption("exact-weights", exact)), &cpuStats, ShadingMode::Phong);
        const Image cpuDefault = test::render("motion-path", scene, 96, 72, test::withOption("exact-weights", exact), nullptr, ShadingMode::Phong);
        std::printf("exact-weights=%s: gl vs cpu %.1f dB, vs cpu merging segments %.1f dB\n", exact, psnr(gl, cpu), psnr(gl, cpuDefault));
        EXPECT_GE(psnr(gl, cpu), 80.0) << exact;
        EXPECT_GE(psnr(gl, cpuDefault), 80.0) << exact;
        ASSERT_GT(cpuStats.counter("intervals"), 0.0);
        for (const char* counter : {"intervals", "shaded_spans", "interval_splits", "backface_intervals_culled"})
            EXPECT_NEAR(gpuStats.counter(counter), cpuStats.counter(counter), 1e-3 * cpuStats.counter("intervals")) << counter << " " << exact;
        EXPECT_EQ(gpuStats.counter("interval_overflow_samples"), 0.0);
    }
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, MotionPathGlAgreement,
                         testing::Values("rotating-cube", "crossing", "twist", "fence", "pan", "translucent", "cubes"));

// motion-path-gl's passes come from its resolve's record of what shows in each sample: on the
// swept wall (test::sweptWall) each object's Cryptomatte coverage and the depth are their
// closed forms, and the deep samples flatten to the image; with the sweeper translucent too.
TEST(MotionPathGl, WritesTheClosedFormPassesAndDeepSamples) {
    const int width = test::kSweptWallWidth, height = test::kSweptWallHeight;
    for (const bool isTranslucent : {false, true}) {
        SCOPED_TRACE(isTranslucent ? "translucent" : "opaque");
        Scene scene = test::sweptWall();
        if (isTranslucent) scene.materials[1].opacity = 0.4f;
        std::unique_ptr<Renderer> renderer = createRenderer("motion-path-gl", OptionMap());
        ASSERT_TRUE(renderer->writesPasses());
        RenderSettings settings;
        settings.width = width, settings.height = height, settings.shading = ShadingMode::Unlit;
        settings.passes.depth = settings.passes.objectId = settings.passes.deep = true;
        settings.passes.cryptoRanks = 2;
        RenderStats stats;
        RenderContext context{stats};
        const Image image = renderer->render(scene, settings, context);
        ASSERT_NE(image.deep(), nullptr);
        EXPECT_EQ(stats.counter("shown_overflow_samples"), 0.0);
        auto values = [&](const std::string& name) -> const std::vector<float>& {
            for (const ImageChannel& c : image.channels())
                if (c.name == name) return c.values;
            throw std::runtime_error("no channel " + name);
        };
        const float opacity = isTranslucent ? 0.4f : 1.0f;
        for (int py = 0; py < height; ++py)
            for (int px = 0; px < width; ++px) {
                SCOPED_TRACE("pixel " + std::to_string(px) + "," + std::to_string(py));
                const std::size_t i = std::size_t(py) * width + std::size_t(px);
                const test::Expected e = test::expectedAt(px);
                // Translucent, the sweeper takes its opacity of its share, the wall the rest.
                const float sweeper = opacity * e.sweeper, wall = e.wall + (isTranslucent && px < 6 ? (1.0f - opacity) * e.sweeper : 0.0f);
                float sweeperMatte = 0.0f, wallMatte = 0.0f;
                for (const char* rank : {"CryptoObject00.r", "CryptoObject00.b"}) {
                    const std::string coverage = std::string(rank).substr(0, 15) + (rank[15] == 'r' ? "g" : "a");
                    const float id = values(rank)[i], share = values(coverage)[i];
                    if (id == cryptomatteId("sweeper")) sweeperMatte += share;
                    if (id == cryptomatteId("wall")) wallMatte += share;
                }
                // (Translucent lists are resolved in 128 slices of the shutter, as on the CPU.)
                const float tolerance = isTranslucent ? 1.0f / 128.0f + 1e-5f : 1e-5f;
                EXPECT_NEAR(sweeperMatte, sweeper, tolerance);
                EXPECT_NEAR(wallMatte, wall, tolerance);
                if (sweeper + wall > 0.0f) EXPECT_NEAR(values("Z")[i], (2.0f * sweeper + 3.0f * wall) / (sweeper + wall), isTranslucent ? 0.05f : 1e-4f);
                else EXPECT_EQ(values("Z")[i], kEmptyDepth);
                glm::vec4 flat(0.0f);
                for (const DeepSample& d : image.deep()->samples(px, py)) flat += (1.0f - flat.w) * glm::vec4(d.color, d.alpha);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(flat[c], image.at(px, py)[c], 1e-5f);
                EXPECT_NEAR(flat.w, 1.0f, 1e-5f);
            }
    }
    // A sample swept by more triangles than it has records: 16 strips of one mesh ("strips", 32
    // triangles) crossing each sample in turn over a wall of another ("wall") behind them. The
    // strips' triangles come first, fill the records and join by mesh; the wall's frees one.
    // The two mattes still sum to the alpha, and the deep samples flatten to the image.
    {
        Scene scene = test::emptyScene(glm::vec3(0.2f));
        const test::PixelCamera near{8, 2, 2.0f};
        Mesh strips;
        strips.name = "strips", strips.material = test::addMaterial(scene, glm::vec3(1.0f)), strips.numKeys = 2;
        for (const float dx : {0.0f, 32.0f})
            for (int k = 0; k < 16; ++k) {
                const float x0 = -32.0f + 2.0f * float(k) + dx;
                for (const glm::vec2 c : {glm::vec2(x0, -1.0f), glm::vec2(x0, 3.0f), glm::vec2(x0 + 1.0f, 3.0f), glm::vec2(x0 + 1.0f, -1.0f)})
                    strips.positions.push_back(near.at(c.x, c.y));
            }
        for (std::uint32_t k = 0; k < 16; ++k) strips.triangles.push_back({4 * k, 4 * k + 1, 4 * k + 2}), strips.triangles.push_back({4 * k, 4 * k + 2, 4 * k + 3});
        scene.meshes.push_back(strips);
        test::addPixelQuad(scene, test::PixelCamera{8, 2, 3.0f}, test::addMaterial(scene, glm::vec3(0.5f)), -4.0f, -1.0f, 12.0f, 3.0f);
        scene.meshes.back().name = "wall";
        validateScene(scene);
        RenderSettings settings;
        settings.width = 8, settings.height = 2, settings.shading = ShadingMode::Unlit;
        settings.passes.objectId = settings.passes.deep = true;
        settings.passes.cryptoRanks = 2;
        RenderStats stats;
        RenderContext context{stats};
        const Image image = createRenderer("motion-path-gl", OptionMap())->render(scene, settings, context);
        EXPECT_EQ(stats.counter("shown_overflow_samples"), 0.0);
        auto values = [&](const std::string& name) -> const std::vector<float>& {
            for (const ImageChannel& c : image.channels())
                if (c.name == name) return c.values;
            throw std::runtime_error("no channel " + name);
        };
        for (std::size_t i = 0; i < 16; ++i) {
            float matte[2] = {0.0f, 0.0f};
            for (const auto& [id, coverage] : {std::pair{"CryptoObject00.r", "CryptoObject00.g"}, std::pair{"CryptoObject00.b", "CryptoObject00.a"}})
                for (int o = 0; o < 2; ++o)
                    if (values(id)[i] == cryptomatteId(o == 0 ? "strips" : "wall")) matte[o] += values(coverage)[i];
            // Strip k covers pixel centre x_c while 32 t lies in [x_c + 31 - 2k, x_c + 32 - 2k].
            const int px = int(i % 8), py = int(i / 8);
            const float xc = float(px) + 0.5f;
            float strips = 0.0f;
            for (int k = 0; k < 16; ++k)
                strips += std::max(0.0f, std::min(32.0f, xc + 32.0f - 2.0f * float(k)) - std::max(0.0f, xc + 31.0f - 2.0f * float(k))) / 32.0f;
            EXPECT_NEAR(matte[0], strips, 1e-5f) << i;
            EXPECT_NEAR(matte[1], 1.0f - strips, 1e-5f) << i;
            glm::vec4 flat(0.0f);
            for (const DeepSample& d : image.deep()->samples(px, py)) flat += (1.0f - flat.w) * glm::vec4(d.color, d.alpha);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(flat[c], image.at(px, py)[c], 1e-5f) << i;
        }
    }
    // Within --gpu-memory: 256 bytes a sample, past it refused in one line.
    RenderSettings big;
    big.width = 128, big.height = 64, big.aa = 8, big.passes.depth = true;
    RenderStats stats;
    RenderContext context{stats};
    EXPECT_THROW(createRenderer("motion-path-gl", test::withOption("gpu-memory", "1"))->render(test::sweptWall(), big, context), Error);
}

// Both span texture filters (SpanTextureFilter) agree with the CPU's on a textured scene, and
// differ from each other there: the option reaches the shader. (Not fence: its bars are a
// masked texture, which keeps the taps under either filter.)
TEST(MotionPathGl, EachTextureFilterMatchesTheCpus) {
    for (const char* name : {"rotating-cube"}) {
        const Scene scene = builtin(name);
        std::vector<Image> gls;
        for (const char* filter : {"taps", "swept"}) {
            const Image gl = test::render("motion-path-gl", scene, 96, 72, test::withOption("texture-filter", filter), nullptr, ShadingMode::Phong);
            const Image cpu = test::render("motion-path", scene, 96, 72, cpuTwin(test::withOption("texture-filter", filter)), nullptr,
                                           ShadingMode::Phong);
            EXPECT_GE(psnr(gl, cpu), 80.0) << name << " " << filter;
            gls.push_back(gl);
        }
        EXPECT_LT(psnr(gls[0], gls[1]), 70.0) << name;
    }
}

// shading=pixel on the GPU (motion_path_gl_pixel_shading): the pixel's pieces gathered, sorted,
// cut into the same time clusters and shaded once each as exposure::PixelShading does, so the
// images agree to float rounding and so do the shadings and the distinct triangles counted. On
// textured scenes at --aa 4 in one cell a pixel (the default at --aa 2 to 4; box and lookup
// filters), at --aa 2 (one box of a quarter of the budget), at --aa 8 in 4 x 4 cells of 2 x 2
// samples, and at --aa 1, whose clusters of one piece
// shade as their sample does; rotating-cube's pixels take more clusters than one dispatch shades
// (kClustersPerDispatch), so the later dispatches are tested. twist's still textured backdrop
// shares one shading a pixel, each sample shaded at its own point (Sharing::StillTextured), and
// unlit, crossing's untextured triangles of one colour take one a pixel (Sharing::OneColour).
TEST(MotionPathGl, ShadingPerPixelMatchesTheCpus) {
    struct Case {
        int aa;
        const char* filter;
    };
    for (const char* name : {"rotating-cube", "twist", "translucent"}) {
        const Scene scene = builtin(name);
        for (const Case c : {Case{4, "box"}, Case{4, "lookup"}, Case{8, "box"}, Case{1, "box"}, Case{2, "box"}}) {
            if (c.aa == 8 && std::string(name) == "twist") continue;  // below, with its still lookups
            OptionMap options = test::withOption("shading", "pixel");
            options.set("shading-filter", c.filter);
            RenderStats gpuStats, cpuStats;
            const Image gl = test::render("motion-path-gl", scene, 48, 36, options, &gpuStats, ShadingMode::Phong, c.aa);
            const Image cpu = test::render("motion-path", scene, 48, 36, options, &cpuStats, ShadingMode::Phong, c.aa);
            const std::string what = std::string(name) + " --aa " + std::to_string(c.aa) + " " + c.filter;
            std::printf("%s: gl vs cpu %.1f dB, %g dispatches\n", what.c_str(), psnr(gl, cpu), gpuStats.counter("pixel_shading_dispatches"));
            EXPECT_GE(psnr(gl, cpu), 80.0) << what;
            ASSERT_GT(cpuStats.counter("visible_pieces"), 0.0) << what;
            if (c.aa > 1) { EXPECT_LT(cpuStats.counter("shaded_spans"), cpuStats.counter("visible_pieces")) << what; }  // shared
            if (std::string(name) == "twist") { EXPECT_GT(cpuStats.counter("still_sample_lookups"), 0.0) << what; }  // its still backdrop
            for (const char* counter : {"visible_pieces", "shaded_spans", "visible_triangles_per_pixel", "still_sample_lookups"})
                EXPECT_NEAR(gpuStats.counter(counter), cpuStats.counter(counter), 1e-3 * cpuStats.counter(counter)) << counter << " " << what;
            EXPECT_EQ(gpuStats.counter("piece_overflow_samples"), 0.0) << what;
            EXPECT_EQ(gpuStats.counter("piece_overflow_pixels"), 0.0) << what;
            if (std::string(name) == "rotating-cube" && c.aa == 4) { EXPECT_GT(gpuStats.counter("pixel_shading_dispatches"), 1.0) << what; }
        }
    }
    // (Both twins at shading=pixel, 48 x 36: the images agree.)
    auto renderBoth = [](const char* name, ShadingMode mode, int aa, RenderStats& gpuStats, RenderStats& cpuStats) {
        const Scene scene = builtin(name);
        const OptionMap options = test::withOption("shading", "pixel");
        const Image gl = test::render("motion-path-gl", scene, 48, 36, options, &gpuStats, mode, aa);
        const Image cpu = test::render("motion-path", scene, 48, 36, options, &cpuStats, mode, aa);
        std::printf("%s --aa %d: gl vs cpu %.1f dB\n", name, aa, psnr(gl, cpu));
        EXPECT_GE(psnr(gl, cpu), 80.0) << name;
    };
    // A still cluster is shaded once per piece within one dispatch: at --aa 8 twist's backdrop
    // gives 64 pieces a pixel, and every pixel is still shaded within llvmpipe's 65,535 loop
    // iterations an invocation (an unshaded pixel would cost the PSNR tens of dB).
    {
        RenderStats gpuStats, cpuStats;
        renderBoth("twist", ShadingMode::Phong, 8, gpuStats, cpuStats);
        EXPECT_GT(cpuStats.counter("still_sample_lookups"), 0.0);
        EXPECT_EQ(gpuStats.counter("still_sample_lookups"), cpuStats.counter("still_sample_lookups"));
        EXPECT_EQ(gpuStats.counter("shaded_spans"), cpuStats.counter("shaded_spans"));
    }
    // Unlit, crossing's untextured triangles of one colour take one shading a pixel each,
    // whatever the times their pieces are seen at (Sharing::OneColour), on the GPU as on the CPU.
    {
        RenderStats gpuStats, cpuStats;
        renderBoth("crossing", ShadingMode::Unlit, 4, gpuStats, cpuStats);
        EXPECT_EQ(cpuStats.counter("shaded_spans_per_pixel"), cpuStats.counter("visible_triangles_per_pixel"));
        EXPECT_EQ(gpuStats.counter("shaded_spans"), cpuStats.counter("shaded_spans"));
        EXPECT_NEAR(gpuStats.counter("visible_triangles_per_pixel"), cpuStats.counter("visible_triangles_per_pixel"), 1e-9);
    }
    // The option reaches the shaders: on a textured scene the shared shading is not per-sample's.
    const Scene cube = builtin("rotating-cube");
    const Image perPixel = test::render("motion-path-gl", cube, 48, 36, test::withOption("shading", "pixel"), nullptr, ShadingMode::Phong, 4);
    const Image perSample = test::render("motion-path-gl", cube, 48, 36, test::withOption("shading", "sample"), nullptr, ShadingMode::Phong, 4);
    EXPECT_LT(psnr(perPixel, perSample), 70.0);
}

// A piece pool too small for the frame (--gpu-memory 1): the samples it cannot hold shade their
// own pieces, as shading=sample does, and are counted; the image stays close to the CPU's.
TEST(MotionPathGl, ShadingPerPixelPastThePoolShadesPerSampleAndCounts) {
    const Scene scene = builtin("rotating-cube");
    OptionMap options = test::withOption("shading", "pixel");
    options.set("shading-cells", "2");
    OptionMap small = options;
    small.set("gpu-memory", "1");
    RenderStats stats;
    const Image gl = test::render("motion-path-gl", scene, 48, 36, small, &stats, ShadingMode::Phong, 4);
    const Image cpu = test::render("motion-path", scene, 48, 36, options, nullptr, ShadingMode::Phong, 4);
    EXPECT_GT(stats.counter("piece_overflow_samples"), 0.0);
    EXPECT_GT(stats.counter("piece_capacity"), 0.0);
    std::printf("past the pool: gl vs cpu %.1f dB, %g samples shaded alone\n", psnr(gl, cpu), stats.counter("piece_overflow_samples"));
    EXPECT_GE(psnr(gl, cpu), 35.0);
}

// At --aa powers of two or not: the n-rooks offsets of --aa 3, 5 and 6 took a residue of a
// negative number in GLSL, undefined there and the true one on llvmpipe only for powers of two
// (57 dB apart at --aa 3). And past the pixel pass's pieces (pan at --aa 5 holds 21 such pixels)
// the further pieces are shaded a few per dispatch, where shading them all in the first dispatch
// ended llvmpipe's loops for their whole workgroups (65.6 dB); and a pixel's pieces are sorted in
// n log n steps, where an insertion sort of pan's up to 288 pieces at --aa 6 did the same (41.5 dB).
TEST(MotionPathGl, MatchesCpuWithSubpixelSamples) {
    for (const auto& [name, aa] : {std::pair<const char*, int>{"crossing", 2}, {"crossing", 3}, {"pan", 5}, {"pan", 6}}) {
        const Scene scene = builtin(name);
        RenderStats stats;
        // (pan at 96 x 72: at 64 x 48 no workgroup ran out.)
        const int w = name == std::string("pan") ? 96 : 64, h = w * 3 / 4;
        const Image gl = test::render("motion-path-gl", scene, w, h, OptionMap(), &stats, ShadingMode::Phong, aa);
        const Image cpu = test::render("motion-path", scene, w, h, cpuTwin(), nullptr, ShadingMode::Phong, aa);
        std::printf("%s --aa %d: gl vs cpu %.1f dB, %g pixels past the pixel pass\n", name, aa, psnr(gl, cpu), stats.counter("piece_overflow_pixels"));
        EXPECT_GE(psnr(gl, cpu), 80.0) << name << " --aa " << aa;
    }
}

// An interval budget of 2 keeps each sample's two nearest intervals (by minimum depth) on both,
// and counts the overflow alike. The two triangles of a pane can tie for nearest, and which one
// a tie keeps is not defined (GPU list order is that of atomics), so the images agree less
// closely than at the full budget, though far more than either agrees with the full budget.
TEST(MotionPathGl, KeepsTheNearestIntervalsPastTheBudgetAsTheCpuDoes) {
    const Scene scene = builtin("translucent");
    RenderStats gpuStats, cpuStats;
    const Image gl = test::render("motion-path-gl", scene, 64, 48, test::withOption("max-intervals", "2"), &gpuStats);
    const Image cpu = test::render("motion-path", scene, 64, 48, cpuTwin(test::withOption("max-intervals", "2")), &cpuStats);
    const Image full = test::render("motion-path", scene, 64, 48, cpuTwin());
    EXPECT_GT(gpuStats.counter("interval_overflow_samples"), 0.0);
    EXPECT_EQ(gpuStats.counter("interval_overflow_samples"), cpuStats.counter("interval_overflow_samples"));
    EXPECT_GE(psnr(gl, cpu), 33.0);
    EXPECT_LT(psnr(gl, full), 25.0);
}

// A list buffer too small for the frame is grown and the frame rendered again: the image does
// not change, and the second render is counted.
TEST(MotionPathGl, RendersAgainWhenTheListBufferOverflows) {
    const Scene scene = builtin("fence", test::withOption("travel", "3"));
    RenderStats stats;
    const Image image = test::render("motion-path-gl", scene, 96, 72, OptionMap(), &stats);
    const Image cpu = test::render("motion-path", scene, 96, 72, cpuTwin());
    EXPECT_GE(stats.counter("path_renders"), 2.0);
    EXPECT_GE(psnr(image, cpu), 80.0);
}

// Past the memory cap the buffer stays at the cap and a per-sample budget that it always holds
// applies: refused spans are counted, nothing is written out of bounds, and the image is
// still close to the CPU's (the budget drops the spans past each sample's first few).
TEST(MotionPathGl, PastTheMemoryCapAppliesAPerSampleBudgetAndCountsTheOverflow) {
    const Scene scene = builtin("fence", test::withOption("travel", "3"));
    RenderStats stats;
    const Image capped = test::render("motion-path-gl", scene, 128, 96, test::withOption("gpu-memory", "1"), &stats);
    const Image cpu = test::render("motion-path", scene, 128, 96, cpuTwin());
    const double capNodes = double(1 << 20) / 24.0;
    EXPECT_LE(stats.counter("list_capacity_nodes"), capNodes);
    EXPECT_LT(stats.counter("sample_budget"), 150.0);
    EXPECT_LE(stats.counter("sample_budget") * 128 * 96, capNodes);
    EXPECT_GT(stats.counter("fragment_overflow_spans"), 0.0);
    EXPECT_GE(psnr(capped, cpu), 25.0);
    EXPECT_LT(psnr(capped, cpu), 45.0);
}

// blur-shell-gl draws the CPU's shell with the GPU's blender: the same image, in submission order
// and sorted, on a rigid and a deforming sphere, lit.
class BlurShellGlAgreement : public testing::TestWithParam<std::pair<std::string, std::string>> {};

TEST_P(BlurShellGlAgreement, MatchesCpuBlurShell) {
    const auto& [squash, blend] = GetParam();
    const Scene scene = builtin("sphere", test::withOption("squash", squash));
    RenderStats gpuStats, cpuStats;
    const OptionMap options = test::withOption("blend", blend);
    const Image gl = test::render("blur-shell-gl", scene, 96, 72, options, &gpuStats, ShadingMode::Phong);
    const Image cpu = test::render("blur-shell", scene, 96, 72, options, &cpuStats, ShadingMode::Phong, 1, true);
    EXPECT_GE(psnr(gl, cpu), 58.0);
    EXPECT_GT(cpuStats.counter("shell_triangles"), 100.0);
    EXPECT_EQ(gpuStats.counter("shell_triangles"), cpuStats.counter("shell_triangles"));
    EXPECT_EQ(gpuStats.counter("translucent_layer_overflow_samples"), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Spheres, BlurShellGlAgreement,
                         testing::Values(std::pair{std::string("0"), std::string("ordered")}, std::pair{std::string("0"), std::string("sorted")},
                                         std::pair{std::string("0.4"), std::string("ordered")}));

// Order matters: blended in submission order and sorted, the images differ (the test above
// could not tell them apart otherwise).
TEST(BlurShellGl, OrderedAndSortedBlendingDiffer) {
    const Scene scene = builtin("sphere");
    const Image ordered = test::render("blur-shell-gl", scene, 96, 72, test::withOption("blend", "ordered"), nullptr, ShadingMode::Phong);
    const Image sorted = test::render("blur-shell-gl", scene, 96, 72, test::withOption("blend", "sorted"), nullptr, ShadingMode::Phong);
    EXPECT_LT(psnr(ordered, sorted), 55.0);  // and more than 58 dB from the CPU's twin
}

// post-filter-gl runs the CPU filter's passes as compute shaders, with the CPU's jitter: the
// same image on the grid, from the centre frame to the gather.
class PostFilterGlAgreement : public testing::TestWithParam<std::pair<std::string, int>> {};

TEST_P(PostFilterGlAgreement, MatchesCpuPostFilter) {
    const auto& [name, aa] = GetParam();
    const Scene scene = builtin(name);
    RenderStats stats;
    const Image gl = test::render("post-filter-gl", scene, 96, 72, OptionMap{}, &stats, ShadingMode::Phong, aa);
    const Image cpu = test::render("post-filter", scene, 96, 72, OptionMap{}, nullptr, ShadingMode::Phong, aa, true);
    EXPECT_GE(psnr(gl, cpu), 45.0);
    const Image instant = test::render("accumulation", scene, 96, 72, test::withOption("samples", "1"), nullptr, ShadingMode::Phong, aa, true);
    EXPECT_LT(psnr(cpu, instant), 40.0) << "the filter should blur this scene";
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, PostFilterGlAgreement,
                         testing::Values(std::pair{std::string("rotating-cube"), 1}, std::pair{std::string("fence"), 1},
                                         std::pair{std::string("pan"), 1}, std::pair{std::string("translucent"), 1},
                                         std::pair{std::string("spin"), 2}));

}  // namespace
}  // namespace streak

namespace streak {
namespace {

// fill_rule_methods_test's shared edge on the GL methods: the diagonal of a split square runs
// through sample positions, still and moving along itself (its edge functions there are exact
// zeros at every time), and each such sample is covered once by the top-left rule: opaque, it
// shows the triangle right of the diagonal; translucent, it is blended once. The expected
// pixels are the rule's closed form (test::diagonalSplitPixel).
TEST(GlFillRule, ASharedEdgeThroughSamplesCoversEachOnceStillAndMovingAlongIt) {
    const glm::vec3 upper(0.9f, 0.2f, 0.1f), lower(0.1f, 0.3f, 0.8f);
    constexpr int kSize = 16;
    for (const char* method : {"motion-path-gl", "accumulation-gl", "stochastic-gl"})
        for (const float opacity : {1.0f, 0.5f})
            for (const float d : {0.0f, 3.0f, -5.25f})
                for (const int aa : {1, 2}) {
                    OptionMap options;
                    if (std::string(method) != "motion-path-gl") options.set("samples", "4");
                    const Scene scene = test::diagonalSplitSquare(kSize, -8.0f, 24.0f, d, upper, lower, opacity);
                    const Image image = test::render(method, scene, kSize, kSize, options, nullptr, ShadingMode::Unlit, aa, /*isGridPattern=*/true);
                    int wrong = 0;
                    for (int py = 0; py < kSize; ++py)
                        for (int px = 0; px < kSize; ++px) {
                            const glm::vec3 expected = test::diagonalSplitPixel(px, py, aa, upper, lower, opacity);
                            for (int c = 0; c < 3; ++c) wrong += std::abs(image.at(px, py)[c] - expected[c]) > 1e-5f;
                        }
                    EXPECT_EQ(wrong, 0) << method << " opacity " << opacity << " d " << d << " aa " << aa;
                }
}

}  // namespace
}  // namespace streak
