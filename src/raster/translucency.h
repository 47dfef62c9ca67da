#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace streak::raster {

// A shaded fragment of a translucent surface at one sample.
struct TranslucentFragment {
    std::uint32_t sample = 0;  ///< caller's sample index
    float invW = 0.0f;         ///< 1 / view depth: larger is nearer
    glm::vec3 color{0.0f};     ///< linear, not premultiplied
    float alpha = 0.0f;
    std::uint32_t triangle = 0;  ///< caller's id of its surface (for the passes)
};

// Blends, per sample, the translucent fragments in front of its opaque surface over its colour,
// front to back: C = sum_i T_i a_i c_i + T_n C_opaque with T_i = prod_{j<i} (1 - a_j).
// Fragments behind (or at the depth of) the opaque surface are hidden. Sorts `fragments`.
// Equal depths keep submission order (stable), so results do not depend on threads. Each
// sample's coverage (1: its opaque surface, 0: the background) becomes 1 - T_n (1 - coverage).
void compositeTranslucent(std::vector<TranslucentFragment>& fragments, std::span<const float> opaqueInvW,
                          std::span<glm::vec3> color, std::span<float> coverage);

// What compositeTranslucent gave each surface, for the passes: once it has sorted `fragments`,
// calls show(fragment, share) for each that shows (in front of its sample's opaque surface),
// share being its weight in the sample's colour (T_i a_i), and sets transmittance[sample] to
// what they leave the opaque surface behind them (T_n), for the samples with fragments.
template <class Show>
void forEachCompositedFragment(const std::vector<TranslucentFragment>& sorted, std::span<const float> opaqueInvW,
                               std::span<float> transmittance, Show&& show) {
    for (std::size_t i = 0; i < sorted.size();) {
        const std::uint32_t sample = sorted[i].sample;
        float t = 1.0f;
        for (; i < sorted.size() && sorted[i].sample == sample; ++i) {
            const TranslucentFragment& f = sorted[i];
            if (f.invW <= opaqueInvW[sample]) continue;
            show(f, t * f.alpha);
            t *= 1.0f - f.alpha;
        }
        transmittance[sample] = t;
    }
}

}  // namespace streak::raster
