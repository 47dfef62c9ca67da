#include "scene/flat_geometry.h"
#include "scene/shading.h"
#include "support/test_scenes.h"
#include "util/error.h"

#include <gtest/gtest.h>

namespace streak {

namespace {

// One 2x1 texture: left texel alpha 0.25, right texel alpha 0.75, both white.
Scene sceneWithAlphaTexture(AlphaMode mode, float opacity) {
    Scene scene = test::emptyScene();
    scene.textures.push_back(Texture::fromLinear(2, 1, {glm::vec4(1, 1, 1, 0.25f), glm::vec4(1, 1, 1, 0.75f)},
                                                 WrapMode::ClampToEdge, WrapMode::ClampToEdge));
    Material m;
    m.baseColor = glm::vec3(0.5f, 1.0f, 1.0f);
    m.baseColorTexture = 0;
    m.opacity = opacity;
    m.alphaMode = mode;
    scene.materials.push_back(m);
    return scene;
}

}  // namespace

TEST(Material, AlphaModesDecideTranslucencyAndAlpha) {
    Material m;
    EXPECT_FALSE(m.isTranslucent());
    EXPECT_EQ(m.alphaOf(0.1f), 1.0f);  // Opaque ignores the point's alpha
    m.opacity = 0.5f;
    EXPECT_TRUE(m.isTranslucent());
    EXPECT_EQ(m.alphaOf(0.1f), 0.5f);
    m.opacity = 1.0f;
    m.alphaMode = AlphaMode::Blend;
    EXPECT_TRUE(m.isTranslucent());
    EXPECT_FLOAT_EQ(m.alphaOf(0.3f), 0.3f);
    m.alphaMode = AlphaMode::Mask;
    m.alphaCutoff = 0.3f;
    EXPECT_TRUE(m.isTranslucent());
    EXPECT_EQ(m.alphaOf(0.3f), 1.0f);  // >= cutoff is opaque (glTF)
    EXPECT_EQ(m.alphaOf(0.29f), 0.0f);
    m.opacity = 0.5f;                  // base colour alpha multiplies before the cut
    EXPECT_EQ(m.alphaOf(0.59f), 0.0f);
    EXPECT_EQ(m.alphaOf(0.61f), 1.0f);
}

TEST(MaterialAlbedo, MultipliesBaseTextureAndVertexColourAndCutsMasks) {
    const glm::vec2 left(0.25f, 0.5f), right(0.75f, 0.5f);
    const glm::vec4 vertex(0.5f, 1.0f, 0.25f, 0.8f);
    const Scene blend = sceneWithAlphaTexture(AlphaMode::Blend, 1.0f);
    const ShadedColor b = materialAlbedo(blend, 0, right, {}, vertex);
    EXPECT_FLOAT_EQ(b.color.x, 0.25f);
    EXPECT_FLOAT_EQ(b.color.y, 1.0f);
    EXPECT_FLOAT_EQ(b.color.z, 0.25f);
    EXPECT_FLOAT_EQ(b.alpha, 0.75f * 0.8f);
    // Mask with cutoff 0.5: 0.75 * 0.8 = 0.6 passes, 0.25 * 0.8 does not.
    const Scene mask = sceneWithAlphaTexture(AlphaMode::Mask, 1.0f);
    EXPECT_EQ(materialAlbedo(mask, 0, right, {}, vertex).alpha, 1.0f);
    EXPECT_EQ(materialAlbedo(mask, 0, left, {}, vertex).alpha, 0.0f);
    // Without a vertex colour the default is white.
    EXPECT_FLOAT_EQ(materialAlbedo(blend, 0, left).alpha, 0.25f);
    const Scene opaque = sceneWithAlphaTexture(AlphaMode::Opaque, 1.0f);
    EXPECT_EQ(materialAlbedo(opaque, 0, left, {}, vertex).alpha, 1.0f);
}

TEST(FlatGeometry, InterpolatesVertexColoursIntoTheSurfacePoint) {
    Scene scene = test::emptyScene();
    const std::uint32_t white = test::addMaterial(scene, glm::vec3(1.0f));
    const test::PixelCamera cam{8, 8, 2.0f};
    test::addPixelQuad(scene, cam, white, 1, 1, 6, 6);
    scene.meshes[0].colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 0.5f}, {1, 1, 1, 1}};
    validateScene(scene);
    const FlatGeometry geometry(scene);
    const FlatTriangle& tri = geometry.triangles()[0];  // vertices 0, 1, 2
    const glm::vec3 bary(0.5f, 0.25f, 0.25f);
    const glm::vec4 expected(0.5f, 0.25f, 0.25f, 0.875f);
    EXPECT_EQ(geometry.vertexColorAt(tri, bary), expected);
    const SurfacePoint p = geometry.surfacePoint(tri, geometry.cornersAt(tri, 0.0f), geometry.cornerNormalsAt(tri, 0.0f), bary, bary,
                                                 bary, true);
    EXPECT_EQ(p.vertexColor, expected);
    const ShadedColor c = shadeSurface(scene, ShadingMode::Unlit, p, glm::vec3(0.0f));
    EXPECT_FLOAT_EQ(c.color.x, 0.5f);
    EXPECT_FLOAT_EQ(c.color.y, 0.25f);
    EXPECT_EQ(c.alpha, 1.0f);  // opaque material: vertex alpha ignored
}

TEST(ValidateScene, RejectsMisSizedColoursAndBadAlphaSettings) {
    Scene scene = test::emptyScene();
    test::addMaterial(scene, glm::vec3(1.0f));
    test::addPixelQuad(scene, test::PixelCamera{8, 8, 2.0f}, 0, 1, 1, 4, 4);
    Scene badColors = scene;
    badColors.meshes[0].colors.assign(3, glm::vec4(1.0f));
    EXPECT_THROW(validateScene(badColors), Error);
    Scene badCutoff = scene;
    badCutoff.materials[0].alphaCutoff = 1.5f;
    EXPECT_THROW(validateScene(badCutoff), Error);
    Scene badOpacity = scene;
    badOpacity.materials[0].opacity = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(validateScene(badOpacity), Error);
    scene.meshes[0].colors.assign(4, glm::vec4(1.0f));
    EXPECT_NO_THROW(validateScene(scene));
}

}  // namespace streak
