#include "exposure/segmented_geometry.h"
#include "support/test_scenes.h"
#include "util/random.h"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace streak::exposure {

namespace {

void expectNear(const glm::vec3& a, const glm::vec3& b, const char* what) {
    EXPECT_NEAR(a.x, b.x, 1e-6f) << what;
    EXPECT_NEAR(a.y, b.y, 1e-6f) << what;
    EXPECT_NEAR(a.z, b.z, 1e-6f) << what;
}

}  // namespace

TEST(SegmentedGeometry, CornersAreEachMeshsVerticesAtTheSegmentEnds) {
    // Two quads moving linearly in world space under a moving and turning camera, so each
    // triangle's motion is cut into curveSegments = 4 segments. Segment s of a triangle spans [s/4, (s+1)/4]; its
    // world corners must be that triangle's own vertices at those times (the closed form
    // open + t (close - open)), and its normals the mesh's normals there, also for the second
    // mesh, whose vertices come after the first's in the flat geometry.
    Scene scene = test::emptyScene();
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    const std::array<glm::vec3, 4> openA{glm::vec3(-1, 1, -4), glm::vec3(-1, -1, -4), glm::vec3(1, -1, -4), glm::vec3(1, 1, -4)};
    std::array<glm::vec3, 4> closeA = openA, openB = openA, closeB = openA;
    for (glm::vec3& p : closeA) p += glm::vec3(1.0f, 0.0f, 0.0f);
    for (glm::vec3& p : openB) p += glm::vec3(0.0f, 3.0f, -2.0f);
    for (glm::vec3& p : closeB) p += glm::vec3(0.0f, 1.0f, -1.0f);
    test::addMovingQuad(scene, m, openA, closeA);
    test::addMovingQuad(scene, m, openB, closeB);
    // The second mesh turns its normal from +z to +x over the shutter (per key, linearly).
    scene.meshes[1].normals = std::vector<glm::vec3>(4, glm::vec3(0, 0, 1));
    scene.meshes[1].normals.resize(8, glm::vec3(1, 0, 0));
    scene.camera.close.position = glm::vec3(0.5f, 0.0f, 0.0f);
    scene.camera.close.worldFromCamera = glm::angleAxis(0.1f, glm::vec3(0.0f, 1.0f, 0.0f));
    validateScene(scene);

    const SegmentedGeometry geometry(scene, raster::Viewport{640, 480}, 4);
    ASSERT_EQ(geometry.numSegments(), 4);
    ASSERT_EQ(geometry.flat().triangles().size(), 4u);
    for (std::uint32_t tri = 0; tri < 4; ++tri) {
        const bool isB = tri >= 2;
        const Mesh& mesh = scene.meshes[isB ? 1 : 0];
        const glm::uvec3 v = mesh.triangles[tri % 2];
        for (int s = 0; s < 4; ++s) {
            const TriangleSegment& segment = geometry.segment(tri, s);
            const SegmentedGeometry::WorldCorners c = geometry.cornersOf(segment);
            const float ta = float(s) / 4.0f, tb = float(s + 1) / 4.0f;
            for (int i = 0; i < 3; ++i) {
                const glm::vec3 open = mesh.positions[v[i]], close = mesh.positions[4 + v[i]];
                expectNear(c.world0[i], open + ta * (close - open), "world corner at the segment's start");
                expectNear(c.world1[i], open + tb * (close - open), "world corner at the segment's end");
                const glm::vec3 n0 = isB ? glm::mix(glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), ta) : glm::vec3(0.0f);
                const glm::vec3 n1 = isB ? glm::mix(glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), tb) : glm::vec3(0.0f);
                expectNear(c.normal0[i], n0, "normal at the segment's start (zero without normals)");
                expectNear(c.normal1[i], n1, "normal at the segment's end");
                // The clip-space corners are the same vertices seen by the camera at those times.
                const glm::vec4 clip0 = scene.camera.clipFromWorld(ta, 4.0f / 3.0f) * glm::vec4(c.world0[i], 1.0f);
                const glm::vec4 clip1 = scene.camera.clipFromWorld(tb, 4.0f / 3.0f) * glm::vec4(c.world1[i], 1.0f);
                for (int j = 0; j < 4; ++j) {
                    EXPECT_NEAR(segment.clip0[i][j], clip0[j], 1e-5f);
                    EXPECT_NEAR(segment.clip1[i][j], clip1[j], 1e-5f);
                }
            }
        }
    }
}

