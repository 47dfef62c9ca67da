#include "exposure/instant_frame.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

namespace streak::exposure {

void InstantFrame::setup(const FlatGeometry& geometry, float time, const raster::Viewport& viewport, float aspect) {
    const Scene& scene = geometry.scene();
    t = time;
    geometry.positionsAt(t, positions);
    geometry.normalsAt(t, normals);
    eye = scene.camera.positionAt(t);
    const glm::mat4 clipFromWorld = scene.camera.clipFromWorld(t, aspect);
    const auto& flat = geometry.triangles();
    constexpr std::size_t kChunk = 4096;
    const std::size_t numChunks = (flat.size() + kChunk - 1) / kChunk;
    std::vector<std::vector<raster::RasterTriangle>> chunks(numChunks);
    tbb::parallel_for(std::size_t(0), numChunks, [&](std::size_t c) {
        raster::TriangleSetup setup;
        for (std::size_t i = c * kChunk; i < std::min(flat.size(), (c + 1) * kChunk); ++i) {
            const FlatTriangle& tri = flat[i];
            const std::array<glm::vec4, 3> clip{clipFromWorld * glm::vec4(positions[tri.vertices.x], 1.0f),
                                                clipFromWorld * glm::vec4(positions[tri.vertices.y], 1.0f),
                                                clipFromWorld * glm::vec4(positions[tri.vertices.z], 1.0f)};
            raster::setupTriangle(clip, std::uint32_t(i), scene.camera.zNear, viewport,
                                  tri.isDoubleSided ? raster::CullMode::None : raster::CullMode::Back, setup);
            chunks[c].insert(chunks[c].end(), setup.triangles.begin(), setup.triangles.begin() + setup.count);
        }
    });
    triangles.clear();
    for (auto& chunk : chunks) triangles.insert(triangles.end(), chunk.begin(), chunk.end());
}

std::int64_t drawInstantTile(const FlatGeometry& geometry, const InstantFrame& frame, const raster::TileGrid& grid, int tile,
                             const raster::SamplePattern& pattern, const InstantDraw& draw, InstantScratch& scratch) {
    const Scene& scene = geometry.scene();
    const raster::PixelBounds rect = grid.tileBounds(tile);
    const int tileWidth = rect.x1 - rect.x0 + 1, tileHeight = rect.y1 - rect.y0 + 1;
    const int spp = pattern.count();
    const std::size_t numSamples = std::size_t(tileWidth) * tileHeight * spp;
    scratch.visible.assign(numSamples, InstantScratch::VisibleSample{});
    scratch.translucent.clear();
    scratch.inOrder.clear();
    auto sampleIndex = [&](int px, int py, int s) { return (std::size_t(py - rect.y0) * tileWidth + (px - rect.x0)) * spp + s; };
    auto shade = [&](const raster::RasterTriangle& rt, const raster::EdgeValues& e) {
        const FlatTriangle& tri = geometry.triangles()[rt.source];
        const raster::SourceFootprint f = rt.sourceFootprint(e, pattern.footprintStep());
        const std::array<glm::vec3, 3> corners{frame.positions[tri.vertices.x], frame.positions[tri.vertices.y],
                                               frame.positions[tri.vertices.z]};
        const std::array<glm::vec3, 3> normals{frame.normals[tri.vertices.x], frame.normals[tri.vertices.y],
                                               frame.normals[tri.vertices.z]};
        const SurfacePoint point = geometry.surfacePoint(tri, corners, normals, f.bary, f.right, f.down, rt.screen.isFrontFacing);
        return shadeSurface(scene, draw.shading, point, frame.eye);
    };

    std::int64_t fragments = 0;
    for (const std::uint32_t index : grid.items(tile)) {
        const raster::RasterTriangle& rt = frame.triangles[index];
        const FlatTriangle& tri = geometry.triangles()[rt.source];
        const bool isTranslucent = scene.materials[tri.material].isTranslucent();
        std::vector<raster::TranslucentFragment>& blended = tri.mesh >= draw.firstInOrderMesh ? scratch.inOrder : scratch.translucent;
        raster::scanTriangle(rt.screen, rect, pattern, [&](int px, int py, int s, const raster::EdgeValues& e) {
            ++fragments;
            const std::size_t i = sampleIndex(px, py, s);
            const float invW = rt.screen.interpolate(e).invW;
            if (isTranslucent) {
                const ShadedColor c = shade(rt, e);
                blended.push_back({std::uint32_t(i), invW, c.color, c.alpha, rt.source});
            } else if (invW > scratch.visible[i].invW) {
                scratch.visible[i] = {invW, index, e};
            }
        });
    }

    scratch.color.resize(numSamples);
    scratch.coverage.resize(numSamples);
    scratch.opaqueInvW.resize(numSamples);
    for (std::size_t i = 0; i < numSamples; ++i) {
        const InstantScratch::VisibleSample& v = scratch.visible[i];
        scratch.opaqueInvW[i] = v.invW;
        scratch.color[i] = v.invW > 0.0f ? shade(frame.triangles[v.triangle], v.edges).color : scene.background;
        scratch.coverage[i] = v.invW > 0.0f ? 1.0f : 0.0f;
    }
    if (draw.keepsSurfaces) {
        scratch.opaqueColor.assign(scratch.color.begin(), scratch.color.end());
        scratch.opaqueTriangle.resize(numSamples);
        for (std::size_t i = 0; i < numSamples; ++i)
            scratch.opaqueTriangle[i] = scratch.visible[i].invW > 0.0f ? frame.triangles[scratch.visible[i].triangle].source : ~0u;
    }
    if (!scratch.translucent.empty()) raster::compositeTranslucent(scratch.translucent, scratch.opaqueInvW, scratch.color, scratch.coverage);
    // Submission order within the tile is the scene's triangle order, and each triangle's
    // fragments come in scan order: blending the list in turn is the thesis' draw order.
    for (const raster::TranslucentFragment& f : scratch.inOrder)
        if (f.invW > scratch.opaqueInvW[f.sample]) {
            scratch.color[f.sample] = f.alpha * f.color + (1.0f - f.alpha) * scratch.color[f.sample];
            scratch.coverage[f.sample] = f.alpha + (1.0f - f.alpha) * scratch.coverage[f.sample];
        }
    return fragments;
}

}  // namespace streak::exposure
