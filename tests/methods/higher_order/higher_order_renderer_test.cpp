// The higher-order renderer against the true curved motion (accumulation over 64 keys), against
// analytic on linear keys, and its traversals against each other.

#include "image/metrics.h"
#include "methods/registry.h"
#include "scene/builtin_scenes.h"
#include "support/render.h"
#include "support/test_scenes.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <iostream>

namespace streak {

using test::render;
using test::withOption;

namespace {

Scene curvedScene(const std::string& name, int keys, const std::string& curve) {
    OptionMap options;
    options.set("keys", std::to_string(keys));
    options.set("curve", curve);
    Scene scene = makeBuiltinScene(name, options);
    validateScene(scene);
    return scene;
}

}  // namespace

TEST(HigherOrderRenderer, FollowsCurvedMotionWhereLinearKeysCannot) {
    // spin turns by 120 degrees: against the true motion (64 linear keys, accumulated at 512
    // times), analytic on 3 linear keys skews the shapes; higher-order on the quadratic through
    // the same 3 poses follows the arcs (bench/higher_order_bench.py has the full-size figures).
    const Scene truth = curvedScene("spin", 64, "linear");
    const Image reference = render("accumulation", truth, 96, 72, withOption("samples", "512"), nullptr, ShadingMode::Unlit, 2);
    const double linear = psnr(render("analytic", curvedScene("spin", 3, "linear"), 96, 72, OptionMap(), nullptr, ShadingMode::Unlit, 2), reference);
    const double quadratic = psnr(render("higher-order", curvedScene("spin", 3, "bezier"), 96, 72, OptionMap(), nullptr, ShadingMode::Unlit, 2), reference);
    const double cubic = psnr(render("higher-order", curvedScene("spin", 4, "bezier"), 96, 72, OptionMap(), nullptr, ShadingMode::Unlit, 2), reference);
    EXPECT_GT(quadratic, linear + 6.0) << "linear " << linear << " quadratic " << quadratic;
    std::cout << "spin at 96x72: analytic 3 linear keys " << linear << " dB, higher-order n=2 " << quadratic << " dB, n=3 " << cubic << " dB\n";
    EXPECT_GT(cubic, quadratic) << "quadratic " << quadratic << " cubic " << cubic;
    EXPECT_GT(cubic, 35.0);
}

TEST(HigherOrderRenderer, OnLinearKeysItIsAnalytic) {
    // Order 1 hands the edge equations to MovingTriangle, and resolve and shading are shared:
    // only the shading's surface point is computed another way (corners at t rather than the
    // segment's quadratics), so the images agree to float rounding. Without refined depth, as
    // analytic has none.
    for (const char* name : {"rotating-cube", "crossing", "twist", "translucent"}) {
        SCOPED_TRACE(name);
        Scene scene = makeBuiltinScene(name, OptionMap());
        validateScene(scene);
        const Image higher = render("higher-order", scene, 64, 48, withOption("depth-tolerance", "0"), nullptr, ShadingMode::Phong);
        const Image analytic = render("analytic", scene, 64, 48, OptionMap(), nullptr, ShadingMode::Phong);
        EXPECT_GT(psnr(higher, analytic), 80.0);
    }
}

TEST(HigherOrderRenderer, FitsTheCurvedPathsOfAMovingCamera) {
    // pan: a static scene, the camera sliding and turning. Each vertex's clip-space path is
    // fitted by the cubic through four times of it; against 1024 accumulated times, as
    // analytic's own test of the built-in scenes asks (42 dB at this size).
    Scene scene = makeBuiltinScene("pan", OptionMap());
    validateScene(scene);
    RenderStats stats;
    const Image higher = render("higher-order", scene, 96, 72, OptionMap(), &stats, ShadingMode::Phong);
    EXPECT_EQ(stats.counter("motion_fitted"), 1.0);
    EXPECT_EQ(stats.counter("motion_order"), 3.0);
    EXPECT_GT(psnr(higher, render("accumulation", scene, 96, 72, withOption("samples", "1024"), nullptr, ShadingMode::Phong)), 42.0);
}

TEST(HigherOrderRenderer, IntervalAndTileTraversalLeaveTheImageBitIdentical) {
    // Generalized INTERVAL skips pixels no sub-interval's box reaches, TILE blocks its slefes
    // prove missed: the spans found are the same, so the image is too; and each tests fewer
    // samples than the bounding box.
    for (const char* name : {"spin", "clothball"}) {
        SCOPED_TRACE(name);
        const Scene scene = curvedScene(name, 3, "bezier");
        RenderStats box;
        const Image a = render("higher-order", scene, 80, 60, withOption("traversal", "bbox"), &box);
        OptionMap sixteen = withOption("traversal", "interval"), tile = withOption("traversal", "tile");
        sixteen.set("intervals", "16");
        for (const char* t : {"1", "4"}) {
            tile.set("tile", t);
            for (const auto& [options, isTile] : {std::pair{sixteen, false}, std::pair{tile, true}}) {
                RenderStats culled;
                const Image b = render("higher-order", scene, 80, 60, options, &culled);
                for (int y = 0; y < 60; ++y)
                    for (int x = 0; x < 80; ++x) ASSERT_EQ(a.at(x, y), b.at(x, y)) << x << "," << y;
                EXPECT_LT(culled.counter("coverage_tests"), box.counter("coverage_tests"));
                if (isTile) {
                    EXPECT_GT(culled.counter("tile_time_culled_fraction"), 0.0);
                    EXPECT_GT(culled.counter("tiles_culled_by_triangle_test"), 0.0);
                }
                EXPECT_GT(culled.counter("sample_test_efficiency"), box.counter("sample_test_efficiency"));
            }
        }
    }
}

TEST(HigherOrderRenderer, BothRootSolversGiveTheSameImage) {
    const Scene scene = curvedScene("clothball", 3, "bezier");
    const Image a = render("higher-order", scene, 64, 48, withOption("solver", "closed-form"));
    const Image b = render("higher-order", scene, 64, 48, withOption("solver", "clipping"));
    EXPECT_GT(psnr(a, b), 70.0);
}

TEST(HigherOrderRenderer, ResolvedVisibilityMatchesBruteForceAtExactTimes) {
    // The paper's visibility accuracy (97.4 - 99.6% on its scenes): the nearest resolved
    // interval at a random time is the triangle nearest at that exact time.
    for (const char* name : {"spin", "clothball"}) {
        SCOPED_TRACE(name);
        RenderStats stats;
        render("higher-order", curvedScene(name, 3, "bezier"), 64, 48, withOption("check-visibility", "4000"), &stats);
        EXPECT_GT(stats.counter("visibility_accuracy"), 0.99);
    }
}

TEST(HigherOrderRenderer, RejectsWhatItCannotDo) {
    EXPECT_THROW(createRenderer("higher-order", withOption("traversal", "tiles")), Error);
    EXPECT_THROW(createRenderer("higher-order", withOption("tile", "3")), Error);
    EXPECT_THROW(createRenderer("higher-order", withOption("solver", "newton")), Error);
    // Bezier keys of order 4 (five control points): above the order the edge equations take.
    Scene scene = curvedScene("spin", 3, "bezier");
    for (Mesh& mesh : scene.meshes) {
        if (mesh.interpolation != MotionInterpolation::Bezier) continue;
        const std::size_t n = mesh.numVertices();
        for (int k = 0; k < 2; ++k) {
            mesh.positions.insert(mesh.positions.end(), mesh.positions.end() - std::ptrdiff_t(n), mesh.positions.end());
            mesh.normals.insert(mesh.normals.end(), mesh.normals.end() - std::ptrdiff_t(n), mesh.normals.end());
        }
        mesh.numKeys += 2;
    }
    validateScene(scene);
    EXPECT_THROW(render("higher-order", scene, 16, 12, OptionMap()), Error);
}

}  // namespace streak
