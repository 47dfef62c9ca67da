#include "raster/translucency.h"

#include <algorithm>

namespace streak::raster {

void compositeTranslucent(std::vector<TranslucentFragment>& fragments, std::span<const float> opaqueInvW,
                          std::span<glm::vec3> color, std::span<float> coverage) {
    std::stable_sort(fragments.begin(), fragments.end(), [](const TranslucentFragment& a, const TranslucentFragment& b) {
        return a.sample != b.sample ? a.sample < b.sample : a.invW > b.invW;
    });
    for (std::size_t i = 0; i < fragments.size();) {
        const std::uint32_t sample = fragments[i].sample;
        glm::vec3 sum(0.0f);
        float transmittance = 1.0f;
        for (; i < fragments.size() && fragments[i].sample == sample; ++i) {
            const TranslucentFragment& f = fragments[i];
            if (f.invW <= opaqueInvW[sample]) continue;
            sum += transmittance * f.alpha * f.color;
            transmittance *= 1.0f - f.alpha;
        }
        color[sample] = sum + transmittance * color[sample];
        coverage[sample] = 1.0f - transmittance * (1.0f - coverage[sample]);
    }
}

}  // namespace streak::raster
