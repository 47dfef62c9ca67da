// The occlusion cull (exposure::cullHiddenIntervals) in the methods that resolve exposure
// intervals: dropping what no resolve can show leaves every image as it was, to rounding.

#include "image/metrics.h"
#include "scene/builtin_scenes.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace streak {

namespace {

// Every built-in scene, the dense ones made lighter, with its name.
std::vector<std::pair<std::string, Scene>> lightBuiltinScenes() {
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const std::string name(info.name);
        OptionMap sceneOptions;
        if (name == "cubes") sceneOptions.set("n", "150");
        if (name == "sphere") sceneOptions.set("triangles", "2000");
        Scene scene = makeBuiltinScene(name, sceneOptions);
        validateScene(scene);
        scenes.emplace_back(name, std::move(scene));
    }
    return scenes;
}

bool sameBits(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin()) &&
           std::equal(a.alpha().begin(), a.alpha().end(), b.alpha().begin());
}

// A quad 4 high from x0 to x1 at height z, its corners at the shutter's open and at its close,
// `shift` further along x.
std::pair<std::array<glm::vec3, 4>, std::array<glm::vec3, 4>> slidingQuad(float x0, float x1, float z, float shift) {
    std::array<glm::vec3, 4> open{glm::vec3(x0, 2, z), glm::vec3(x0, -2, z), glm::vec3(x1, -2, z), glm::vec3(x1, 2, z)}, close = open;
    for (glm::vec3& p : close) p.x += shift;
    return {open, close};
}

// The methods with the early cull (`early-cull`).
constexpr std::array<const char*, 2> kEarlyCullMethods{"analytic", "motion-path"};

// A method at 32 x 24 --aa 3 unlit with and without the early cull: the same bits, and it hid
// samples. Returns the image.
Image renderWithAndWithoutEarlyCull(const char* method, const Scene& scene) {
    SCOPED_TRACE(method);
    RenderStats stats;
    const Image with = test::render(method, scene, 32, 24, OptionMap(), &stats, ShadingMode::Unlit, 3);
    const Image without = test::render(method, scene, 32, 24, test::withOption("early-cull", "0"), nullptr, ShadingMode::Unlit, 3);
    EXPECT_TRUE(sameBits(with, without));
    EXPECT_GT(stats.counter("samples_hidden_before_solving"), 0.0);
    return with;
}

}  // namespace

TEST(OcclusionCull, EveryBuiltinSceneRendersAsWithoutIt) {
    double culled = 0.0;
    for (const auto& [name, scene] : lightBuiltinScenes()) {
        for (const char* method : {"analytic", "higher-order"}) {
            SCOPED_TRACE(name + " " + method);
            RenderStats stats;
            const Image with = test::render(method, scene, 64, 48, OptionMap(), &stats, ShadingMode::Phong);
            const Image without = test::render(method, scene, 64, 48, test::withOption("occlusion-cull", "0"), nullptr, ShadingMode::Phong);
            EXPECT_GE(psnr(with, without), 60.0);
            culled += stats.counter("hidden_intervals_culled");
        }
    }
    EXPECT_GT(culled, 0.0);  // the scenes do hide intervals: the cull ran
}

TEST(OcclusionCull, TheEarlyCullLeavesEveryBitAsItWas) {
    // analytic does not solve a segment at a sample, nor motion-path build a path's interval
    // there, where an opaque triangle drawn before it covers the sample all the shutter from
    // nearer than the segment's nearest corner: no resolve gives such an interval a share, so
    // every image is the one without the early cull, to the bit, on every built-in scene at
    // --aa 2 (lit) and on a stack of quads where a translucent one is drawn first (it hides
    // nothing: counted as an occluder, the opaque quad behind it would vanish) and a moving
    // opaque one hides the one behind it for part of the shutter.
    for (const char* method : kEarlyCullMethods) {
        double hidden = 0.0;
        for (const auto& [name, scene] : lightBuiltinScenes()) {
            SCOPED_TRACE(name + " " + method);
            RenderStats stats;
            const Image with = test::render(method, scene, 64, 48, OptionMap(), &stats, ShadingMode::Phong, 2);
            const Image without = test::render(method, scene, 64, 48, test::withOption("early-cull", "0"), nullptr, ShadingMode::Phong, 2);
            EXPECT_TRUE(sameBits(with, without));
            hidden += stats.counter("samples_hidden_before_solving");
        }
        EXPECT_GT(hidden, 0.0) << method;  // the scenes do hide segments early: the cull ran
    }

    Scene scene = test::emptyScene();
    const std::uint32_t glass = test::addMaterial(scene, glm::vec3(0.2f, 0.4f, 1.0f), 0.5f);
    const std::uint32_t red = test::addMaterial(scene, glm::vec3(1, 0, 0)), green = test::addMaterial(scene, glm::vec3(0, 1, 0));
    const std::uint32_t blue = test::addMaterial(scene, glm::vec3(0, 0, 1));
    for (const auto& [material, q] : {std::pair{glass, slidingQuad(-6, 6, -3, 0)}, std::pair{red, slidingQuad(-6, 0.5f, -4, 0)},
                                      std::pair{green, slidingQuad(-8, 8, -5, 0)}, std::pair{blue, slidingQuad(-1, 1, -4.5f, 2)}})
        test::addMovingQuad(scene, material, q.first, q.second);
    validateScene(scene);
    for (const char* method : kEarlyCullMethods) {
        const Image with = renderWithAndWithoutEarlyCull(method, scene);
        // Through the glass, the red quad on the left, the green one on the right.
        EXPECT_GT(with.at(10, 12).x, 0.4f);
        EXPECT_GT(with.at(24, 12).y, 0.4f);
    }
}

