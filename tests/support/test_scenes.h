#pragma once

#include "scene/builtin_scenes.h"
#include "scene/scene.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace streak::test {

// Tiny hand-made scenes for tests: a static camera at the origin looking down -z with a 90
// degree vertical field of view, so a point at depth d maps to raster coordinates by
// worldXAt / worldYAt below, and positions can be stated in pixels.
struct PixelCamera {
    int width;
    int height;
    float depth;  ///< distance of the plane where positions are given

    float aspect() const { return float(width) / float(height); }
    // World x at raster x (pixels from the left edge) on the plane z = -depth.
    float worldX(float rasterX) const { return (2.0f * rasterX / float(width) - 1.0f) * depth * aspect(); }
    // World y at raster y (pixels from the top edge).
    float worldY(float rasterY) const { return (1.0f - 2.0f * rasterY / float(height)) * depth; }
    glm::vec3 at(float rasterX, float rasterY) const { return {worldX(rasterX), worldY(rasterY), -depth}; }
};

// A built-in scene with its options, validated as the command line would.
inline Scene validBuiltin(const std::string& name, OptionMap options = OptionMap()) {
    Scene scene = makeBuiltinScene(name, std::move(options));
    validateScene(scene);
    return scene;
}

inline Scene emptyScene(glm::vec3 background = glm::vec3(0.0f)) {
    Scene scene;
    scene.name = "test";
    scene.camera.verticalFov = 1.5707963f;  // 90 degrees
    scene.camera.open = CameraPose::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    scene.camera.close = scene.camera.open;
    scene.background = background;
    return scene;
}

inline std::uint32_t addMaterial(Scene& scene, glm::vec3 color, float opacity = 1.0f) {
    Material m;
    m.baseColor = color;
    m.opacity = opacity;
    m.doubleSided = true;
    scene.materials.push_back(m);
    return std::uint32_t(scene.materials.size() - 1);
}

// A quad with corners given at t = 0 and t = 1 (linear motion), counter-clockwise as seen by
// the camera when given in order top-left, bottom-left, bottom-right, top-right.
inline void addMovingQuad(Scene& scene, std::uint32_t material, const std::array<glm::vec3, 4>& open,
                          const std::array<glm::vec3, 4>& close) {
    Mesh mesh;
    mesh.material = material;
    mesh.numKeys = 2;
    for (const glm::vec3& p : open) mesh.positions.push_back(p);
    for (const glm::vec3& p : close) mesh.positions.push_back(p);
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(mesh);
}

// A 256 x 4 texture, a linear ramp along u (red = (x + 1/2) / 256 at texel centres, so red = u
// under bilinear lookups inside), constant along v; returns its index.
inline int addRampTexture(Scene& scene) {
    std::vector<glm::vec4> texels(256 * 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 256; ++x) texels[std::size_t(y) * 256 + x] = glm::vec4((float(x) + 0.5f) / 256.0f, 0.0f, 0.0f, 1.0f);
    scene.textures.push_back(Texture::fromLinear(256, 4, std::move(texels), WrapMode::ClampToEdge, WrapMode::ClampToEdge));
    return int(scene.textures.size()) - 1;
}

// An axis-aligned quad of raster rectangle [x0,x1] x [y0,y1] at the camera's depth, moved by
// (dx, dy) pixels over the shutter.
inline void addPixelQuad(Scene& scene, const PixelCamera& cam, std::uint32_t material, float x0, float y0, float x1, float y1,
                         float dx = 0.0f, float dy = 0.0f) {
    addMovingQuad(scene, material, {cam.at(x0, y0), cam.at(x0, y1), cam.at(x1, y1), cam.at(x1, y0)},
                  {cam.at(x0 + dx, y0 + dy), cam.at(x0 + dx, y1 + dy), cam.at(x1 + dx, y1 + dy), cam.at(x1 + dx, y0 + dy)});
}

