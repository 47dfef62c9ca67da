#pragma once

#include <cstdint>
#include <deque>
#include <vector>

namespace streak::exposure {

// Per-segment edge equations (a MovingTriangle, a CurvedTriangle), built on first use and kept
// until clear(): a tile builds each once however many samples and spans use it. One per thread.
template <class Triangle>
class TriangleCache {
public:
    // The triangle of segment `index` of numSegments, made by make() the first time.
    template <class Make>
    const Triangle& get(std::size_t numSegments, std::uint32_t index, Make&& make) {
        if (m_slot.size() != numSegments) {
            m_slot.assign(numSegments, -1);
            m_triangles.clear(), m_used.clear();
        }
        std::int32_t& slot = m_slot[index];
        if (slot < 0) {
            slot = std::int32_t(m_triangles.size());
            m_triangles.push_back(make());
            m_used.push_back(index);
        }
        return m_triangles[std::size_t(slot)];
    }
    // Forgets what was built (cheaply: only the entries used).
    void clear() {
        for (const std::uint32_t index : m_used) m_slot[index] = -1;
        m_used.clear();
        m_triangles.clear();
    }

private:
    std::vector<std::int32_t> m_slot;  ///< per segment: index into m_triangles, or -1
    std::deque<Triangle> m_triangles;  ///< a deque: references stay valid as it grows
    std::vector<std::uint32_t> m_used;  ///< segments with a slot
};

}  // namespace streak::exposure
