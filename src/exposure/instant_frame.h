#pragma once

#include "raster/clip.h"
#include "raster/sample_pattern.h"
#include "raster/tile_grid.h"
#include "raster/translucency.h"
#include "scene/flat_geometry.h"
#include "scene/shading.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace streak::exposure {

// InstantFrame is the scene at one shutter time, set up for the rasterizer: accumulation draws
// S of them, blur-shell one. Triangles keep the scene's order (set up in fixed chunks), so which
// of two equally deep surfaces wins does not depend on the thread count.
struct InstantFrame {
    float t = 0.0f;
    glm::vec3 eye{0.0f};
    VertexArray positions;  ///< world, per global vertex
    VertexArray normals;
    std::vector<raster::RasterTriangle> triangles;

    void setup(const FlatGeometry& geometry, float time, const raster::Viewport& viewport, float aspect);
};

// How one tile is drawn. Opaque surfaces are depth tested; translucent ones are sorted and
// blended per sample front to back over the nearest opaque surface. Translucent triangles of the
// meshes from firstInOrderMesh on are instead blended last, in submission order, over the
// resolved colour, depth tested against the opaque surface without writing depth (Jones' blur
// shell as the thesis draws it).
struct InstantDraw {
    ShadingMode shading = ShadingMode::Phong;
    std::uint32_t firstInOrderMesh = std::numeric_limits<std::uint32_t>::max();
    bool keepsSurfaces = false;  ///< keep each sample's opaque surface and colour (for the passes)
};

// Scratch memory of one thread for one tile.
struct InstantScratch {
    struct VisibleSample {
        float invW = 0.0f;             ///< 0: nothing (every visible point has 1/w > 0)
        std::uint32_t triangle = 0;    ///< index into the frame's raster triangles
        raster::EdgeValues edges{};    ///< at the sample, for barycentrics and footprint
    };
    std::vector<VisibleSample> visible;
    std::vector<float> opaqueInvW;
    std::vector<glm::vec3> color;      ///< the tile's samples, pixel-major: the result
    std::vector<float> coverage;       ///< and their coverage (alpha)
    std::vector<raster::TranslucentFragment> translucent;  ///< sorted by compositeTranslucent; `triangle` a FlatTriangle
    std::vector<raster::TranslucentFragment> inOrder;
    // With InstantDraw::keepsSurfaces, per sample: the FlatTriangle of its opaque surface (~0u:
    // none), its 1 / depth (opaqueInvW) and its colour, before the translucent ones over it.
    std::vector<std::uint32_t> opaqueTriangle;
    std::vector<glm::vec3> opaqueColor;
    std::vector<float> transmittance;  ///< the passes' scratch
};

// Rasterizes, shades and resolves one tile of `frame` (binned in `grid`) into scratch.color
// and scratch.coverage;
// returns the fragments scanned.
std::int64_t drawInstantTile(const FlatGeometry& geometry, const InstantFrame& frame, const raster::TileGrid& grid, int tile,
                             const raster::SamplePattern& pattern, const InstantDraw& draw, InstantScratch& scratch);

}  // namespace streak::exposure