TEST(OcclusionCull, NearestFirstSoWhatIsDrawnBeforeItsOccluderIsHiddenToo) {
    // A quad moving between two still ones, then the far still one, then the near one that
    // hides the middle of both. Drawn in the mesh's order, nothing would be covered when the
    // others are drawn; nearest first, the near quad is, and what lies behind it is not
    // solved (pixels whose every sample is covered are not even visited). The samples' lists
    // go back to the mesh's order for the resolve, so the image keeps its bits.
    Scene scene = test::emptyScene();
    const std::uint32_t red = test::addMaterial(scene, glm::vec3(1, 0, 0)), green = test::addMaterial(scene, glm::vec3(0, 1, 0));
    const std::uint32_t blue = test::addMaterial(scene, glm::vec3(0, 0, 1));
    for (const auto& [material, q] : {std::pair{blue, slidingQuad(-3, -2, -5, 4)}, std::pair{green, slidingQuad(-8, 8, -6, 0)}, std::pair{red, slidingQuad(-2, 2, -4, 0)}})
        test::addMovingQuad(scene, material, q.first, q.second);
    validateScene(scene);
    for (const char* method : kEarlyCullMethods) {
        const Image with = renderWithAndWithoutEarlyCull(method, scene);
        EXPECT_GT(with.at(16, 12).x, 0.5f);  // the near quad in the middle
        EXPECT_GT(with.at(2, 12).y, 0.9f);   // the far one at the side
    }
}

TEST(OcclusionCull, AStillTriangleInAKeyedSceneCoversTheShutterToo) {
    // Five keys: a quad moving along a zigzag (a kink at each key), far; a still one, near, in
    // the middle of it. The near quad's segments merge into one over the whole shutter
    // (SegmentedGeometry), so it covers its samples all the shutter and what lies behind it is
    // not solved, in a scene that is cut into four segments: the same bits as without the early
    // cull, the near quad shown whole in its middle, the far one at the side.
    Scene scene = test::emptyScene();
    const std::uint32_t red = test::addMaterial(scene, glm::vec3(1, 0, 0)), green = test::addMaterial(scene, glm::vec3(0, 1, 0));
    auto addKeyedQuad = [&](std::uint32_t material, float x0, float x1, float z, std::array<float, 5> shifts) {
        Mesh mesh;
        mesh.material = material;
        mesh.numKeys = 5;
        for (const float shift : shifts)
            for (const glm::vec3& p : slidingQuad(x0 + shift, x1 + shift, z, 0.0f).first) mesh.positions.push_back(p);
        mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
        scene.meshes.push_back(mesh);
    };
    addKeyedQuad(green, -8, 8, -6, {0.0f, 1.0f, 0.0f, 1.0f, 0.0f});
    addKeyedQuad(red, -2, 2, -4, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f});
    validateScene(scene);
    for (const char* method : kEarlyCullMethods) {
        const Image with = renderWithAndWithoutEarlyCull(method, scene);
        EXPECT_NEAR(with.at(16, 12).x, 1.0f, 1e-6f);  // the near quad in the middle
        EXPECT_NEAR(with.at(2, 12).y, 1.0f, 1e-6f);   // the far one at the side
    }
}

