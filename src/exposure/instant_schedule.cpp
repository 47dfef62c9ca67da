#include "exposure/instant_schedule.h"

#include <algorithm>
#include <cmath>

namespace streak::exposure {

InstantSchedule::InstantSchedule(const Shutter& shutter, int samples, int height) : m_shutter(shutter), m_height(height) {
    if (!shutter.isRolling()) {
        const ShutterWindow window = shutter.rowWindow(0, height);
        for (int s = 0; s < samples; ++s) m_times.push_back(window.timeAt((float(s) + 0.5f) / float(samples)));
        m_rows.assign(m_times.size(), {0, height - 1});
        return;
    }
    const int n = int(std::ceil(double(samples) / double(shutter.rollingDuration)));
    for (int k = 0; k < n; ++k) m_times.push_back((float(k) + 0.5f) / float(n));
    for (int k = 0; k < n; ++k) {
        // Rows open at (1 - D) y / (H - 1): those whose window [start, start + D] meets the cell.
        int first = height, last = -1;
        for (int y = 0; y < height; ++y)
            if (weight(k, y) > 0.0f) first = std::min(first, y), last = std::max(last, y);
        m_rows.emplace_back(first, last);
    }
}

float InstantSchedule::weight(int k, int row) const {
    if (isUniform()) return 1.0f / float(m_times.size());
    const float n = float(m_times.size());
    return m_shutter.rowWindow(row, m_height).measure(float(k) / n, float(k + 1) / n);
}

}  // namespace streak::exposure
