#include "exposure/span_shading.h"
#include "support/test_scenes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>

namespace streak::exposure {

namespace {

// A point whose uv, position and normal are given functions of time, with a fixed footprint.
class ScriptedPoint final : public MovingSurfacePoint {
public:
    std::function<glm::vec2(float)> uv = [](float) { return glm::vec2(0.5f); };
    std::function<glm::vec3(float)> normal = [](float) { return glm::vec3(0, 0, 1); };
    glm::vec2 footprint{1.0f / 1024.0f, 0.0f};
    std::optional<glm::vec2> footprintDown;  ///< duvdy; else footprint with its axes swapped
    std::uint32_t material = 0;
    bool saysMaterial = false;  ///< materialIndex() tells it, as the methods' points do
    std::function<glm::vec4(float)> vertexColor = [](float) { return glm::vec4(1.0f); };
    mutable int evaluations = 0, footprints = 0;  ///< at() calls, and those asking for a footprint
    bool saysStill = false;  ///< isStill() says so, as a method's point does where nothing moves

    int materialIndex() const override { return saysMaterial ? int(material) : -1; }
    bool isStill(float, float) const override { return saysStill; }
    bool at(float t, bool withFootprint, SurfacePoint& out) const override {
        ++evaluations, footprints += withFootprint;
        out = {};
        out.vertexColor = vertexColor(t);
        out.uv = uv(t);
        out.normal = normal(t);
        out.position = glm::vec3(0.0f);
        out.material = material;
        if (withFootprint) out.duvdx = footprint, out.duvdy = footprintDown.value_or(glm::vec2(footprint.y, footprint.x));
        return true;
    }
};

// A 256-texel linear ramp along u (red = (x + 1/2) / 256 at texel centres), constant along v.
Scene rampScene() {
    Scene scene = test::emptyScene();
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[m].baseColorTexture = test::addRampTexture(scene);
    return scene;
}

// A 256 x 256 texture, dark left of u = 1/2 and light right of it, with a dark line along
// v = 1/2: a sharp edge both ways, where any difference in filtering shows.
Scene stepScene() {
    Scene scene = test::emptyScene();
    std::vector<glm::vec4> texels(256 * 256);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) texels[std::size_t(y) * 256 + x] = glm::vec4(x < 128 || y == 128 ? 0.05f : 0.9f, 0.0f, 0.0f, 1.0f);
    scene.textures.push_back(Texture::fromLinear(256, 256, std::move(texels), WrapMode::ClampToEdge, WrapMode::ClampToEdge));
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[m].baseColorTexture = 0;
    return scene;
}

}  // namespace

TEST(ShadeTimeSpan, AStillPointShadesAsAnInstantDoes) {
    // A span of a point that does not move is that point's instant: the same texels, the same
    // filter, whatever the footprint. Magnified (under a texel per sample, anisotropic: the
    // wall of builtin:fence at 1024x768, which lost 44 dB to a finer filter than the instant's),
    // about one texel, and minified.
    const Scene scene = stepScene();
    for (const float scale : {0.5f, 0.8f, 1.0f, 1.3f, 3.0f}) {
        for (const glm::vec2 uv : {glm::vec2(128.3f / 256.0f, 0.3f), glm::vec2(0.7f, 128.6f / 256.0f), glm::vec2(127.8f / 256.0f, 128.2f / 256.0f)}) {
            ScriptedPoint point;
            point.uv = [uv](float) { return uv; };
            point.footprint = glm::vec2(0.7f * scale / 256.0f, 0.0f);
            point.footprintDown = glm::vec2(0.0f, 1.1f * scale / 256.0f);
            SurfacePoint instant;
            ASSERT_TRUE(point.at(0.5f, true, instant));
            const ShadedColor still = shadeSurface(scene, ShadingMode::Unlit, instant, glm::vec3(0.0f, 0.0f, 1.0f));
            for (const SpanTextureFilter filter : {SpanTextureFilter::Taps, SpanTextureFilter::Swept}) {
                SpanShadingSettings settings;
                settings.textureFilter = filter;
                const ShadedColor span = shadeTimeSpan(scene, ShadingMode::Unlit, 0.2f, 0.9f, point, settings);
                EXPECT_NEAR(span.color.x, still.color.x, 1e-6f)
                    << "scale " << scale << " uv " << uv.x << "," << uv.y << " swept " << (filter == SpanTextureFilter::Swept);
            }
        }
    }
}

