#include "raster/clip.h"

namespace streak::raster {

namespace {

// Signed distances to the five clip planes; inside is >= 0.
std::array<float, 5> planeDistances(const glm::vec4& p, float zNear) {
    return {p.w - zNear, kGuardBand * p.w - p.x, kGuardBand * p.w + p.x, kGuardBand * p.w - p.y, kGuardBand * p.w + p.y};
}

}  // namespace

bool needsClipping(const std::array<glm::vec4, 3>& clip, float zNear) {
    for (const glm::vec4& p : clip)
        for (float d : planeDistances(p, zNear))
            if (d < 0.0f) return true;
    return false;
}

ClippedPolygon clipTriangle(const std::array<glm::vec4, 3>& clip, float zNear) {
    ClippedPolygon poly;
    const std::array<glm::vec3, 3> corners{glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
    for (int i = 0; i < 3; ++i) poly.vertices[i] = {clip[i], corners[i]};
    poly.count = 3;
    for (int plane = 0; plane < 5 && poly.count > 0; ++plane) {
        ClippedPolygon next;
        for (int i = 0; i < poly.count; ++i) {
            const ClipVertex& a = poly.vertices[i];
            const ClipVertex& b = poly.vertices[(i + 1) % poly.count];
            const float da = planeDistances(a.clip, zNear)[plane];
            const float db = planeDistances(b.clip, zNear)[plane];
            if (da >= 0.0f) next.vertices[next.count++] = a;
            if ((da >= 0.0f) != (db >= 0.0f)) {
                // Clip space is where interpolation is linear, so the crossing mixes both the
                // position and the source barycentrics with one parameter.
                const float s = da / (da - db);
                next.vertices[next.count++] = {a.clip + (b.clip - a.clip) * s, a.sourceBary + (b.sourceBary - a.sourceBary) * s};
            }
        }
        poly = next;
    }
    if (poly.count < 3) poly.count = 0;
    return poly;
}

void setupTriangle(const std::array<glm::vec4, 3>& clip, std::uint32_t source, float zNear, const Viewport& viewport,
                   CullMode cull, TriangleSetup& out) {
    out.count = 0;
    auto emit = [&](const std::array<glm::vec4, 3>& corners, const glm::mat3* sourceFromLocal) {
        RasterTriangle& tri = out.triangles[out.count];
        if (!setupScreenTriangle(corners, viewport, tri.screen)) return;
        if (cull == CullMode::Back && !tri.screen.isFrontFacing) return;
        if (tri.screen.bounds.empty()) return;
        tri.source = source;
        tri.isClipped = sourceFromLocal != nullptr;
        tri.sourceFromLocal = sourceFromLocal ? *sourceFromLocal : glm::mat3(1.0f);
        ++out.count;
    };
    if (!needsClipping(clip, zNear)) {
        emit(clip, nullptr);
        return;
    }
    const ClippedPolygon poly = clipTriangle(clip, zNear);
    for (int i = 1; i + 1 < poly.count; ++i) {
        const ClipVertex& v0 = poly.vertices[0];
        const ClipVertex& v1 = poly.vertices[i];
        const ClipVertex& v2 = poly.vertices[i + 1];
        const glm::mat3 sourceFromLocal(v0.sourceBary, v1.sourceBary, v2.sourceBary);
        emit({v0.clip, v1.clip, v2.clip}, &sourceFromLocal);
    }
}

}  // namespace streak::raster
