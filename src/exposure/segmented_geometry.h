#pragma once

#include "raster/screen_triangle.h"
#include "scene/flat_geometry.h"
#include "scene/scene.h"
#include "util/memory.h"
#include "util/stats.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace streak::exposure {

// One triangle over one linear segment [t0, t1] of the shutter: its corners at both ends in
// clip space (for the edge equations). Between the ends every corner moves linearly, in clip
// space and in world space alike; the world-space corners (for shading) are the geometry's
// vertices at the segment's ends (SegmentedGeometry::cornersOf), kept per vertex, not per
// triangle segment: that is 144 bytes less for each of a dense mesh's millions of segments.
struct TriangleSegment {
    std::uint32_t triangle = 0;
    float t0 = 0.0f, t1 = 0.0f;
    std::array<glm::vec4, 3> clip0{}, clip1{};
    float nearness = 0.0f;                           ///< 1 / smallest corner view depth; 0 if a corner is at or behind the eye
    std::int8_t orientation = 0;                     ///< +1 front facing throughout, -1 back facing throughout, 0 turns over (or reaches behind the eye)
    bool isBackFacingThroughout = false;             ///< single-sided, or on a closed surface (ClosedSurfaces), and seen from behind at every time: never visible
    bool isStill = false;                            ///< nothing of it moves: its clip corners, and its world corners and normals (SegmentedGeometry::cornersOf), the same at both ends
    // Its ends as segment ends k / numSegments: key1 = key0 + 1, or more where the triangle's
    // motion stays linear over several segments and they are merged into one
    // (SegmentedGeometry, kMergeTolerancePixels). Every slot of a merged run holds the merged
    // segment; the slot at key0 is the one binned and solved.
    std::uint32_t key0 = 0, key1 = 1;

    // A shutter time as the segment's parameter u in [0, 1].
    double localTime(float t) const { return t1 > t0 ? (double(t) - t0) / (double(t1) - t0) : 0.0; }
    bool isInFront() const { return nearness > 0.0f; }
};

// SegmentedGeometry is a scene's triangles cut into linear segments of the shutter, the form
// every exact-time method (motion paths, analytic edge equations) works on. Linear keys under a
// camera that does not turn (still, or moving without turning) move linearly in clip space, so
// one segment per key segment is exact. Curved screen motion (Bezier keys, a turning camera) is
// followed by linear pieces per key segment: curveSegments of them, or with curveSegments =
// kAutoCurveSegments as many (1, 2, 4, ... 64) as keep the scene's vertices within
// kCurveTolerancePixels of their true screen paths (SegmentPlan). Segments are triangle-major:
// segment s of triangle i is at i * numSegments + s.
class SegmentedGeometry {
public:
    static constexpr int kAutoCurveSegments = 0;
    // The key chooser's default screen tolerance (--key-tolerance): how far, in pixels of the
    // image's height, a linear piece may stray from a vertex's curved screen path.
    static constexpr double kCurveTolerancePixels = 0.125;
    static constexpr int kMaxCurveSegments = 64;
    // How far (pixels) a triangle's corners may stray, at the segment ends a merge drops, from
    // the merged segment's straight screen path: float rounding, and nothing an image can show
    // (a vertex a thousandth of a pixel off). View depth is held to 1e-5 of its size, a normal's
    // direction to a thousandth of a radian. 0: no merging. Only under a camera that does not
    // turn (where a straight path in clip space is one in the world, which shading follows).
    static constexpr double kMergeTolerancePixels = 1e-3;

    // How a scene's motion is cut: numSegments linear segments over the shutter, piecesPerKey of
    // them per key segment, and the largest screen distance (pixels) measured between a probed
    // vertex's true position at the middle of a piece and the piece's linear one (-1 where
    // nothing was measured: linear motion, or a fixed curveSegments).
    struct SegmentPlan {
        int numSegments = 1;
        int piecesPerKey = 1;
        double deviationPixels = -1.0;
    };
    static SegmentPlan plan(const Scene& scene, int curveSegments, const raster::Viewport& viewport);

