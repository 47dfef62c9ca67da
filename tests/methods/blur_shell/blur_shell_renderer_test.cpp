#include "methods/blur_shell/blur_shell_renderer.h"

#include "image/metrics.h"
#include "scene/blur_shell.h"
#include "scene/builtin_scenes.h"
#include "support/render.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace streak {
namespace {

// The sphere scene with plain colours (no textures): unlit, a pixel's colour is its albedo. The
// sphere's vertex colours vary over it, so overlapping strips differ and blending order shows.
Scene plainSphere(const std::string& squash = "0") {
    OptionMap options;
    options.set("squash", squash);
    Scene scene = makeBuiltinScene("sphere", options);
    for (Mesh& mesh : scene.meshes)
        if (mesh.name == "sphere")
            for (std::size_t v = 0; v < mesh.numVertices(); ++v) {
                const glm::vec3 n = mesh.normals[v];
                mesh.colors.push_back(glm::vec4(0.5f + 0.5f * n.y, 0.5f + 0.5f * n.z, 0.6f - 0.4f * n.x, 1.0f));
            }
    scene.materials[0].baseColor = {0.9f, 0.35f, 0.2f};
    scene.materials[1].baseColor = {0.15f, 0.3f, 0.8f};
    for (Material& m : scene.materials) m.baseColorTexture = -1;
    scene.textures.clear();
    validateScene(scene);
    return scene;
}

struct Hit {
    float distance;
    glm::vec3 bary;
    std::size_t mesh, triangle;
};

// Moller-Trumbore, both faces: the barycentrics where the ray meets the triangle's plane (in
// front of the origin), inside or not.
std::optional<Hit> intersectPlane(const glm::vec3& origin, const glm::vec3& dir, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(dir, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) return std::nullopt;
    const glm::vec3 s = origin - a;
    const float u = glm::dot(s, p) / det;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(dir, q) / det, t = glm::dot(e2, q) / det;
    if (t <= 0.0f) return std::nullopt;
    return Hit{t, {1.0f - u - v, u, v}, 0, 0};
}

// The hits of one ray through raster point (x, y) of the shell scene at shutter close: the
// nearest opaque one, and every shell hit in front of it in submission order.
struct RayHits {
    std::optional<Hit> opaque;
    std::vector<Hit> layers;

    bool seesTheSameAs(const RayHits& other) const {
        auto id = [](const Hit& h) { return std::pair{h.mesh, h.triangle}; };
        if (opaque.has_value() != other.opaque.has_value() || (opaque && id(*opaque) != id(*other.opaque))) return false;
        return std::equal(layers.begin(), layers.end(), other.layers.begin(), other.layers.end(),
                          [&](const Hit& a, const Hit& b) { return id(a) == id(b); });
    }
};

RayHits castRay(const Scene& scene, std::size_t firstShellMesh, float rasterX, float rasterY, int width, int height) {
    const glm::mat4 worldFromView = glm::inverse(scene.camera.viewFromWorld(1.0f));
    const float tanHalf = std::tan(scene.camera.verticalFov * 0.5f), aspect = float(width) / float(height);
    const float x = rasterX / float(width) * 2.0f - 1.0f, y = 1.0f - rasterY / float(height) * 2.0f;
    const glm::vec3 origin(worldFromView[3]);
    const glm::vec3 dir = glm::normalize(glm::mat3(worldFromView) * glm::vec3(x * aspect * tanHalf, y * tanHalf, -1.0f));
    RayHits hits;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            const glm::uvec3 tri = mesh.triangles[t];
            std::optional<Hit> hit = intersectPlane(origin, dir, mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]);
            if (!hit || std::min({hit->bary.x, hit->bary.y, hit->bary.z}) < 0.0f) continue;
            hit->mesh = m, hit->triangle = t;
            if (m >= firstShellMesh) hits.layers.push_back(*hit);
            else if (!hits.opaque || hit->distance < hits.opaque->distance) hits.opaque = hit;
        }
    }
    std::erase_if(hits.layers, [&](const Hit& h) { return hits.opaque && h.distance >= hits.opaque->distance; });
    return hits;
}