TEST(OcclusionCull, AMovingSurfaceCoversASampleWithItsTrianglesInTurn) {
    // A strip of two quads (one mesh, shared corners) sliding by its own width in front of a far
    // still quad: no triangle of the strip covers a sample all the shutter, but between its ends
    // the strip does, one quad after the other. analytic keeps the union of a mesh's opaque
    // intervals at a sample (EarlyCull::coverStretch, pieces of at least kShortestStretch), so
    // the far quad is not solved there: samples hidden, the same bits as without the early cull.
    Scene scene = test::emptyScene();
    const std::uint32_t red = test::addMaterial(scene, glm::vec3(1, 0, 0)), green = test::addMaterial(scene, glm::vec3(0, 1, 0));
    Mesh strip;
    strip.material = red;
    strip.numKeys = 2;
    for (const float shift : {0.0f, 2.0f})
        for (const glm::vec2 p : {glm::vec2(-2, 2), glm::vec2(-2, -2), glm::vec2(0, -2), glm::vec2(0, 2), glm::vec2(2, -2), glm::vec2(2, 2)})
            strip.positions.push_back(glm::vec3(p.x + shift, p.y, -4.0f));
    strip.triangles = {{0, 1, 2}, {0, 2, 3}, {3, 2, 4}, {3, 4, 5}};
    scene.meshes.push_back(strip);
    test::addMovingQuad(scene, green, slidingQuad(-8, 8, -6, 0).first, slidingQuad(-8, 8, -6, 0).second);
    validateScene(scene);
    RenderStats stats;
    const Image with = test::render("analytic", scene, 32, 24, OptionMap(), &stats, ShadingMode::Unlit, 3);
    const Image without = test::render("analytic", scene, 32, 24, test::withOption("early-cull", "0"), nullptr, ShadingMode::Unlit, 3);
    EXPECT_TRUE(sameBits(with, without));
    EXPECT_GT(stats.counter("samples_hidden_before_solving"), 0.0);
    int wholeRed = 0;  // pixels the strip covers all the shutter: red, no green
    for (int x = 0; x < 32; ++x) wholeRed += with.at(x, 12).x > 0.9999f && with.at(x, 12).y < 1e-4f;
    EXPECT_GT(wholeRed, 2);
}

TEST(OcclusionCull, AClosedDoubleSidedMeshDropsItsBackFacesAndEveryPixelItMovesGoesToTheReference) {
    // The built-in rotating cube and a field of moving, turning textured cubes, made
    // double-sided: each cube is a closed surface (exposure/closed_surfaces.h), whose faces
    // turned away are hidden by those turned towards the eye, so analytic and motion-path drop
    // them before any sample sees them (closed-cull, the default); they are counted, and none
    // are without it. The one cube renders as it does with both sides drawn, to rounding. Among
    // the many, a few pixels move: there the resolve, which takes depth along an interval as
    // linear, put a turning cube's back face in front of its front face for part of the
    // shutter. Every pixel that moves must move towards accumulation of 256 instants (an
    // independent method, each instant rasterized with both sides drawn), and by more than that
    // reference's own error.
    for (const std::string name : {"rotating-cube", "cubes"}) {
        OptionMap options;
        if (name == "cubes") options.set("n", "150");
        Scene scene = makeBuiltinScene(name, options);
        for (Material& material : scene.materials) material.doubleSided = true;
        validateScene(scene);
        const Image reference = test::render("accumulation", scene, 64, 48, test::withOption("samples", "256"), nullptr, ShadingMode::Phong, 3);
        for (const char* method : kEarlyCullMethods) {
            SCOPED_TRACE(name + " " + method);
            RenderStats culled, kept;
            const Image with = test::render(method, scene, 64, 48, OptionMap(), &culled, ShadingMode::Phong, 3);
            const Image without = test::render(method, scene, 64, 48, test::withOption("closed-cull", "0"), &kept, ShadingMode::Phong, 3);
            EXPECT_GT(culled.counter("closed_surfaces"), 0.0);
            const std::string skipped = std::string(method) == "analytic" ? "backfacing_segments_skipped" : "backfacing_paths_skipped";
            EXPECT_GT(culled.counter(skipped), 0.0);
            EXPECT_EQ(kept.counter("closed_surfaces"), 0.0);
            EXPECT_EQ(kept.counter(skipped), 0.0);
            if (name == "rotating-cube") {
                EXPECT_GE(psnr(with, without), 100.0);
            }
            int moved = 0;
            for (int y = 0; y < with.height(); ++y)
                for (int x = 0; x < with.width(); ++x) {
                    const float change = glm::length(with.at(x, y) - without.at(x, y));
                    if (change <= 1e-4f) continue;
                    ++moved;
                    const float errorWith = glm::length(with.at(x, y) - reference.at(x, y));
                    const float errorWithout = glm::length(without.at(x, y) - reference.at(x, y));
                    EXPECT_LT(errorWith, 0.5f * errorWithout) << x << ", " << y;
                }
            EXPECT_LE(moved, 8);
        }
    }
}

}  // namespace streak
