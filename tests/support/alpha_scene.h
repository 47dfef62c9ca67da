#pragma once

// A scene whose alpha has a closed form, and the checks every method's alpha is held to.

#include "image/image.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace streak::test {

// 16 x 8 pixels over a coloured background. Rows 0-3: a white quad whose right edge sweeps x
// from 2 to 14 over the shutter, so the centre x_c = p + 1/2 of pixel p is covered for
// (14 - x_c) / 12 of it. Rows 5-7: a static red pane of opacity 0.4 over pixels 4-11, which
// covers them by 0.4 (its colour over a transparent background is (0.4, 0, 0)).
struct AlphaScene {
    static constexpr int kWidth = 16, kHeight = 8;
    static constexpr float kPaneOpacity = 0.4f;

    static Scene make(glm::vec3 background) {
        const PixelCamera cam{kWidth, kHeight, 3.0f};
        Scene scene = emptyScene(background);
        addPixelQuad(scene, cam, addMaterial(scene, glm::vec3(1.0f)), -20.0f, -1.0f, 2.0f, 4.0f, 12.0f, 0.0f);
        addPixelQuad(scene, cam, addMaterial(scene, glm::vec3(1.0f, 0.0f, 0.0f), kPaneOpacity), 4.0f, 5.0f, 12.0f, 9.0f);
        validateScene(scene);
        return scene;
    }

    // The exact coverage of pixel (px, py) at one sample per pixel, at its centre.
    static float coverage(int px, int py) {
        if (py <= 3) return std::clamp((14.0f - (float(px) + 0.5f)) / 12.0f, 0.0f, 1.0f);
        if (py >= 5 && px >= 4 && px <= 11) return kPaneOpacity;
        return 0.0f;
    }
};

// Renders the AlphaScene with `method` over a coloured background and checks:
// - its colour over a transparent background (withTransparentBackground) is its render over
//   black, to rounding: the background's share is 1 - alpha;
// - its alpha is what its own white-on-black colour says: the sweeping quad's green channel and
//   the pane's red over its opacity;
// - when closedFormTolerance >= 0, its alpha is the closed form within it (a sampled method:
//   1/S; an exact one: rounding).
inline void expectAlphaIsCoverage(const std::string& method, const OptionMap& options, float closedFormTolerance) {
    SCOPED_TRACE(method);
    const glm::vec3 background(0.3f, 0.5f, 0.7f);
    const Image over = render(method, AlphaScene::make(background), AlphaScene::kWidth, AlphaScene::kHeight, options);
    const Image black = render(method, AlphaScene::make(glm::vec3(0.0f)), AlphaScene::kWidth, AlphaScene::kHeight, options);
    ASSERT_TRUE(over.hasAlpha());
    const Image transparent = withTransparentBackground(over, background);
    for (int py = 0; py < AlphaScene::kHeight; ++py)
        for (int px = 0; px < AlphaScene::kWidth; ++px) {
            SCOPED_TRACE("pixel " + std::to_string(px) + "," + std::to_string(py));
            const float alpha = over.alphaAt(px, py);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(transparent.at(px, py)[c], black.at(px, py)[c], 2e-5f);
            const glm::vec3 own = black.at(px, py);
            if (py <= 3) {
                EXPECT_NEAR(alpha, own.y, 2e-5f);
            } else {
                EXPECT_NEAR(alpha, own.x, 2e-5f);  // the pane is red 1: its red over black is its coverage
            }
            if (py == 4) {
                EXPECT_EQ(alpha, 0.0f);
            }
            if (closedFormTolerance >= 0.0f) {
                EXPECT_NEAR(alpha, AlphaScene::coverage(px, py), closedFormTolerance);
            }
        }
}

}  // namespace streak::test
