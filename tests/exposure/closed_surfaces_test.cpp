#include "exposure/closed_surfaces.h"
#include "exposure/segmented_geometry.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace streak::exposure {

namespace {

// A cube of half size h about `centre`, each face with its own four vertices (as a glTF mesh
// splits them for normals and uvs), counter-clockwise seen from outside; at the shutter's close
// moved by `move`.
void addCube(Mesh& mesh, glm::vec3 centre, float h, glm::vec3 move = glm::vec3(0.0f)) {
    std::vector<glm::vec3> open;
    for (int axis = 0; axis < 3; ++axis)
        for (const float side : {1.0f, -1.0f}) {
            glm::vec3 normal(0.0f), u(0.0f), v(0.0f);
            normal[axis] = side, u[(axis + 1) % 3] = 1.0f, v[(axis + 2) % 3] = 1.0f;
            if (side < 0.0f) std::swap(u, v);  // u x v = the outward normal
            const auto first = std::uint32_t(mesh.positions.size() / 2 + open.size());
            for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
                open.push_back(centre + h * (normal + c.x * u + c.y * v));
            mesh.triangles.push_back({first, first + 1, first + 2});
            mesh.triangles.push_back({first, first + 2, first + 3});
        }
    // Keys: every open vertex, then every close one (the mesh's earlier vertices kept in place).
    const std::size_t before = mesh.positions.size() / 2;
    std::vector<glm::vec3> positions(mesh.positions.begin(), mesh.positions.begin() + std::ptrdiff_t(before));
    positions.insert(positions.end(), open.begin(), open.end());
    positions.insert(positions.end(), mesh.positions.begin() + std::ptrdiff_t(before), mesh.positions.end());
    for (const glm::vec3& p : open) positions.push_back(p + move);
    mesh.positions = std::move(positions);
}

Scene cubeScene(bool isDoubleSided, float opacity, const std::function<void(Mesh&)>& change,
                glm::vec3 move = glm::vec3(0.5f, 0.25f, 0.0f)) {
    Scene scene = test::emptyScene();
    const std::uint32_t material = test::addMaterial(scene, glm::vec3(0.8f), opacity);
    scene.materials[material].doubleSided = isDoubleSided;
    Mesh mesh;
    mesh.numKeys = 2;
    mesh.material = material;
    addCube(mesh, glm::vec3(0.3f, -0.2f, -5.0f), 1.0f, move);
    change(mesh);
    scene.meshes.push_back(std::move(mesh));
    validateScene(scene);
    return scene;
}

// The closed surfaces of a scene, at both ends of its shutter.
std::pair<std::uint32_t, std::vector<std::uint32_t>> surfacesOf(const Scene& scene) {
    const FlatGeometry flat(scene);
    std::vector<VertexArray> poses(2);
    flat.positionsAt(0.0f, poses[0]), flat.positionsAt(1.0f, poses[1]);
    const ClosedSurfaces closed(flat, poses);
    std::vector<std::uint32_t> of;
    for (std::uint32_t t = 0; t < flat.triangles().size(); ++t) of.push_back(closed.surfaceOf(t));
    return {closed.count(), of};
}

}  // namespace

// A moving cube whose faces share only positions, not vertices, is one closed surface; so is
// each of two cubes in one mesh.
TEST(ClosedSurfaces, FindsACubeWhoseFacesShareOnlyPositions) {
    const auto [count, of] = surfacesOf(cubeScene(true, 1.0f, [](Mesh&) {}));
    EXPECT_EQ(count, 1u);
    EXPECT_EQ(of, std::vector<std::uint32_t>(12, 0u));

    const auto [two, ofTwo] = surfacesOf(cubeScene(true, 1.0f, [](Mesh& mesh) { addCube(mesh, glm::vec3(3.0f, 0.0f, -6.0f), 0.5f); }));
    EXPECT_EQ(two, 2u);
    for (int t = 0; t < 24; ++t) EXPECT_EQ(ofTwo[std::size_t(t)], t < 12 ? 0u : 1u) << t;
}

