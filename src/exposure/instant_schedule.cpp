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
    // Row y is open over [s, s + D], s = (1 - D) y / (H - 1): cell [c0, c1] meets the rows with
    // c0 - D < s < c1 (a curve that is closed at a window's end may leave them a weight of 0).
    const double d = shutter.rollingDuration, rowStep = height > 1 ? (1.0 - d) / double(height - 1) : 0.0;
    for (int k = 0; k < n; ++k) {
        m_times.push_back((float(k) + 0.5f) / float(n));
        const double c0 = double(k) / n, c1 = double(k + 1) / n;
        if (rowStep <= 0.0) {
            m_rows.emplace_back(0, height - 1);
            continue;
        }
        const int first = std::max(0, int(std::floor((c0 - d) / rowStep)));
        const int last = std::min(height - 1, int(std::ceil(c1 / rowStep)));
        m_rows.emplace_back(first, last);
    }
}

float InstantSchedule::weight(int k, int row) const {
    if (isUniform()) return 1.0f / float(m_times.size());
    const float n = float(m_times.size());
    return m_shutter.rowWindow(row, m_height).measure(float(k) / n, float(k + 1) / n);
}

}  // namespace streak::exposure