// The raster square [lo, hi]^2 of a size x size image at depth 2 as two single-triangle meshes
// split along the diagonal x = y (raster), which runs through every pixel centre and every grid
// sample on it; both move by (d, d) pixels over the shutter, along the diagonal, so it stays on
// those samples at every time (its edge functions there are exact zeros). `upper` colours the
// triangle right of the diagonal (x > y), whose left edge it is: the top-left rule gives it the
// samples on the diagonal.
inline Scene diagonalSplitSquare(int size, float lo, float hi, float d, glm::vec3 upper, glm::vec3 lower, float opacity) {
    Scene scene = emptyScene();
    const PixelCamera cam{size, size, 2.0f};
    const std::array<std::uint32_t, 2> materials{addMaterial(scene, upper, opacity), addMaterial(scene, lower, opacity)};
    // Corners top-left, bottom-left, bottom-right, top-right (counter-clockwise on screen).
    const std::array<glm::vec2, 4> corners{glm::vec2(lo, lo), glm::vec2(lo, hi), glm::vec2(hi, hi), glm::vec2(hi, lo)};
    const std::array<std::array<int, 3>, 2> halves{{{0, 2, 3}, {0, 1, 2}}};
    for (int h = 0; h < 2; ++h) {
        Mesh mesh;
        mesh.material = materials[std::size_t(h)];
        for (const float shift : {0.0f, d})
            for (const int c : halves[std::size_t(h)]) mesh.positions.push_back(cam.at(corners[std::size_t(c)].x + shift, corners[std::size_t(c)].y + shift));
        mesh.triangles = {{0, 1, 2}};
        scene.meshes.push_back(mesh);
    }
    validateScene(scene);
    return scene;
}

// diagonalSplitSquare's closed form at pixel (px, py) over black, for the N x N grid of cell
// centres (RenderSettings::isGridPattern) of a square that covers the pixel all shutter: each
// sample shows the triangle that owns it, once, its colour times the opacity.
inline glm::vec3 diagonalSplitPixel(int px, int py, int aa, glm::vec3 upper, glm::vec3 lower, float opacity) {
    glm::vec3 sum(0.0f);
    for (int j = 0; j < aa; ++j)
        for (int i = 0; i < aa; ++i) {
            const float x = float(px) + (float(i) + 0.5f) / float(aa), y = float(py) + (float(j) + 0.5f) / float(aa);
            sum += x >= y ? upper : lower;
        }
    return opacity * sum / float(aa * aa);
}

// Red moves from depth 2 to 4, green from 4 to 2, both covering an 8x8 image.
inline Scene crossingQuads() {
    Scene scene = emptyScene();
    const PixelCamera c2{8, 8, 2.0f}, c4{8, 8, 4.0f};
    const std::uint32_t red = addMaterial(scene, {1, 0, 0}), green = addMaterial(scene, {0, 1, 0});
    auto corners = [](const PixelCamera& c) { return std::array<glm::vec3, 4>{c.at(-4, -4), c.at(-4, 12), c.at(12, 12), c.at(12, -4)}; };
    addMovingQuad(scene, red, corners(c2), corners(c4));
    addMovingQuad(scene, green, corners(c4), corners(c2));
    validateScene(scene);
    return scene;
}

// A 16 x 4 image of the passes' closed form: "wall" (material "grey") at depth 3 covers x < 6;
// "sweeper" (material "white") at depth 2, in front of it, has its right edge sweep x from 2 to
// 14 over the shutter; the background is 0.2. At pixel centre x_c the sweeper covers
// s = (14 - x_c) / 12 of the shutter (clamped), the wall the rest where x_c < 6 (expectedAt).
inline constexpr int kSweptWallWidth = 16, kSweptWallHeight = 4;
inline Scene sweptWall() {
    Scene scene = emptyScene(glm::vec3(0.2f));
    const std::uint32_t grey = addMaterial(scene, glm::vec3(0.5f)), white = addMaterial(scene, glm::vec3(1.0f));
    scene.materials[grey].name = "grey", scene.materials[white].name = "white";
    addPixelQuad(scene, PixelCamera{kSweptWallWidth, kSweptWallHeight, 3.0f}, grey, -20.0f, -1.0f, 6.0f, 5.0f);
    scene.meshes.back().name = "wall";
    addPixelQuad(scene, PixelCamera{kSweptWallWidth, kSweptWallHeight, 2.0f}, white, -30.0f, -1.0f, 2.0f, 5.0f, 12.0f, 0.0f);
    scene.meshes.back().name = "sweeper";
    validateScene(scene);
    return scene;
}

// Each one's share of pixel column px (at its centre) in sweptWall().
struct Expected {
    float sweeper, wall;
};
inline Expected expectedAt(int px) {
    const float xc = float(px) + 0.5f, sweeper = std::clamp((14.0f - xc) / 12.0f, 0.0f, 1.0f);
    return {sweeper, xc < 6.0f ? 1.0f - sweeper : 0.0f};
}

}  // namespace streak::test
