// Vertex colours and the glTF alpha modes, the same under every method.

#include "methods/registry.h"
#include "support/render.h"
#include "support/sanitized.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

namespace streak {

namespace {

bool isStochastic(std::string_view method) { return method == "stochastic" || method == "stochastic-gl"; }

// Each method with its default options, but stochastic (CPU and GL) with enough time samples
// per pixel (64) that stratified coverage is within 1/32.
Image render(const std::string& method, const Scene& scene, int width, int height) {
    return test::render(method, scene, width, height, isStochastic(method) ? test::withOption("samples", "64") : OptionMap());
}

// A white material whose texture is texels of the given alphas in one row (nearest texels
// are exact at their centres; bilinear in between).
std::uint32_t addMaskMaterial(Scene& scene, const std::vector<float>& alphas, WrapMode wrap) {
    std::vector<glm::vec4> texels;
    for (float a : alphas) texels.emplace_back(1.0f, 1.0f, 1.0f, a);
    scene.textures.push_back(Texture::fromLinear(int(alphas.size()), 1, texels, wrap, wrap));
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[m].baseColorTexture = int(scene.textures.size() - 1);
    scene.materials[m].alphaMode = AlphaMode::Mask;
    return m;
}

// Quad with uv (0,0) top-left to (1,1) bottom-right.
void setQuadUvs(Scene& scene) { scene.meshes.back().uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}}; }

}  // namespace

TEST(MaterialModes, VertexColoursTintAndMasksCutOutUnderEveryMethod) {
    // Blue backdrop. Left half: a quad with one vertex colour (1, 0.5, 0.25). Right half: a
    // Mask quad whose left four texels have alpha 0.3 and right four 0.7: cut at 0.5, the
    // backdrop shows through on x in [8, 12) and white covers [12, 16), with no blending.
    const test::PixelCamera c2{16, 16, 2.0f}, c3{16, 16, 3.0f}, c4{16, 16, 4.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, c4, test::addMaterial(scene, {0, 0, 1}), -1, -1, 17, 17);
    test::addPixelQuad(scene, c3, test::addMaterial(scene, glm::vec3(1.0f)), 0, 0, 8, 16);
    scene.meshes.back().colors.assign(4, glm::vec4(1.0f, 0.5f, 0.25f, 0.3f));
    test::addPixelQuad(scene, c2, addMaskMaterial(scene, {0.3f, 0.3f, 0.3f, 0.3f, 0.7f, 0.7f, 0.7f, 0.7f}, WrapMode::ClampToEdge), 8, 0, 16, 16);
    setQuadUvs(scene);
    validateScene(scene);
    for (const MethodInfo& method : registeredMethods()) {
        if (!test::runsHere(method.name)) continue;
        SCOPED_TRACE(std::string(method.name));
        const Image image = render(std::string(method.name), scene, 16, 16);
        for (int y : {2, 8, 13}) {
            EXPECT_NEAR(image.at(3, y).x, 1.0f, 1e-4f);
            EXPECT_NEAR(image.at(3, y).y, 0.5f, 1e-4f);
            EXPECT_NEAR(image.at(3, y).z, 0.25f, 1e-4f);
            EXPECT_NEAR(image.at(9, y).x, 0.0f, 1e-4f);  // masked out: the blue backdrop
            EXPECT_NEAR(image.at(9, y).z, 1.0f, 1e-4f);
            EXPECT_NEAR(image.at(14, y).x, 1.0f, 1e-4f);  // masked in: white
            EXPECT_NEAR(image.at(14, y).z, 1.0f, 1e-4f);
        }
    }
}

TEST(MaterialModes, MovingMaskAveragesToCoverage) {
    // A Mask quad of four-pixel stripes (alpha 1 on four texels, 0 on the next four) slides 8
    // pixels over a blue backdrop. Each pixel sees white for half the shutter: (0.5, 0.5, 1).
    // The methods that shade time spans (motion-path, analytic) average the cut alphas of a few
    // texture taps per texel of path (exposure/span_shading), split between the quad's two
    // triangles, so they get within 1/8; the reference methods sample 256 or 64 instants per
    // pixel, within 1/32.
    const test::PixelCamera c2{16, 4, 2.0f}, c4{16, 4, 4.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, c4, test::addMaterial(scene, {0, 0, 1}), -1, -1, 17, 5);
    std::vector<float> stripes;
    for (int i = 0; i < 32; ++i) stripes.push_back(float(i / 4 % 2));
    test::addPixelQuad(scene, c2, addMaskMaterial(scene, stripes, WrapMode::Repeat), -16.25f, -1, 15.75f, 5, 8.0f, 0.0f);
    setQuadUvs(scene);
    validateScene(scene);
    for (const MethodInfo& method : registeredMethods()) {
        if (!test::runsHere(method.name)) continue;
        SCOPED_TRACE(std::string(method.name));
        if (createRenderer(method.name, OptionMap{})->animationTrail()) continue;  // a trail (blur-shell), not a shutter average
        // The games' filter takes its velocities from the opaque surface behind a translucent
        // one: its known translucency failure (tests/methods/post_filter, BENCHMARKS).
        if (method.name.starts_with("post-filter")) continue;
        const Image image = render(std::string(method.name), scene, 16, 4);
        const bool isInstants = method.name == "accumulation" || isStochastic(method.name);
        const float tolerance = isInstants ? 1.0f / 32 : 1.0f / 8;
        for (int x : {2, 5, 9})
            for (int y : {1, 2}) {
                EXPECT_NEAR(image.at(x, y).x, 0.5f, tolerance) << x;
                EXPECT_NEAR(image.at(x, y).z, 1.0f, 1e-4f) << x;
            }
    }
}

}  // namespace streak