// What is not a closed, outward, opaque, double-sided surface at both poses is none: each change
// below takes the cube's surface away (and a second, open cube beside a closed one leaves the
// closed one alone).
TEST(ClosedSurfaces, LeavesOutWhatIsOpenFlippedSeeThroughOrPulledApart) {
    const std::vector<std::pair<std::string, Scene>> changed{
        {"a triangle missing", cubeScene(true, 1.0f, [](Mesh& mesh) { mesh.triangles.pop_back(); })},
        {"a triangle turned over", cubeScene(true, 1.0f, [](Mesh& mesh) { std::swap(mesh.triangles[3].y, mesh.triangles[3].z); })},
        {"every triangle turned over (inward)",
         cubeScene(true, 1.0f, [](Mesh& mesh) {
             for (glm::uvec3& t : mesh.triangles) std::swap(t.y, t.z);
         })},
        {"a face twice", cubeScene(true, 1.0f, [](Mesh& mesh) { mesh.triangles.push_back(mesh.triangles[0]); })},
        {"translucent", cubeScene(true, 0.5f, [](Mesh&) {})},
        {"single-sided (its back faces go anyway)", cubeScene(false, 1.0f, [](Mesh&) {})},
        // One of the three vertices at a corner leaves the others at the close: the faces part.
        {"a corner pulled apart", cubeScene(true, 1.0f, [](Mesh& mesh) { mesh.positions[24 + 0] += glm::vec3(0.0f, 0.0f, 0.01f); })},
    };
    for (const auto& [what, scene] : changed) {
        SCOPED_TRACE(what);
        EXPECT_EQ(surfacesOf(scene).first, 0u);
    }
    const auto [count, of] = surfacesOf(cubeScene(true, 1.0f, [](Mesh& mesh) {
        addCube(mesh, glm::vec3(3.0f, 0.0f, -6.0f), 0.5f);
        mesh.triangles.pop_back();
    }));
    EXPECT_EQ(count, 1u);
    for (int t = 0; t < 23; ++t) EXPECT_EQ(of[std::size_t(t)], t < 12 ? 0u : ClosedSurfaces::kNone) << t;
}

// Shells join across edges, never at a corner alone: a small cube touching the cube at one
// corner is a surface of its own, or none where it is wound inward (whose volume, summed with
// the cube's, would still be positive).
TEST(ClosedSurfaces, ShellsTouchingAtACornerAreMeasuredApart) {
    for (const bool isInward : {false, true}) {
        SCOPED_TRACE(isInward ? "inward" : "outward");
        const glm::vec3 corner = glm::vec3(0.3f, -0.2f, -5.0f) + glm::vec3(1.0f);  // the cube's (+, +, +) corner
        const auto [count, of] = surfacesOf(cubeScene(true, 1.0f, [&](Mesh& mesh) {
            addCube(mesh, corner + glm::vec3(0.25f), 0.25f, glm::vec3(0.5f, 0.25f, 0.0f));
            if (isInward)
                for (std::size_t t = 12; t < 24; ++t) std::swap(mesh.triangles[t].y, mesh.triangles[t].z);
        }));
        EXPECT_EQ(count, isInward ? 1u : 2u);
        for (int t = 0; t < 24; ++t) EXPECT_EQ(of[std::size_t(t)], t < 12 ? 0u : isInward ? ClosedSurfaces::kNone : 1u) << t;
    }
}

// In a frame, the closed surface's segments that face away all the shutter are dropped, as a
// single-sided triangle's are, and no others; not where the near plane cuts the surface, nor
// with cullClosed off.
TEST(ClosedSurfaces, AFrameDropsTheSegmentsFacingAwayOnlyWhereTheNearPlaneIsClear) {
    const raster::Viewport viewport{64, 48};
    const Scene scene = cubeScene(true, 1.0f, [](Mesh&) {});
    const SegmentedGeometry culled(scene, viewport, 1);
    EXPECT_EQ(culled.numClosedSurfaces(), 1);
    EXPECT_EQ(culled.numClosedTriangles(), 12);
    int away = 0;
    for (const TriangleSegment& s : culled.segments()) {
        EXPECT_EQ(s.isBackFacingThroughout, s.orientation < 0);
        away += s.orientation < 0;
    }
    EXPECT_GE(away, 2);  // the cube is seen from off its axes: its far faces
    EXPECT_EQ(culled.numBackFacing(), away);

    const SegmentedGeometry kept(scene, viewport, 1, SegmentedGeometry::kMergeTolerancePixels, false);
    EXPECT_EQ(kept.numClosedSurfaces(), 0);
    EXPECT_EQ(kept.numBackFacing(), 0);

    // The cube around the near plane: its inside shows through the cut.
    Scene cut = scene;
    cut.camera.zNear = 4.5f;
    const SegmentedGeometry cutGeometry(cut, viewport, 1);
    EXPECT_EQ(cutGeometry.numClosedSurfaces(), 0);
    EXPECT_EQ(cutGeometry.numBackFacing(), 0);

    // The cube coming towards the eye, clear of the near plane at the open (depth 4 and more)
    // and cut by it at the close (its front at depth 2.2).
    Scene coming = cubeScene(true, 1.0f, [](Mesh&) {}, glm::vec3(0.0f, 0.0f, 1.8f));
    coming.camera.zNear = 2.5f;
    const SegmentedGeometry comingGeometry(coming, viewport, 1);
    EXPECT_EQ(comingGeometry.numClosedSurfaces(), 0);
    coming.camera.zNear = 2.0f;
    EXPECT_EQ(SegmentedGeometry(coming, viewport, 1).numClosedSurfaces(), 1);
}

}  // namespace streak::exposure