TEST(ShadeTimeSpan, AStillSpanIsShadedAsTheMovingPathShadesAPointThatDoesNotMove) {
    // A point that says it is still is shaded as one instant (a rasterizer's shading); the same
    // point not saying so goes through the moving path (the span's lighting, its swept lookup
    // or taps), which must come to the same colour and opacity: lit, unlit, the normal pass
    // (whose opacity is the unlit shading's, its texture filtered as the beauty's), and masked
    // and blended materials, over a texture whose alpha alternates texel by texel.
    Scene scene = stepScene();
    std::vector<glm::vec4> texels(256 * 256);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) texels[std::size_t(y) * 256 + x] = glm::vec4(x < 128 ? 0.05f : 0.9f, 0.3f, 0.1f, x % 2 ? 0.3f : 1.0f);
    scene.textures[0] = Texture::fromLinear(256, 256, std::move(texels), WrapMode::ClampToEdge, WrapMode::ClampToEdge);
    scene.camera.open.position = scene.camera.close.position = glm::vec3(0.3f, 0.2f, 2.0f);
    scene.materials[0].specular = 0.5f, scene.materials[0].shininess = 20.0f;
    for (const AlphaMode alphaMode : {AlphaMode::Opaque, AlphaMode::Mask, AlphaMode::Blend}) {
        scene.materials[0].alphaMode = alphaMode;
        for (const ShadingMode mode : {ShadingMode::Phong, ShadingMode::Unlit, ShadingMode::Normal}) {
            for (const SpanTextureFilter filter : {SpanTextureFilter::Taps, SpanTextureFilter::Swept}) {
                ScriptedPoint still, moving;
                for (ScriptedPoint* point : {&still, &moving}) {
                    point->uv = [](float) { return glm::vec2(128.4f / 256.0f, 0.3f); };
                    point->normal = [](float) { return glm::normalize(glm::vec3(0.2f, 0.3f, 1.0f)); };
                    point->vertexColor = [](float) { return glm::vec4(0.8f, 0.9f, 1.0f, 0.7f); };
                    point->footprint = glm::vec2(1.5f / 256.0f, 0.0f);
                    point->saysMaterial = true;
                }
                still.saysStill = true;
                SpanShadingSettings settings;
                settings.textureFilter = filter;
                const ShadedColor a = shadeTimeSpan(scene, mode, 0.1f, 0.8f, still, settings);
                const ShadedColor b = shadeTimeSpan(scene, mode, 0.1f, 0.8f, moving, settings);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.color[c], b.color[c], 1e-5f) << "mode " << int(mode) << " mask " << (alphaMode == AlphaMode::Mask);
                EXPECT_NEAR(a.alpha, b.alpha, 1e-6f) << "mode " << int(mode) << " alpha mode " << int(alphaMode);
                EXPECT_GT(a.color.x, 0.0f);
                EXPECT_LT(still.evaluations, moving.evaluations) << "the still point is shaded at one instant";
            }
        }
    }
}

TEST(ShadeTimeSpan, MeanOfALinearRampAlongAStraightPath) {
    // Bilinear filtering reproduces a linear ramp exactly (away from the clamped ends), and so
    // does every mip level of it: the mean over a uniform straight path is the ramp at the
    // path's middle, u = 0.45, whatever the taps and levels.
    const Scene scene = rampScene();
    ScriptedPoint point;
    point.uv = [](float t) { return glm::vec2(0.2f + 0.5f * t, 0.5f); };
    for (const SpanTextureFilter filter : {SpanTextureFilter::Taps, SpanTextureFilter::Swept}) {
        for (int k : {1, 4, 16}) {
            SpanShadingSettings settings;
            settings.maxTextureTaps = k;
            settings.textureFilter = filter;
            const ShadedColor c = shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, point, settings);
            EXPECT_NEAR(c.color.x, 0.45f, 2e-3f) << "k " << k;
            EXPECT_FLOAT_EQ(c.alpha, 1.0f);
        }
        // A sub-span: [0.5, 1] covers u in [0.45, 0.7].
        SpanShadingSettings settings;
        settings.textureFilter = filter;
        EXPECT_NEAR(shadeTimeSpan(scene, ShadingMode::Unlit, 0.5f, 1.0f, point, settings).color.x, 0.575f, 2e-3f);
    }
}

