#pragma once

#include "scene/shutter.h"

#include <utility>
#include <vector>

namespace streak::exposure {

// InstantSchedule is which instants a method that averages whole frames renders (accumulation
// and its GL twin), and how much each counts in each image row:
//
// - global shutter: S instants at the midpoints of S equal shares of the curve's exposure
//   (stratified inverse CDF: for a box, (s + 1/2) / S), each weighing 1/S in every row;
// - rolling shutter (D < 1): ceil(S / D) evenly spaced instants, each weighing in a row the
//   exposure of its cell of time in that row's window, so every row's weights still sum to 1
//   and a frame only touches the rows whose windows it falls in.
class InstantSchedule {
public:
    InstantSchedule(const Shutter& shutter, int samples, int height);

    int numInstants() const { return int(m_times.size()); }
    float time(int k) const { return m_times[std::size_t(k)]; }
    // Every row weighs every instant 1 / numInstants(): sum, then scale once.
    bool isUniform() const { return !m_shutter.isRolling(); }
    // Instant k's weight in `row`; the rows [first, last] where it is non-zero.
    float weight(int k, int row) const;
    std::pair<int, int> rows(int k) const { return m_rows[std::size_t(k)]; }

private:
    const Shutter& m_shutter;
    int m_height;
    std::vector<float> m_times;
    std::vector<std::pair<int, int>> m_rows;
};

}  // namespace streak::exposure
