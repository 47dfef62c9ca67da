#include "raster/tile_grid.h"

#include <algorithm>

namespace streak::raster {

TileGrid::TileGrid(const Viewport& viewport, int tileSize, const std::optional<PixelBounds>& region)
    : m_viewport(viewport),
      m_tileSize(tileSize),
      m_tilesX((viewport.width + tileSize - 1) / tileSize),
      m_tilesY((viewport.height + tileSize - 1) / tileSize),
      m_offsets(std::size_t(m_tilesX) * m_tilesY + 1, 0) {
    m_active = {0, 0, m_tilesX - 1, m_tilesY - 1};
    if (region) m_active = tileRange(*region);
}

bool TileGrid::isActive(int tile) const {
    const int tx = tile % m_tilesX, ty = tile / m_tilesX;
    return tx >= m_active.x0 && tx <= m_active.x1 && ty >= m_active.y0 && ty <= m_active.y1;
}

PixelBounds TileGrid::tileBounds(int tile) const {
    const int tx = tile % m_tilesX, ty = tile / m_tilesX;
    return {tx * m_tileSize, ty * m_tileSize, std::min(m_viewport.width, (tx + 1) * m_tileSize) - 1,
            std::min(m_viewport.height, (ty + 1) * m_tileSize) - 1};
}

PixelBounds TileGrid::tileRange(const PixelBounds& p) const {
    if (p.empty()) return {};
    PixelBounds t{std::max(0, p.x0) / m_tileSize, std::max(0, p.y0) / m_tileSize,
                  std::min(m_viewport.width - 1, p.x1) / m_tileSize, std::min(m_viewport.height - 1, p.y1) / m_tileSize};
    if (p.x1 < 0 || p.y1 < 0 || p.x0 >= m_viewport.width || p.y0 >= m_viewport.height) return {};
    return t;
}

PixelBounds TileGrid::activeTileRange(const PixelBounds& p) const {
    const PixelBounds t = tileRange(p);
    if (t.empty()) return t;
    return {std::max(t.x0, m_active.x0), std::max(t.y0, m_active.y0), std::min(t.x1, m_active.x1), std::min(t.y1, m_active.y1)};
}

}  // namespace streak::raster