TEST(ShadeTimeSpan, TapsFollowTheTimeParameterisationNotTheStraightLine) {
    // uv accelerating along the ramp, u = 0.2 + 0.6 t^2: the time mean is 0.2 + 0.6 / 3 = 0.4,
    // while an average over the straight uv segment (the paper's) would give 0.5.
    const Scene scene = rampScene();
    ScriptedPoint point;
    point.uv = [](float t) { return glm::vec2(0.2f + 0.6f * t * t, 0.5f); };
    SpanShadingSettings settings;
    settings.maxTextureTaps = 64;
    settings.textureFilter = SpanTextureFilter::Taps;
    EXPECT_NEAR(shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, point, settings).color.x, 0.4f, 2e-3f);
    // The swept lookups follow it piece by piece: the path bends by 38 texels, so it is cut into
    // kMaxSweptPieces straight pieces of equal time, each the ramp at its chord's middle (the
    // trapezoid rule of u(t): 0.2 + 0.6 (1/3 + 1/(6 * 8^2)) = 0.4016). One straight lookup over
    // the whole path would be the straight line's 0.5.
    settings.textureFilter = SpanTextureFilter::Swept;
    EXPECT_NEAR(shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, point, settings).color.x, 0.4016f, 1e-3f);
}

namespace {

// A 256 x 256 texture whose red is a cosine of u with a period of `period` texels (mean 1/2,
// amplitude 1/2), constant along v; repeating.
Scene cosineScene(int period) {
    Scene scene = test::emptyScene();
    std::vector<glm::vec4> texels(256 * 256);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            texels[std::size_t(y) * 256 + x] = glm::vec4(0.5f + 0.5f * std::cos(2.0f * 3.14159265f * (float(x) + 0.5f) / float(period)), 0, 0, 1);
    scene.textures.push_back(Texture::fromLinear(256, 256, std::move(texels)));
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[m].baseColorTexture = 0;
    return scene;
}

}  // namespace

TEST(ShadeTimeSpan, SweptLookupIsTheBoxMeanAlongThePath) {
    // A point sweeping L texels of a cosine of period P at constant speed, at an angle to it, with
    // a footprint of a quarter texel (magnified: the filter is the path alone). Its time mean is
    // closed form: the cosine at the path's middle damped by sinc(L_u / P), L_u the path's extent
    // along u. The swept lookup (a box of the path's variance) and the taps both follow it, at
    // dampings from 0.9 down to 0.2 and a sign flip.
    const int period = 32;
    const Scene scene = cosineScene(period);
    for (const float length : {8.0f, 16.0f, 24.0f, 40.0f}) {
        for (const float angle : {0.0f, 0.5f, 1.0f}) {
            const glm::vec2 along = glm::vec2(std::cos(angle), std::sin(angle)) * length / 256.0f;
            const glm::vec2 middle(0.37f, 0.52f);
            ScriptedPoint point;
            point.uv = [=](float t) { return middle + (t - 0.5f) * along; };
            point.footprint = glm::vec2(0.25f / 256.0f, 0.0f);
            const float x = length * std::cos(angle) / float(period), pi = 3.14159265f;
            const float damping = x == 0.0f ? 1.0f : std::sin(pi * x) / (pi * x);
            const float expected = 0.5f + 0.5f * damping * std::cos(2.0f * pi * middle.x * 256.0f / float(period));
            for (const SpanTextureFilter filter : {SpanTextureFilter::Taps, SpanTextureFilter::Swept}) {
                SpanShadingSettings settings;
                settings.textureFilter = filter;
                const float got = shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, point, settings).color.x;
                EXPECT_NEAR(got, expected, 0.03f) << "L " << length << " angle " << angle << " swept " << (filter == SpanTextureFilter::Swept);
            }
        }
    }
}

