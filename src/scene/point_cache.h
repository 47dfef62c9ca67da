#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace streak {

// A point cache: the positions of a mesh's vertices at a series of times, as Blender's Mesh
// Cache modifier reads them, from a PC2 or an MDD file. Between two samples a point moves on the
// line between them; before the first and after the last it stays there.
//
// PC2 (little-endian): "POINTCACHE2\0", version 1, the point count, the start frame and the
// frames between samples (floats), the sample count, then the points of each sample (3 floats
// each). MDD (big-endian): the frame count, the point count, each frame's time in seconds, then
// each frame's points; a file holding one block more than its frames starts with a rest pose
// (Blender's MDD export writes one), which is skipped.
class PointCache {
public:
    // Reads a .pc2 or .mdd file of at most maxBytes; `fps` turns PC2's frames into seconds.
    // Throws Error naming the file and the problem (unknown extension, bad header, a size that
    // does not match it).
    static PointCache read(const std::string& path, double fps, std::uint64_t maxBytes);
    // From memory (tests, and read above): `isMdd` picks the format, `name` starts error messages.
    static PointCache parse(std::span<const char> bytes, bool isMdd, double fps, const std::string& name);

    std::size_t numPoints() const { return m_numPoints; }
    std::size_t numSamples() const { return m_times.size(); }
    double firstTime() const { return m_times.front(); }  ///< seconds
    double lastTime() const { return m_times.back(); }    ///< seconds

    // The points `count` from `first` at `seconds` of animation time.
    void pointsAt(double seconds, std::size_t first, std::size_t count, std::span<glm::vec3> out) const;

private:
    std::size_t m_numPoints = 0;
    std::vector<double> m_times;        ///< seconds, increasing
    std::vector<glm::vec3> m_points;    ///< numSamples x numPoints
};

}  // namespace streak
