#include "raster/translucency.h"

#include <gtest/gtest.h>

namespace streak::raster {

TEST(CompositeTranslucent, BlendsFrontToBackOverOpaque) {
    // Sample 0: opaque blue at 1/w = 0.1; red (a = 0.5) at 0.5 and green (a = 0.25) at 0.3 in
    // front, submitted back to front; a fragment behind the opaque surface is hidden.
    // C = 0.5 red + 0.5 (0.25 green + 0.75 blue) = (0.5, 0.125, 0.375).
    std::vector<TranslucentFragment> fragments{
        {0, 0.3f, {0, 1, 0}, 0.25f}, {0, 0.05f, {1, 1, 1}, 0.9f}, {0, 0.5f, {1, 0, 0}, 0.5f}, {1, 0.2f, {1, 1, 1}, 0.5f}};
    std::vector<float> opaqueInvW{0.1f, 0.0f};
    std::vector<glm::vec3> color{{0, 0, 1}, {0, 0, 0}};
    std::vector<float> coverage{1.0f, 0.0f};
    compositeTranslucent(fragments, opaqueInvW, color, coverage);
    EXPECT_FLOAT_EQ(color[0].x, 0.5f);
    EXPECT_FLOAT_EQ(color[0].y, 0.125f);
    EXPECT_FLOAT_EQ(color[0].z, 0.375f);
    // Sample 1: white at a = 0.5 over the black background.
    EXPECT_FLOAT_EQ(color[1].x, 0.5f);
    // Coverage: the opaque sample stays covered; the other is covered by its layer's opacity.
    EXPECT_FLOAT_EQ(coverage[0], 1.0f);
    EXPECT_FLOAT_EQ(coverage[1], 0.5f);
}

}  // namespace streak::raster