    // Segments of a triangle whose corners (clip space and normals) move along one line at one
    // pace through the joints between them are merged into one (mergeTolerancePixels; 0: none).
    // Keys are shared by every vertex of a scene, so a morph or a skinned mesh is cut everywhere
    // its fastest-changing vertices need; its still parts and its parts moving linearly need
    // one segment, which also lets them cover the whole shutter (the early cull, line samples).
    // With cullClosed, a segment facing away all its time on a closed opaque surface that the
    // eye stays outside of and the near plane clear of is dropped as a single-sided one is
    // (ClosedSurfaces): its own front faces hide it.
    SegmentedGeometry(const Scene& scene, const raster::Viewport& viewport, int curveSegments,
                      double mergeTolerancePixels = kMergeTolerancePixels, bool cullClosed = true);

    const SegmentPlan& segmentPlan() const { return m_plan; }
    const Scene& scene() const { return m_flat.scene(); }
    const FlatGeometry& flat() const { return m_flat; }
    int numSegments() const { return m_numSegments; }
    std::span<const TriangleSegment> segments() const { return m_segments; }
    const TriangleSegment& segment(std::uint32_t triangle, int s) const {
        return m_segments[std::size_t(triangle) * std::size_t(m_numSegments) + std::size_t(s)];
    }
    // The segment of a triangle holding shutter time t (a merged run's first slot).
    const TriangleSegment& segmentAt(std::uint32_t triangle, float t) const;
    // True for a slot merged into an earlier one: it is never binned (an empty screen box).
    bool isMergedAway(std::size_t index) const { return m_segments[index].key0 != index % std::size_t(m_numSegments); }
    // Slots merged into an earlier one, over the whole scene.
    std::int64_t numMergedAway() const { return m_numMergedAway; }
    // True where some segment spans the whole shutter (one segment a triangle, or a merged
    // run): only such a segment can cover a sample all the shutter (the early cull) or stay
    // still all of it (line samples).
    bool hasWholeShutterSegments() const { return m_hasWholeShutterSegments; }
    // A segment's corners in world space at its start and end, and their normals (zero for
    // meshes without normals).
    struct WorldCorners {
        std::array<glm::vec3, 3> world0, world1, normal0, normal1;
    };
    WorldCorners cornersOf(const TriangleSegment& segment) const;
    // Whether nothing of a segment moves from its key0 to its key1: its clip corners (so not under
    // a moving camera), world corners and normals (TriangleSegment::isStill, set for every
    // segment at construction).
    bool isStill(const TriangleSegment& segment) const;
    // Whether a triangle is one still segment over the whole shutter and the camera does not
    // move either: every point of it shades the same at every time.
    bool isStillAllShutter(std::uint32_t triangle) const {
        const TriangleSegment& s = segment(triangle, 0);
        return s.isStill && s.t0 == 0.0f && s.t1 == 1.0f && m_isCameraStatic;
    }
    std::int64_t numBackFacing() const { return m_numBackFacing; }
    // The closed surfaces whose back faces were dropped (cullClosed), and their triangles.
    std::int64_t numClosedSurfaces() const { return m_numClosedSurfaces; }
    std::int64_t numClosedTriangles() const { return m_numClosedTriangles; }

    // The pixels each segment may cover over its time, for binning: with all corners in front of
    // the eye each corner's screen path is a straight segment between its ends, so the box of
    // the six projected corners holds the triangle at every time; a segment reaching behind the
    // eye may cover anything; one that faces away throughout covers nothing.
    LargeBuffer<raster::PixelBounds> screenBounds(const raster::Viewport& viewport) const;

private:
    FlatGeometry m_flat;
    SegmentPlan m_plan;
    int m_numSegments = 1;
    LargeBuffer<TriangleSegment> m_segments;
    std::vector<VertexArray> m_positions, m_normals;  ///< per segment end k / numSegments: the flat geometry's vertices
    std::int64_t m_numBackFacing = 0;
    std::int64_t m_numMergedAway = 0;
    std::int64_t m_numClosedSurfaces = 0, m_numClosedTriangles = 0;
    bool m_hasWholeShutterSegments = false;
    bool m_isCameraStatic = false;

    void mergeLinearRuns(const raster::Viewport& viewport, double tolerancePixels);
    void cullClosedBackFaces(const Camera& camera);
};

// --stats: segments_per_triangle (the plan's), curve_segments (pieces per key segment), where
// measured curve_deviation_px, and segments_merged (slots merged into an earlier one).
void recordSegments(RenderStats& stats, const SegmentedGeometry& segmented);
void recordSegmentPlan(RenderStats& stats, const SegmentedGeometry::SegmentPlan& plan);

}  // namespace streak::exposure