// An independent reference: a ray through the pixel centre of the shell scene (unlit), the
// nearest opaque hit, then the shell's hits in front of it blended in submission order (or
// sorted front to back). Pixels where rays 1/64 pixel away see other triangles are left out
// (nullopt): rasterization (vertices snapped to 1/256 pixel) and ray casting may round them
// either way. The two interpolate a vertex alpha up to 1e-4 apart.
std::optional<glm::vec3> rayTraced(const ShellScene& shell, int px, int py, int width, int height, bool isSorted) {
    const Scene& scene = shell.scene;
    const float cx = float(px) + 0.5f, cy = float(py) + 0.5f, d = 1.0f / 64.0f;
    const RayHits hits = castRay(scene, shell.firstShellMesh, cx, cy, width, height);
    for (const auto& [ox, oy] : {std::pair{d, 0.0f}, std::pair{-d, 0.0f}, std::pair{0.0f, d}, std::pair{0.0f, -d}})
        if (!castRay(scene, shell.firstShellMesh, cx + ox, cy + oy, width, height).seesTheSameAs(hits)) return std::nullopt;
    glm::vec3 color = scene.background;
    std::vector<Hit> layers = hits.layers;
    auto shade = [&](const Hit& h) {
        const Mesh& mesh = scene.meshes[h.mesh];
        const glm::uvec3 tri = mesh.triangles[h.triangle];
        const glm::vec4 vertex = h.bary.x * mesh.color(tri.x) + h.bary.y * mesh.color(tri.y) + h.bary.z * mesh.color(tri.z);
        const Material& material = scene.materials[mesh.material];
        return glm::vec4(material.baseColor * glm::vec3(vertex), material.opacity * vertex.w);
    };
    if (hits.opaque) color = glm::vec3(shade(*hits.opaque));
    if (!isSorted) {
        for (const Hit& h : layers) {
            const glm::vec4 c = shade(h);
            color = c.w * glm::vec3(c) + (1.0f - c.w) * color;
        }
        return color;
    }
    std::stable_sort(layers.begin(), layers.end(), [](const Hit& a, const Hit& b) { return a.distance < b.distance; });
    glm::vec3 sum(0.0f);
    float transmittance = 1.0f;
    for (const Hit& h : layers) {
        const glm::vec4 c = shade(h);
        sum += transmittance * c.w * glm::vec3(c);
        transmittance *= 1.0f - c.w;
    }
    return sum + transmittance * color;
}

void expectMatchesRayTracing(const Scene& scene, bool isSorted) {
    const int width = 96, height = 72;
    OptionMap options;
    if (isSorted) options.set("blend", "sorted");
    RenderStats stats;
    const Image image = test::render("blur-shell", scene, width, height, options, &stats, ShadingMode::Unlit, 1, true);
    ASSERT_GT(stats.counter("shell_triangles"), 100.0);
    const ShellScene shell = makeShellScene(scene, buildBlurShell(scene, BlurShellOptions{}));
    int compared = 0, throughShell = 0;
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            const std::optional<glm::vec3> expected = rayTraced(shell, px, py, width, height, isSorted);
            if (!expected) continue;
            ++compared;
            const glm::vec3 got = image.at(px, py);
            throughShell += castRay(shell.scene, shell.firstShellMesh, float(px) + 0.5f, float(py) + 0.5f, width, height).layers.empty() ? 0 : 1;
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], (*expected)[c], 1e-3f) << px << "," << py;
        }
    EXPECT_GT(compared, width * height / 2);
    EXPECT_GT(throughShell, 300);  // the shell covers a good part of the image
}

TEST(BlurShellRenderer, BlendsTheShellInSubmissionOrderOverTheMeshAsARayCasterDoes) { expectMatchesRayTracing(plainSphere(), false); }

TEST(BlurShellRenderer, SortedBlendingMatchesARayCasterThatSortsByDistance) { expectMatchesRayTracing(plainSphere(), true); }

TEST(BlurShellRenderer, DeformingMeshMatchesTheRayCasterToo) { expectMatchesRayTracing(plainSphere("0.4"), false); }

// Alpha 0: the shell is there but shows nothing, so the image is the scene at shutter close.
TEST(BlurShellRenderer, WithNoAlphaItIsTheSceneAtShutterClose) {
    const Scene scene = plainSphere();
    RenderStats stats;
    const Image image = test::render("blur-shell", scene, 64, 48, test::withOption("alpha", "0"), &stats, ShadingMode::Unlit, 1, true);
    EXPECT_GT(stats.counter("shell_triangles"), 100.0);
    BlurShellOptions none;
    none.alpha = 0.0f;
    const ShellScene shell = makeShellScene(scene, buildBlurShell(scene, none));
    int compared = 0, onSphere = 0;
    for (int py = 0; py < 48; ++py)
        for (int px = 0; px < 64; ++px)
            if (const std::optional<glm::vec3> expected = rayTraced(shell, px, py, 64, 48, false)) {
                ++compared;
                onSphere += *expected != scene.materials[1].baseColor ? 1 : 0;
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(image.at(px, py)[c], (*expected)[c], 1e-3f) << px << "," << py;
            }
    EXPECT_GT(compared, 1000);
    EXPECT_GT(onSphere, 100);
}

TEST(BlurShellRenderer, NeedsTheTrailLoadedWithOneKeyPerUpdate) {
    OptionMap options;
    options.set("length", "0.5");
    options.set("subdivisions", "20");
    const std::unique_ptr<Renderer> renderer = createRenderer("blur-shell", options);
    const std::optional<AnimationTrail> trail = renderer->animationTrail();
    ASSERT_TRUE(trail.has_value());
    EXPECT_DOUBLE_EQ(trail->lengthSeconds, 0.5);
    EXPECT_EQ(trail->keys, 21);
    EXPECT_FALSE(createRenderer("accumulation", OptionMap{})->animationTrail().has_value());
}

}  // namespace
}  // namespace streak