// A camera that moves without turning (a truck and a dolly at once) keeps linear motion linear
// in clip space, so each key segment stays one segment: the clip corners of a moving quad at
// any time are the segment ends' mix, to float rounding. A turning camera takes curveSegments.
TEST(SegmentedGeometry, ACameraMovingWithoutTurningKeepsOneSegmentPerKey) {
    Scene scene = test::emptyScene();
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    const std::array<glm::vec3, 4> open{glm::vec3(-1, 1, -4), glm::vec3(-1, -1, -5), glm::vec3(1, -1, -4), glm::vec3(1, 1, -3)};
    std::array<glm::vec3, 4> close = open;
    for (glm::vec3& p : close) p += glm::vec3(0.7f, -0.2f, 0.5f);
    test::addMovingQuad(scene, m, open, close);
    scene.camera.open.position = glm::vec3(0.0f, 0.0f, 0.0f);
    scene.camera.close.position = glm::vec3(0.6f, 0.3f, -0.8f);
    validateScene(scene);
    ASSERT_FALSE(scene.camera.isTurning());
    const float aspect = 4.0f / 3.0f;
    const SegmentedGeometry geometry(scene, raster::Viewport{640, 480}, 4);
    ASSERT_EQ(geometry.numSegments(), 1);
    const Mesh& mesh = scene.meshes[0];
    for (std::uint32_t tri = 0; tri < 2; ++tri) {
        const TriangleSegment& segment = geometry.segment(tri, 0);
        const glm::uvec3 v = mesh.triangles[tri];
        for (const float t : {0.2f, 0.5f, 0.9f}) {
            for (int i = 0; i < 3; ++i) {
                const glm::vec3 world = glm::mix(mesh.positions[v[i]], mesh.positions[4 + v[i]], t);
                const glm::vec4 exact = scene.camera.clipFromWorld(t, aspect) * glm::vec4(world, 1.0f);
                const glm::vec4 mixed = glm::mix(segment.clip0[i], segment.clip1[i], t);
                for (int j = 0; j < 4; ++j) EXPECT_NEAR(mixed[j], exact[j], 2e-5f) << "corner " << i << " at t = " << t;
            }
        }
    }
    // The same camera turning a little: the projection is no longer linear in t.
    scene.camera.close.worldFromCamera = glm::angleAxis(0.05f, glm::vec3(0.0f, 1.0f, 0.0f));
    ASSERT_TRUE(scene.camera.isTurning());
    EXPECT_EQ(SegmentedGeometry::plan(scene, 4, raster::Viewport{640, 480}).numSegments, 4);
}

