#include "raster/convex_hull.h"

#include <algorithm>

namespace streak::raster {

template <std::size_t N>
ConvexHull convexHull(const std::array<glm::dvec2, N>& p) {
    constexpr int n = int(N);
    std::array<int, N> order{};
    for (int i = 0; i < n; ++i) order[std::size_t(i)] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return p[a].x != p[b].x ? p[a].x < p[b].x : p[a].y < p[b].y; });
    auto cross = [&](int o, int a, int b) { return (p[a].x - p[o].x) * (p[b].y - p[o].y) - (p[a].y - p[o].y) * (p[b].x - p[o].x); };
    ConvexHull hull;
    int& count = hull.count;
    // The lower chain left to right, then the upper right to left; each chain's last point
    // starts the other.
    for (int pass = 0; pass < 2; ++pass) {
        const int start = count;
        for (int k = 0; k < n; ++k) {
            const int i = order[std::size_t(pass == 0 ? k : n - 1 - k)];
            while (count >= start + 2 && cross(hull.index[std::size_t(count - 2)], hull.index[std::size_t(count - 1)], i) <= 0.0) --count;
            hull.index[std::size_t(count++)] = i;
        }
        --count;
    }
    return hull;
}

template ConvexHull convexHull(const std::array<glm::dvec2, 4>&);
template ConvexHull convexHull(const std::array<glm::dvec2, 6>&);

}  // namespace streak::raster
