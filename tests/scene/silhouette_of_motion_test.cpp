#include "scene/silhouette_of_motion.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <vector>

namespace streak {
namespace {

// One triangle moving by +x each update. Its normals are set per update: corner 0 facing +x
// (forward) and corners 1, 2 facing -x (backward) put its edge (1, 2) on the SoM; all three
// facing +x takes it off.
struct OneTriangle {
    std::vector<glm::uvec3> triangles{{0, 1, 2}};
    std::vector<glm::vec3> base{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}};

    std::vector<glm::vec3> positionsAt(int update) const {
        std::vector<glm::vec3> p = base;
        for (glm::vec3& v : p) v.x += float(update);
        return p;
    }
    static std::vector<glm::vec3> normals(bool isOnSilhouette) {
        const glm::vec3 back = isOnSilhouette ? glm::vec3(-1, 0, 0) : glm::vec3(1, 0, 0);
        return {{1, 0, 0}, back, back};
    }
};

// Runs updates 1..onSilhouette.size(); onSilhouette[i] says whether update i + 1 has the SoM.
SilhouetteOfMotion run(const OneTriangle& tri, const std::vector<bool>& onSilhouette, int subdivisions) {
    SilhouetteOfMotion som(tri.triangles, subdivisions);
    for (std::size_t i = 0; i < onSilhouette.size(); ++i) {
        const std::size_t found = som.update(tri.positionsAt(int(i)), tri.positionsAt(int(i) + 1), OneTriangle::normals(onSilhouette[i]));
        EXPECT_EQ(found, onSilhouette[i] ? 1u : 0u) << "update " << i + 1;
    }
    return som;
}

TEST(SilhouetteOfMotion, RecordsTheBackwardEdgeOfAPolygonWithOneForwardVertex) {
    const OneTriangle tri;
    const SilhouetteOfMotion som = run(tri, {true}, 4);
    EXPECT_EQ(som.updatesSinceSilhouette(0), 0u);
    std::vector<ShellStrip> strips;
    som.appendStrips(tri.positionsAt(1), OneTriangle::normals(true), 0.5f, 3, strips);
    ASSERT_EQ(strips.size(), 1u);
    const ShellStrip& strip = strips[0];
    ASSERT_EQ(strip.edges.size(), 2u);  // the mesh edge, and the one update recorded
    EXPECT_EQ(strip.edges[0].vertices, (std::array<std::uint32_t, 2>{1, 2}));
    EXPECT_EQ(strip.edges[0].positions[0], glm::vec3(1, 1, 0));
    EXPECT_EQ(strip.edges[1].positions, strip.edges[0].positions);
}

TEST(SilhouetteOfMotion, VerticesThatDoNotMoveFaceNeitherWay) {
    const OneTriangle tri;
    SilhouetteOfMotion som(tri.triangles, 4);
    EXPECT_EQ(som.update(tri.positionsAt(0), tri.positionsAt(0), OneTriangle::normals(true)), 0u);
    EXPECT_EQ(som.updatesSinceSilhouette(0), SilhouetteOfMotion::kNever);
    std::vector<ShellStrip> strips;
    som.appendStrips(tri.positionsAt(0), OneTriangle::normals(true), 0.5f, 3, strips);
    EXPECT_TRUE(strips.empty());
}

TEST(SilhouetteOfMotion, StripAlphasStepByTheInitialAlphaOverSubdivisions) {
    const OneTriangle tri;
    const int s = 5;
    const SilhouetteOfMotion som = run(tri, std::vector<bool>(s, true), s);
    std::vector<ShellStrip> strips;
    som.appendStrips(tri.positionsAt(s), OneTriangle::normals(true), 0.5f, 3, strips);
    ASSERT_EQ(strips.size(), 1u);
    const ShellStrip& strip = strips[0];
    ASSERT_EQ(strip.edges.size(), std::size_t(s + 1));  // the mesh edge, then s updates
    for (int j = 0; j <= s; ++j) EXPECT_FLOAT_EQ(strip.alphas[std::size_t(j)], 0.5f - float(j) * 0.5f / float(s)) << j;
    // Newest first: entry j was recorded at update s - j + 1, where the edge stood at x = s - j + 1.
    for (int j = 1; j <= s; ++j) EXPECT_EQ(strip.edges[std::size_t(j)].positions[0].x, float(s - j + 1)) << j;
}

TEST(SilhouetteOfMotion, AHoleOfOneUpdateIsPatchedWithTheLastEdgeWhereItStood) {
    const OneTriangle tri;
    const int s = 5;
    // Off the SoM at update 3 only.
    const SilhouetteOfMotion som = run(tri, {true, true, false, true, true}, s);
    std::vector<ShellStrip> strips;
    som.appendStrips(tri.positionsAt(s), OneTriangle::normals(true), 0.5f, 3, strips);
    ASSERT_EQ(strips.size(), 1u);
    const ShellStrip& strip = strips[0];
    ASSERT_EQ(strip.edges.size(), std::size_t(s + 1));  // continuous: no entry left out
    for (int j = 1; j <= s; ++j) EXPECT_EQ(strip.edges[std::size_t(j)].positions[0].x, float(s - j + 1)) << j;
    EXPECT_EQ(strip.edges[3].vertices, (std::array<std::uint32_t, 2>{1, 2}));  // update 3: the patch
}

TEST(SilhouetteOfMotion, AStripLeftForUUpdatesIsFadedByUOverFade) {
    const OneTriangle tri;
    const int s = 8, fade = 4;
    for (int u = 0; u < fade + 2; ++u) {
        std::vector<bool> on(std::size_t(s), true);
        for (int i = 0; i < u; ++i) on[std::size_t(s - 1 - i)] = false;
        const SilhouetteOfMotion som = run(tri, on, s);
        EXPECT_EQ(som.updatesSinceSilhouette(0), std::uint32_t(u));
        std::vector<ShellStrip> strips;
        som.appendStrips(tri.positionsAt(s), OneTriangle::normals(false), 0.8f, fade, strips);
        if (u >= fade) {
            EXPECT_TRUE(strips.empty()) << u;  // faded out: no polygons
            continue;
        }
        ASSERT_EQ(strips.size(), 1u) << u;
        const float stripFade = 1.0f - float(u) / float(fade);
        for (std::size_t j = 0; j < strips[0].alphas.size(); ++j)
            EXPECT_FLOAT_EQ(strips[0].alphas[j], (0.8f - float(j) * 0.8f / float(s)) * stripFade) << u << " " << j;
        // The updates off the SoM patch with the last edge: the strip starts at the mesh.
        EXPECT_EQ(strips[0].edges.size(), std::size_t(s + 1)) << u;
    }
}

TEST(SilhouetteOfMotion, AStripStopsAtFadeUpdatesInARowOffTheSilhouette) {
    const OneTriangle tri;
    const int s = 8, fade = 2;
    // On at 1-4, off at 5-6 (two in a row), on at 7-8.
    const SilhouetteOfMotion som = run(tri, {true, true, true, true, false, false, true, true}, s);
    std::vector<ShellStrip> strips;
    som.appendStrips(tri.positionsAt(s), OneTriangle::normals(true), 0.5f, fade, strips);
    ASSERT_EQ(strips.size(), 1u);
    // The mesh edge, updates 8 and 7, then update 6 (one off: patched); update 5 is the second off.
    EXPECT_EQ(strips[0].edges.size(), 4u);
}

}  // namespace
}  // namespace streak