// A static quad under a camera that moves and turns 0.6 radians: by default the shutter is cut
// into as many pieces (1, 2, 4 ...) as keep the vertices within kCurveTolerancePixels of their
// true screen paths. Checked here against the camera itself at random times, not at the piece
// middles the choice probes: every corner of every piece stays within 1.5 times the tolerance of
// its exact projection, and half as many pieces would stray past the tolerance.
TEST(SegmentedGeometry, ATurningCameraIsCutUntilTheScreenPathsAreWithinTheTolerance) {
    Scene scene = test::emptyScene();
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    const std::array<glm::vec3, 4> quad{glm::vec3(-2, 2, -5), glm::vec3(-2, -2, -6), glm::vec3(2, -2, -5), glm::vec3(2, 2, -4)};
    test::addMovingQuad(scene, m, quad, quad);
    scene.camera.close.position = glm::vec3(0.4f, 0.1f, 0.2f);
    scene.camera.close.worldFromCamera = glm::angleAxis(0.6f, glm::vec3(0.0f, 1.0f, 0.0f));
    validateScene(scene);
    const raster::Viewport viewport{320, 240};
    const float aspect = 4.0f / 3.0f;
    const double pixelsPerNdc = 0.5 * viewport.height;

    // The largest distance, in pixels, between a piece's linear corners and the exact projection.
    Rng rng(5);
    auto worstStray = [&](const SegmentedGeometry& geometry) {
        double worst = 0.0;
        const Mesh& mesh = scene.meshes[0];
        for (int i = 0; i < 200; ++i) {
            const float t = rng.uniform(0.0f, 1.0f);
            const glm::mat4 clipFromWorld = scene.camera.clipFromWorld(t, aspect);
            for (std::uint32_t tri = 0; tri < 2; ++tri) {
                const TriangleSegment& segment = geometry.segmentAt(tri, t);
                const float u = float(segment.localTime(t));
                for (int c = 0; c < 3; ++c) {
                    const glm::vec4 exact = clipFromWorld * glm::vec4(mesh.positions[mesh.triangles[tri][c]], 1.0f);
                    const glm::vec4 linear = glm::mix(segment.clip0[c], segment.clip1[c], u);
                    const glm::dvec2 d = (glm::dvec2(linear) / double(linear.w) - glm::dvec2(exact) / double(exact.w)) * pixelsPerNdc;
                    worst = std::max(worst, std::hypot(d.x * aspect, d.y));
                }
            }
        }
        return worst;
    };

    const SegmentedGeometry chosen(scene, viewport, SegmentedGeometry::kAutoCurveSegments);
    const SegmentedGeometry::SegmentPlan& plan = chosen.segmentPlan();
    EXPECT_GE(plan.piecesPerKey, 8);  // the 4 fixed pieces of before were not enough for this turn
    EXPECT_EQ(chosen.numSegments(), plan.piecesPerKey);
    EXPECT_LE(plan.deviationPixels, SegmentedGeometry::kCurveTolerancePixels);
    EXPECT_LE(worstStray(chosen), 1.5 * SegmentedGeometry::kCurveTolerancePixels);
    const SegmentedGeometry half(scene, viewport, plan.piecesPerKey / 2);
    EXPECT_EQ(half.segmentPlan().deviationPixels, -1.0);  // a fixed count measures nothing
    EXPECT_GT(worstStray(half), SegmentedGeometry::kCurveTolerancePixels);

    // A camera that moves without turning keeps one piece per key segment, unmeasured.
    scene.camera.close.worldFromCamera = scene.camera.open.worldFromCamera;
    const SegmentedGeometry::SegmentPlan straight = SegmentedGeometry::plan(scene, SegmentedGeometry::kAutoCurveSegments, viewport);
    EXPECT_EQ(straight.numSegments, 1);
    EXPECT_EQ(straight.deviationPixels, -1.0);
}

}  // namespace streak::exposure

