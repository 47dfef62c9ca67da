#include "exposure/reconstruction_filter.h"

#include "util/error.h"

#include "util/random.h"

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace streak::exposure {

namespace {

constexpr float kBackgroundDepth = 1e30f;

float cone(float distance, float speed) { return std::clamp(1.0f - distance / std::max(speed, 1e-6f), 0.0f, 1.0f); }

float cylinder(float distance, float speed) {
    const float lo = 0.95f * speed, hi = 1.05f * speed;
    if (distance <= lo) return 1.0f;
    if (distance >= hi) return 0.0f;
    const float x = (distance - lo) / (hi - lo);
    return 1.0f - x * x * (3.0f - 2.0f * x);
}

// 1 where depth a is in front of depth b, falling to 0 over `extent` behind it.
float softDepthCompare(float a, float b, float extent) { return std::clamp(1.0f - (a - b) / extent, 0.0f, 1.0f); }

glm::vec2 longer(glm::vec2 a, glm::vec2 b) { return glm::dot(b, b) > glm::dot(a, a) ? b : a; }

}  // namespace

ReconstructionOptions ReconstructionOptions::read(OptionMap& options) {
    ReconstructionOptions o;
    o.tile = options.getInt("tile", o.tile, 1, 256);
    o.samples = options.getInt("samples", o.samples, 1, 255);
    o.maxRadius = float(options.getDouble("max-radius", double(o.tile), 0.0, 256.0));
    if (o.maxRadius > float(o.tile)) throw Error(options.owner() + ": max-radius must not exceed tile (the tiles see velocities up to k pixels)");
    o.softDepth = float(options.getDouble("soft-depth", o.softDepth, 1e-6, 1.0));
    return o;
}

float gatherJitter(std::uint64_t seed, std::size_t pixel) { return unitFloat(hashValues(seed, std::uint64_t(pixel))) - 0.5f; }

void clampVelocities(VelocityFrame& frame, const ReconstructionOptions& options) {
    for (glm::vec2& v : frame.velocity) {
        v *= options.velocityScale;
        const float speed = glm::length(v);
        if (!(speed >= 0.5f)) v = glm::vec2(0.0f);
        else if (speed > options.maxRadius) v *= options.maxRadius / speed;
    }
}

std::vector<glm::vec2> tileMax(const VelocityFrame& frame, int tile) {
    const int tw = (frame.width + tile - 1) / tile, th = (frame.height + tile - 1) / tile;
    std::vector<glm::vec2> tiles(std::size_t(tw) * std::size_t(th), glm::vec2(0.0f));
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            glm::vec2& t = tiles[std::size_t(y / tile) * std::size_t(tw) + std::size_t(x / tile)];
            t = longer(t, frame.velocity[frame.index(x, y)]);
        }
    return tiles;
}

std::vector<glm::vec2> neighborMax(const std::vector<glm::vec2>& tiles, int tilesWide, int tilesHigh) {
    std::vector<glm::vec2> out(tiles.size(), glm::vec2(0.0f));
    for (int ty = 0; ty < tilesHigh; ++ty)
        for (int tx = 0; tx < tilesWide; ++tx) {
            glm::vec2 m(0.0f);
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int x = tx + dx, y = ty + dy;
                    if (x >= 0 && y >= 0 && x < tilesWide && y < tilesHigh) m = longer(m, tiles[std::size_t(y) * std::size_t(tilesWide) + std::size_t(x)]);
                }
            out[std::size_t(ty) * std::size_t(tilesWide) + std::size_t(tx)] = m;
        }
    return out;
}

Image reconstruct(const VelocityFrame& frame, const ReconstructionOptions& options) {
    const int tw = (frame.width + options.tile - 1) / options.tile, th = (frame.height + options.tile - 1) / options.tile;
    const std::vector<glm::vec2> neighbors = neighborMax(tileMax(frame, options.tile), tw, th);
    Image image(frame.width, frame.height);
    std::vector<float> coverage(frame.coverage.size());
    const int taps = options.samples;
    auto depthAt = [&](std::size_t i) { return std::isfinite(frame.depth[i]) ? frame.depth[i] : kBackgroundDepth; };
    tbb::parallel_for(tbb::blocked_range<int>(0, frame.height, 8), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < frame.width; ++x) {
                const std::size_t cx = frame.index(x, y);
                const glm::vec2 vn = neighbors[std::size_t(y / options.tile) * std::size_t(tw) + std::size_t(x / options.tile)];
                if (glm::length(vn) <= 0.5f) {
                    image.at(x, y) = frame.color[cx];
                    coverage[cx] = frame.coverage[cx];
                    continue;
                }
                const float speedX = glm::length(frame.velocity[cx]), zx = depthAt(cx);
                float weight = 1.0f / std::max(speedX, 0.5f);
                glm::vec3 sum = frame.color[cx] * weight;
                float coverageSum = frame.coverage[cx] * weight;
                // Guertin et al.: a per-pixel jitter of the taps along the line, so the steps
                // between taps become noise instead of ghost copies.
                const float jitter = gatherJitter(options.seed, cx);
                for (int i = 0; i < taps; ++i) {
                    if (i == (taps - 1) / 2) continue;  // the centre is the pixel itself
                    const float t = -1.0f + 2.0f * (float(i) + jitter + 1.0f) / float(taps + 1);
                    const int sx = std::clamp(int(std::floor(float(x) + 0.5f + vn.x * t)), 0, frame.width - 1);
                    const int sy = std::clamp(int(std::floor(float(y) + 0.5f + vn.y * t)), 0, frame.height - 1);
                    const std::size_t cy = frame.index(sx, sy);
                    const float distance = glm::length(glm::vec2(float(sx - x), float(sy - y)));
                    const float zy = depthAt(cy), extent = options.softDepth * std::min(zx, zy);
                    const float speedY = glm::length(frame.velocity[cy]);
                    const float yInFront = softDepthCompare(zy, zx, extent), xInFront = softDepthCompare(zx, zy, extent);
                    const float alpha = yInFront * cone(distance, speedY) + xInFront * cone(distance, speedX) +
                                        2.0f * cylinder(distance, speedY) * cylinder(distance, speedX);
                    weight += alpha;
                    sum += alpha * frame.color[cy];
                    coverageSum += alpha * frame.coverage[cy];
                }
                image.at(x, y) = sum / weight;
                coverage[cx] = coverageSum / weight;
            }
    });
    image.setAlpha(std::move(coverage));
    return image;
}

}  // namespace streak::exposure
