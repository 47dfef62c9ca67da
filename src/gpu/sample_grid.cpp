#include "gpu/sample_grid.h"

#include <glm/vec4.hpp>

#include <vector>

namespace streak::gpu {

Image readSampleGrid(const GlTexture& samples, const SampleGrid& grid, float scale) {
    std::vector<glm::vec4> texels(grid.numSamples());
    glGetTextureImage(samples.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(glm::vec4)), texels.data());
    checkGlError("reading the image back");
    Image image(grid.width, grid.height);
    std::vector<float> alpha(image.pixels().size());
    const float norm = scale / float(grid.aa * grid.aa);
    for (int py = 0; py < grid.height; ++py)
        for (int px = 0; px < grid.width; ++px) {
            glm::vec4 sum(0.0f);
            for (int j = 0; j < grid.aa; ++j)
                for (int i = 0; i < grid.aa; ++i) sum += texels[std::size_t(py * grid.aa + j) * grid.samplesWide() + std::size_t(px * grid.aa + i)];
            image.pixels()[std::size_t(py) * grid.width + px] = glm::vec3(sum) * norm;
            alpha[std::size_t(py) * grid.width + px] = sum.w * norm;
        }
    image.setAlpha(std::move(alpha));
    return image;
}

}  // namespace streak::gpu