namespace streak::exposure {

// One mesh of 5 keys (4 segments) and three quads: A still over the first half and moving at one
// velocity over the second, B moving at one velocity until key 3 and at another after it, C
// still throughout. A triangle's segments merge where its motion goes on along one line at one
// pace: A into [0, 1/2] and [1/2, 1], B into [0, 3/4] and [3/4, 1], C into [0, 1]. The merged
// segment's corners, mixed linearly as the methods mix them, are the exact projections of the
// piecewise motion at every time; a merged-away slot has no screen box, and the segment at any
// time of its run is the run's first slot, with the world corners of the run's ends.
TEST(SegmentedGeometry, ATrianglesSegmentsMergeWhereItsMotionGoesOnAlongOneLine) {
    Scene scene = test::emptyScene();
    Mesh mesh;
    mesh.material = test::addMaterial(scene, glm::vec3(1.0f));
    mesh.numKeys = 5;
    const std::array<glm::vec3, 4> quad{glm::vec3(-1, 1, 0), glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(1, 1, 0)};
    const std::array<glm::vec3, 3> at{glm::vec3(-3, 0, -8), glm::vec3(0, 0, -9), glm::vec3(3, 1, -10)};
    // Where each quad's centre is at key k.
    auto centre = [&](int q, int k) {
        if (q == 0) return at[0] + float(std::max(k - 2, 0)) * glm::vec3(0.3f, 0.2f, -0.1f);
        if (q == 1) return at[1] + float(std::min(k, 3)) * glm::vec3(0.25f, -0.1f, 0.0f) + float(std::max(k - 3, 0)) * glm::vec3(-0.2f, 0.3f, 0.1f);
        return at[2];
    };
    for (int k = 0; k < 5; ++k)
        for (int q = 0; q < 3; ++q)
            for (const glm::vec3& p : quad) mesh.positions.push_back(centre(q, k) + p);
    for (std::uint32_t q = 0; q < 3; ++q) {
        mesh.triangles.push_back({4 * q, 4 * q + 1, 4 * q + 2});
        mesh.triangles.push_back({4 * q, 4 * q + 2, 4 * q + 3});
    }
    scene.meshes.push_back(mesh);
    validateScene(scene);
    const float aspect = 4.0f / 3.0f;
    const raster::Viewport viewport{640, 480};

    const SegmentedGeometry unmerged(scene, viewport, 1, 0.0);
    ASSERT_EQ(unmerged.numSegments(), 4);
    EXPECT_EQ(unmerged.numMergedAway(), 0);
    EXPECT_FALSE(unmerged.hasWholeShutterSegments());

    const SegmentedGeometry geometry(scene, viewport, 1);
    ASSERT_EQ(geometry.numSegments(), 4);
    EXPECT_EQ(geometry.numMergedAway(), 2 * (2 + 2 + 3));
    EXPECT_TRUE(geometry.hasWholeShutterSegments());
    const auto bounds = geometry.screenBounds(viewport);
    const std::array<std::vector<std::pair<int, int>>, 3> runs{std::vector<std::pair<int, int>>{{0, 2}, {2, 4}}, {{0, 3}, {3, 4}}, {{0, 4}}};
    for (std::uint32_t tri = 0; tri < 6; ++tri) {
        const int q = int(tri / 2);
        const glm::uvec3 v = scene.meshes[0].triangles[tri];
        for (const auto& [key0, key1] : runs[std::size_t(q)]) {
            const TriangleSegment& head = geometry.segment(tri, key0);
            EXPECT_EQ(head.key0, key0) << "quad " << q;
            EXPECT_EQ(head.key1, key1) << "quad " << q;
            EXPECT_EQ(head.t0, float(key0) / 4.0f);
            EXPECT_EQ(head.t1, float(key1) / 4.0f);
            const std::size_t headIndex = std::size_t(tri) * 4 + std::size_t(key0);
            EXPECT_FALSE(geometry.isMergedAway(headIndex));
            EXPECT_FALSE(bounds[headIndex].empty());
            for (int s = key0 + 1; s < key1; ++s) {
                EXPECT_TRUE(geometry.isMergedAway(headIndex + std::size_t(s - key0)));
                EXPECT_TRUE(bounds[headIndex + std::size_t(s - key0)].empty()) << "a merged-away slot is never binned";
            }
            const SegmentedGeometry::WorldCorners corners = geometry.cornersOf(head);
            for (int i = 0; i < 3; ++i) {
                expectNear(corners.world0[i], scene.meshes[0].positions[std::size_t(key0) * 12 + v[i]], "world corner at the run's start");
                expectNear(corners.world1[i], scene.meshes[0].positions[std::size_t(key1) * 12 + v[i]], "world corner at the run's end");
            }
            for (int j = 0; j <= 20; ++j) {
                const float t = (float(key0) + float(key1 - key0) * (float(j) + 0.5f) / 21.0f) / 4.0f;
                EXPECT_EQ(&geometry.segmentAt(tri, t), &head) << "t = " << t;
                const double u = head.localTime(t);
                for (int i = 0; i < 3; ++i) {
                    const glm::vec3 world = mesh.positionAt(v[i], mesh.weightsAt(t));
                    const glm::vec4 exact = scene.camera.clipFromWorld(t, aspect) * glm::vec4(world, 1.0f);
                    const glm::vec4 mixed = glm::mix(head.clip0[i], head.clip1[i], float(u));
                    for (int c = 0; c < 4; ++c) EXPECT_NEAR(mixed[c], exact[c], 2e-5f) << "quad " << q << " corner " << i << " at t = " << t;
                }
            }
        }
    }
}

}  // namespace streak::exposure