TEST(ShadeTimeSpan, SweptLookupKeepsTheContrastAcrossItsPath) {
    // Stripes along the motion: a path of 24 texels along v over a cosine of u of period 8 texels,
    // with a footprint of one texel. Across the path nothing moves, so the stripes keep the
    // contrast an instant's lookup gives them (cosine peak and trough): the swept ellipse is long
    // along the path and as narrow as the footprint across it. A lookup as wide as the path is
    // long (an isotropic one at its length) would leave under a tenth of it. (With 16 taps, both
    // filters widen to 1.5 texels across: 0.83 of the contrast.)
    const Scene scene = cosineScene(8);
    auto shadeAt = [&](float u, SpanTextureFilter filter) {
        ScriptedPoint point;
        point.uv = [=](float t) { return glm::vec2(u, 0.2f + t * 24.0f / 256.0f); };
        point.footprint = glm::vec2(1.0f / 256.0f, 0.0f);
        SpanShadingSettings settings;
        settings.maxTextureTaps = 32;  // the methods' default: a tap per texel of the path
        settings.textureFilter = filter;
        return shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, point, settings).color.x;
    };
    ScriptedPoint still;
    still.footprint = glm::vec2(1.0f / 256.0f, 0.0f);
    for (const SpanTextureFilter filter : {SpanTextureFilter::Taps, SpanTextureFilter::Swept}) {
        // Texel centres 0 and 4 are the peak and the trough.
        still.uv = [](float) { return glm::vec2(0.5f / 256.0f, 0.3f); };
        const float stillPeak = shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, still).color.x;
        still.uv = [](float) { return glm::vec2(4.5f / 256.0f, 0.3f); };
        const float stillTrough = shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, still).color.x;
        const float contrast = shadeAt(0.5f / 256.0f, filter) - shadeAt(4.5f / 256.0f, filter);
        ASSERT_GT(stillPeak - stillTrough, 0.9f);
        EXPECT_GT(contrast, 0.95f * (stillPeak - stillTrough)) << "swept " << (filter == SpanTextureFilter::Swept);
    }
}

TEST(ShadeTimeSpan, LightingOfATurningNormalMatchesABruteForceMean) {
    // An untextured surface whose normal turns by 1.2 radians over the span, under the scene's
    // Phong light: the span's colour is the time mean of the shaded colour (brute force with
    // 20000 instants), within 0.5%.
    Scene scene = test::emptyScene();
    scene.light.toLight = glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f));
    scene.camera.open = scene.camera.close = CameraPose::lookAt(glm::vec3(0, 0, 5), glm::vec3(0.0f));
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(0.8f, 0.5f, 0.2f));
    scene.materials[m].specular = 0.5f;
    scene.materials[m].shininess = 16.0f;
    ScriptedPoint point;
    point.normal = [](float t) { const float a = -0.6f + 1.2f * t; return glm::vec3(std::sin(a), 0.0f, std::cos(a)); };
    glm::vec3 brute(0.0f);
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const float t = (float(i) + 0.5f) / float(n);
        brute += lightPhong(scene, scene.materials[m], scene.materials[m].baseColor, glm::vec3(0.0f), point.normal(t), true,
                            scene.camera.positionAt(t));
    }
    brute /= float(n);
    const ShadedColor c = shadeTimeSpan(scene, ShadingMode::Phong, 0.0f, 1.0f, point);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(c.color[i], brute[i], 5e-3f * brute[i]) << "channel " << i;
    // Simpson's three points alone, on a span this turning, are measurably off: more taps were
    // needed and taken.
    SpanShadingSettings coarse;
    coarse.maxLightingTaps = 1;
    const ShadedColor simpson = shadeTimeSpan(scene, ShadingMode::Phong, 0.0f, 1.0f, point, coarse);
    EXPECT_GT(glm::length(simpson.color - brute), glm::length(c.color - brute));
}

TEST(ShadeTimeSpan, AnUntexturedMaterialSkipsTheFootprintAndUnlitAllButTheMiddle) {
    // An untextured material's colour is its base colour times the middle's vertex colour, and
    // its light needs no texture footprint. Told the material, span shading asks for no
    // footprint, and unlit evaluates the point once; the colours are those of the point that does
    // not say its material, to the bit, in every mode. Lit under a turning normal, with a vertex
    // colour and alpha that change over the span.
    Scene scene = test::emptyScene();
    scene.light.toLight = glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f));
    scene.camera.open = scene.camera.close = CameraPose::lookAt(glm::vec3(0, 0, 5), glm::vec3(0.0f));
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(0.8f, 0.5f, 0.2f), 0.7f);
    scene.materials[m].alphaMode = AlphaMode::Blend;
    scene.materials[m].specular = 0.5f;
    for (const ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Phong, ShadingMode::Normal}) {
        ScriptedPoint told, untold;
        for (ScriptedPoint* p : {&told, &untold}) {
            p->material = m;
            p->normal = [](float t) { const float a = -0.4f + 0.8f * t; return glm::vec3(std::sin(a), 0.0f, std::cos(a)); };
            p->vertexColor = [](float t) { return glm::vec4(0.5f + 0.5f * t, 1.0f - t, 0.25f, 1.0f - 0.5f * t); };
        }
        told.saysMaterial = true;
        const ShadedColor fast = shadeTimeSpan(scene, mode, 0.1f, 0.7f, told);
        const ShadedColor full = shadeTimeSpan(scene, mode, 0.1f, 0.7f, untold);
        EXPECT_EQ(fast.color, full.color) << "mode " << int(mode);
        EXPECT_EQ(fast.alpha, full.alpha) << "mode " << int(mode);
        EXPECT_EQ(told.footprints, 0) << "mode " << int(mode);
        EXPECT_GT(untold.footprints, 0) << "mode " << int(mode);
        if (mode == ShadingMode::Unlit) { EXPECT_EQ(told.evaluations, 1); }
    }
    // The vertex colour and opacity are the middle's (t = 0.4), times the material's.
    ScriptedPoint point;
    point.material = m, point.saysMaterial = true;
    point.vertexColor = [](float t) { return glm::vec4(0.5f + 0.5f * t, 1.0f - t, 0.25f, 1.0f - 0.5f * t); };
    const ShadedColor c = shadeTimeSpan(scene, ShadingMode::Unlit, 0.1f, 0.7f, point);
    EXPECT_NEAR(c.color.x, 0.8f * 0.7f, 1e-6f);
    EXPECT_NEAR(c.color.y, 0.5f * 0.6f, 1e-6f);
    EXPECT_NEAR(c.alpha, 0.7f * 0.8f, 1e-6f);
}

TEST(ShadeTimeSpan, OpacityIsTheMeanTextureAlphaTimesTheMaterials) {
    // Texture alpha 1 on the left half, 0 on the right; a path over the whole width at
    // material opacity 0.5 gives 0.5 * 0.5. (Blend: an Opaque material ignores texture alpha.)
    Scene scene = test::emptyScene();
    std::vector<glm::vec4> texels(64);
    for (int x = 0; x < 64; ++x) texels[std::size_t(x)] = glm::vec4(1.0f, 1.0f, 1.0f, x < 32 ? 1.0f : 0.0f);
    scene.textures.push_back(Texture::fromLinear(64, 1, std::move(texels), WrapMode::ClampToEdge, WrapMode::ClampToEdge));
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f), 0.5f);
    scene.materials[m].baseColorTexture = 0;
    scene.materials[m].alphaMode = AlphaMode::Blend;
    ScriptedPoint point;
    point.uv = [](float t) { return glm::vec2(t, 0.5f); };
    point.footprint = glm::vec2(1.0f / 64.0f, 0.0f);
    for (const SpanTextureFilter filter : {SpanTextureFilter::Taps, SpanTextureFilter::Swept}) {
        SpanShadingSettings settings;
        settings.textureFilter = filter;
        scene.materials[m].alphaMode = AlphaMode::Blend;
        EXPECT_NEAR(shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, point, settings).alpha, 0.25f, 0.02f);
        // Mask at cutoff 0.5: each tap's alpha is 0 or 1 (0.5 * 1 passes, 0.5 * 0 does not), so
        // the span's alpha is the coverage, 0.5. (One swept lookup would average the alpha to
        // 0.5 first and cut all of it: a mask keeps the taps.)
        scene.materials[m].alphaMode = AlphaMode::Mask;
        EXPECT_NEAR(shadeTimeSpan(scene, ShadingMode::Unlit, 0.0f, 1.0f, point, settings).alpha, 0.5f, 0.04f)
            << "swept " << (filter == SpanTextureFilter::Swept);
    }
}

}  // namespace streak::exposure
