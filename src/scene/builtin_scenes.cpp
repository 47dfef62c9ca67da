#include "scene/builtin_scenes.h"

#include "util/error.h"
#include "util/random.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <string>

namespace streak {

namespace {

constexpr float kPi = 3.14159265358979f;

// LocalGeometry is a rigid shape in object space; placeMesh() turns it into a Mesh whose key
// poses follow worldFromObject(t), so every built-in scene states its motion as a transform.
struct LocalGeometry {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::uvec3> triangles;

    // A quad centred at c spanning 2u x 2v, facing u x v (counter-clockwise seen from there).
    void addQuad(const glm::vec3& c, const glm::vec3& u, const glm::vec3& v, float uvScale = 1.0f) {
        const auto base = std::uint32_t(positions.size());
        const glm::vec3 n = glm::normalize(glm::cross(u, v));
        const std::array<glm::vec2, 4> corners{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
        for (const glm::vec2& k : corners) {
            positions.push_back(c + k.x * u + k.y * v);
            normals.push_back(n);
            // uv origin is the top-left of the texture: +v in space is -v in uv.
            uvs.push_back(glm::vec2(0.5f + 0.5f * k.x, 0.5f - 0.5f * k.y) * uvScale);
        }
        triangles.push_back({base, base + 1, base + 2});
        triangles.push_back({base, base + 2, base + 3});
    }
    // A unit UV sphere of `rings` x `slices` cells, vertices shared (smooth normals), uvs
    // spanning uvScale; the poles' rings meet in a point, so it has 2 slices (rings - 1) triangles.
    void addSphere(int rings, int slices, glm::vec2 uvScale) {
        const auto base = std::uint32_t(positions.size());
        for (int r = 0; r <= rings; ++r)
            for (int k = 0; k <= slices; ++k) {
                const float theta = kPi * float(r) / float(rings), phi = 2.0f * kPi * float(k) / float(slices);
                const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
                positions.push_back(n), normals.push_back(n);
                uvs.push_back(glm::vec2(float(k) / float(slices), float(r) / float(rings)) * uvScale);
            }
        for (int r = 0; r < rings; ++r)
            for (int k = 0; k < slices; ++k) {
                const auto a = base + std::uint32_t(r * (slices + 1) + k), b = a + 1, c = a + std::uint32_t(slices + 1), d = c + 1;
                // Counter-clockwise seen from outside: b lies towards -x of a at the front.
                if (r > 0) triangles.push_back({a, b, c});
                if (r + 1 < rings) triangles.push_back({b, d, c});
            }
    }
    // An axis-aligned box with half extents h, each face uv-mapped to the whole texture.
    void addBox(const glm::vec3& c, const glm::vec3& h) {
        const glm::vec3 x(h.x, 0, 0), y(0, h.y, 0), z(0, 0, h.z);
        addQuad(c + z, x, y);   // +z
        addQuad(c - z, -x, y);  // -z
        addQuad(c + x, -z, y);  // +x
        addQuad(c - x, z, y);   // -x
        addQuad(c + y, x, -z);  // +y
        addQuad(c - y, x, z);   // -y
    }
};

using Motion = std::function<glm::mat4(float t)>;

glm::mat4 staticAt(const glm::mat4& m, float) { return m; }

// How a built-in scene keys its motion: `keys` poses at evenly spaced shutter times, kept as
// the poses (curve=linear: piecewise linear through them) or turned into the control points of
// the one Bezier curve of order keys - 1 through them (curve=bezier, orders 2 and 3), which
// follows a rotation far closer than the chords between the same poses.
struct MotionKeys {
    int count = 2;
    MotionInterpolation curve = MotionInterpolation::PiecewiseLinear;
};

MotionKeys motionKeysOption(OptionMap& options) {
    MotionKeys keys;
    keys.count = options.getInt("keys", 2, 2, 64);
    const std::string curve = options.getString("curve", "linear");
    if (curve == "bezier") {
        if (keys.count < 3 || keys.count > 4)
            throw Error(options.owner() + ": curve=bezier takes keys=3 or 4 (Bezier order 2 or 3), got keys=" + std::to_string(keys.count));
        keys.curve = MotionInterpolation::Bezier;
    } else if (curve != "linear") {
        throw Error(options.owner() + ": curve must be linear or bezier, got '" + curve + "'");
    }
    return keys;
}

// A mesh whose key poses follow worldFromObject(t): sampled at keys.count evenly spaced times,
// which for Bezier keys become the control points of the curve through them.
Mesh placeMesh(const LocalGeometry& g, std::string name, std::uint32_t material, MotionKeys keys, const Motion& worldFromObject) {
    Mesh mesh;
    mesh.name = std::move(name);
    mesh.material = material;
    mesh.numKeys = keys.count;
    mesh.interpolation = keys.curve;
    mesh.uvs = g.uvs;
    mesh.triangles = g.triangles;
    for (int k = 0; k < keys.count; ++k) {
        const glm::mat4 m = worldFromObject(keyTime(k, keys.count));
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
        for (std::size_t v = 0; v < g.positions.size(); ++v) {
            mesh.positions.push_back(glm::vec3(m * glm::vec4(g.positions[v], 1.0f)));
            mesh.normals.push_back(glm::normalize(normalMatrix * g.normals[v]));
        }
    }
    if (keys.curve == MotionInterpolation::Bezier) {
        bezierControlPointsThroughSamples(mesh.positions, keys.count);
        bezierControlPointsThroughSamples(mesh.normals, keys.count);
    }
    return mesh;
}

Mesh placeMesh(const LocalGeometry& g, std::string name, std::uint32_t material, int numKeys, const Motion& worldFromObject) {
    return placeMesh(g, std::move(name), material, MotionKeys{numKeys, MotionInterpolation::PiecewiseLinear}, worldFromObject);
}

// Procedural two-colour 8-bit sRGB textures, so built-in scenes need no files: texel (x, y)
// takes colour b where pattern(x, y) holds, else a.
template <class Pattern>
Texture twoColourTexture(int size, glm::u8vec3 a, glm::u8vec3 b, Pattern&& pattern) {
    std::vector<std::uint8_t> rgba(std::size_t(size) * size * 4);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::u8vec3 c = pattern(x, y) ? b : a;
            std::uint8_t* p = &rgba[(std::size_t(y) * size + x) * 4];
            p[0] = c.x, p[1] = c.y, p[2] = c.z, p[3] = 255;
        }
    return Texture::fromSrgb8(size, size, rgba);
}

Texture checkerTexture(int size, int cells, glm::u8vec3 a, glm::u8vec3 b) {
    return twoColourTexture(size, a, b, [=](int x, int y) { return ((x * cells / size) + (y * cells / size)) % 2 != 0; });
}

Texture gridTexture(int size, int cells, glm::u8vec3 fill, glm::u8vec3 line) {
    const int cell = size / cells;
    return twoColourTexture(size, fill, line, [=](int x, int y) { return x % cell < 2 || y % cell < 2; });
}

Texture stripeTexture(int size, int stripes, glm::u8vec3 a, glm::u8vec3 b) {
    return twoColourTexture(size, a, b, [=](int x, int y) { return ((x + y) * stripes / size) % 2 != 0; });
}

Material texturedMaterial(std::string name, glm::vec3 color, int texture) {
    Material m;
    m.name = std::move(name);
    m.baseColor = color;
    m.baseColorTexture = texture;
    return m;
}

void setStaticCamera(Scene& scene, const glm::vec3& eye, const glm::vec3& target) {
    scene.camera.open = CameraPose::lookAt(eye, target);
    scene.camera.close = scene.camera.open;
}

glm::vec3 randomUnitVector(Rng& rng) {
    const float z = rng.uniform(-1.0f, 1.0f);
    const float phi = rng.uniform(0.0f, 2.0f * kPi);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

Scene defaultSceneFrame(std::string name) {
    Scene scene;
    scene.name = std::move(name);
    scene.light.toLight = glm::normalize(glm::vec3(0.4f, 0.8f, 0.6f));
    scene.background = glm::vec3(0.02f, 0.025f, 0.04f);
    return scene;
}

// Hong & Oh's random-cube scene: n textured cubes scattered through the view, each translating
// and rotating over the shutter. Sizes and depths are set so that the depth complexity is the
// paper's: about 1.7 intervals per pixel at n = 1000 (their Fig. 15 reports 1.67).
Scene makeCubes(OptionMap& options) {
    const int n = options.getInt("n", 1000, 0, 1000000);
    const int seed = options.getInt("seed", 1, 0, 1 << 30);
    const MotionKeys keys = motionKeysOption(options);
    // Each cube pose is 24 vertices: two million poses are about 2 GB of scene.
    constexpr long long kMaxCubePoses = 2000000;
    if (static_cast<long long>(n) * keys.count > kMaxCubePoses)
        throw Error("scene 'cubes': n * keys must be at most " + std::to_string(kMaxCubePoses) + ", got " + std::to_string(n) + " * " +
                    std::to_string(keys.count));
    Scene scene = defaultSceneFrame("cubes");
    scene.textures.push_back(checkerTexture(128, 8, {235, 235, 235}, {60, 60, 60}));
    scene.textures.push_back(gridTexture(128, 4, {230, 230, 230}, {30, 30, 30}));
    scene.textures.push_back(stripeTexture(128, 8, {240, 240, 240}, {90, 90, 90}));
    const std::array<glm::vec3, 8> palette{{{0.9f, 0.2f, 0.15f}, {0.2f, 0.7f, 0.25f}, {0.2f, 0.35f, 0.9f}, {0.95f, 0.8f, 0.2f},
                                             {0.8f, 0.3f, 0.8f}, {0.2f, 0.8f, 0.85f}, {0.95f, 0.55f, 0.2f}, {0.85f, 0.85f, 0.85f}}};
    for (std::size_t i = 0; i < palette.size(); ++i)
        scene.materials.push_back(texturedMaterial("cube" + std::to_string(i), palette[i], int(i % scene.textures.size())));

    const glm::vec3 eye(0.0f, 0.0f, 0.0f);
    setStaticCamera(scene, eye, glm::vec3(0.0f, 0.0f, -1.0f));
    const float tanHalf = std::tan(scene.camera.verticalFov * 0.5f);
    const float aspect = 4.0f / 3.0f;
    Rng rng(std::uint64_t(seed) * 7919u + 17u);
    LocalGeometry cube;
    cube.addBox(glm::vec3(0.0f), glm::vec3(0.5f));
    for (int i = 0; i < n; ++i) {
        const float depth = rng.uniform(12.0f, 60.0f);
        const glm::vec3 start(rng.uniform(-0.95f, 0.95f) * depth * tanHalf * aspect,
                              rng.uniform(-0.95f, 0.95f) * depth * tanHalf, -depth);
        const float size = rng.uniform(0.3f, 0.6f);
        const glm::vec3 velocity = randomUnitVector(rng) * rng.uniform(0.2f, 1.2f);
        const glm::vec3 axis = randomUnitVector(rng);
        const float angle0 = rng.uniform(0.0f, 2.0f * kPi);
        const float spin = rng.uniform(-0.25f, 0.25f) * kPi;
        const auto material = std::uint32_t(rng.next() % palette.size());
        const Motion motion = [=](float t) {
            glm::mat4 m = glm::translate(glm::mat4(1.0f), start + velocity * t);
            m = glm::rotate(m, angle0 + spin * t, axis);
            return glm::scale(m, glm::vec3(size));
        };
        scene.meshes.push_back(placeMesh(cube, "cube" + std::to_string(i), material, keys, motion));
    }
    return scene;
}

// speed scales the rotation (speed=4: 160, 200 and 120 degrees about x, y and z in the shutter).
Scene makeRotatingCube(OptionMap& options) {
    const MotionKeys keys = motionKeysOption(options);
    const float speed = float(options.getDouble("speed", 1.0, 0.0, 100.0));
    Scene scene = defaultSceneFrame("rotating-cube");
    scene.textures.push_back(checkerTexture(256, 8, {240, 240, 240}, {200, 40, 40}));
    scene.materials.push_back(texturedMaterial("checker", glm::vec3(1.0f), 0));
    setStaticCamera(scene, glm::vec3(0.0f, 0.0f, 6.0f), glm::vec3(0.0f));
    LocalGeometry cube;
    cube.addBox(glm::vec3(0.0f), glm::vec3(1.0f));
    const Motion motion = [speed](float t) {
        glm::mat4 m(1.0f);
        m = glm::rotate(m, glm::radians(20.0f + 40.0f * speed * t), glm::vec3(1, 0, 0));
        m = glm::rotate(m, glm::radians(30.0f + 50.0f * speed * t), glm::vec3(0, 1, 0));
        return glm::rotate(m, glm::radians(10.0f + 30.0f * speed * t), glm::vec3(0, 0, 1));
    };
    scene.meshes.push_back(placeMesh(cube, "cube", 0, keys, motion));
    return scene;
}

// One triangle given by its own corners at t = 0 and t = 1 (linear motion), flat normals.
Mesh movingTriangle(std::string name, std::uint32_t material, const std::array<glm::vec3, 3>& open,
                    const std::array<glm::vec3, 3>& close) {
    Mesh mesh;
    mesh.name = std::move(name);
    mesh.material = material;
    mesh.numKeys = 2;
    for (const auto* key : {&open, &close}) {
        const glm::vec3 n = glm::normalize(glm::cross((*key)[1] - (*key)[0], (*key)[2] - (*key)[0]));
        for (const glm::vec3& p : *key) {
            mesh.positions.push_back(p);
            mesh.normals.push_back(n);
        }
    }
    mesh.uvs = {{0.0f, 1.0f}, {1.0f, 1.0f}, {0.5f, 0.0f}};
    mesh.triangles = {{0, 1, 2}};
    return mesh;
}

Mesh backdrop(const glm::vec3& centre, float halfWidth, float halfHeight, std::uint32_t material, float uvScale) {
    LocalGeometry quad;
    quad.addQuad(centre, glm::vec3(halfWidth, 0, 0), glm::vec3(0, halfHeight, 0), uvScale);
    return placeMesh(quad, "backdrop", material, 2, [](float t) { return staticAt(glm::mat4(1.0f), t); });
}

// Two triangles swapping depth order mid-shutter: the front one moves back through the other.
Scene makeCrossing(OptionMap&) {
    Scene scene = defaultSceneFrame("crossing");
    Material red, green;
    red.name = "red", red.baseColor = {0.9f, 0.15f, 0.1f}, red.doubleSided = true;
    green.name = "green", green.baseColor = {0.15f, 0.8f, 0.2f}, green.doubleSided = true;
    scene.materials = {red, green};
    setStaticCamera(scene, glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f));
    const glm::vec3 d(0.25f, 0.0f, 0.0f);
    const std::array<glm::vec3, 3> up{{{-1.4f, -1.0f, 0.0f}, {1.4f, -1.0f, 0.0f}, {0.0f, 1.3f, 0.0f}}};
    const std::array<glm::vec3, 3> down{{{-1.4f, 1.0f, 0.0f}, {0.0f, -1.3f, 0.0f}, {1.4f, 1.0f, 0.0f}}};
    auto shifted = [](const std::array<glm::vec3, 3>& tri, glm::vec3 offset) {
        return std::array<glm::vec3, 3>{{tri[0] + offset, tri[1] + offset, tri[2] + offset}};
    };
    scene.meshes.push_back(movingTriangle("front-to-back", 0, shifted(up, glm::vec3(0, 0, 1.0f) - d),
                                          shifted(up, glm::vec3(0, 0, -1.0f) + d)));
    scene.meshes.push_back(movingTriangle("back-to-front", 1, shifted(down, glm::vec3(0, 0, -1.0f) + d),
                                          shifted(down, glm::vec3(0, 0, 1.0f) - d)));
    return scene;
}

// A triangle flipping over: its bottom corners swap sides, so the t = 0 and t = 1 projections
// of its bottom edge cross and pixels see it twice (four motion-path fragments).
Scene makeTwist(OptionMap&) {
    Scene scene = defaultSceneFrame("twist");
    scene.textures.push_back(checkerTexture(128, 8, {250, 220, 60}, {40, 40, 160}));
    scene.textures.push_back(gridTexture(128, 8, {120, 120, 130}, {60, 60, 70}));
    Material tri = texturedMaterial("twisting", glm::vec3(1.0f), 0);
    tri.doubleSided = true;
    scene.materials = {tri, texturedMaterial("backdrop", glm::vec3(1.0f), 1)};
    setStaticCamera(scene, glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f));
    scene.meshes.push_back(movingTriangle("twisting", 0, {{{-1.3f, -1.1f, 0.0f}, {1.3f, -1.1f, 0.0f}, {-0.3f, 1.3f, 0.0f}}},
                                          {{{1.3f, -0.8f, 0.4f}, {-1.3f, -0.8f, -0.4f}, {0.3f, 1.3f, 0.0f}}}));
    scene.meshes.push_back(backdrop(glm::vec3(0.0f, 0.0f, -2.0f), 4.0f, 3.0f, 1, 2.0f));
    return scene;
}

// Thin bars sweeping several times their own width: the classic failure case of sampling.
Scene makeFence(OptionMap& options) {
    const int bars = options.getInt("bars", 12, 1, 1000);
    const float travel = float(options.getDouble("travel", 0.3, 0.0, 100.0));  // world units the bars move
    Scene scene = defaultSceneFrame("fence");
    scene.textures.push_back(gridTexture(256, 8, {200, 190, 170}, {70, 60, 50}));
    Material bar;
    bar.name = "bar", bar.baseColor = {0.08f, 0.08f, 0.1f};
    scene.materials = {texturedMaterial("backdrop", glm::vec3(1.0f), 0), bar};
    setStaticCamera(scene, glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f));
    scene.meshes.push_back(backdrop(glm::vec3(0.0f, 0.0f, -3.0f), 6.0f, 4.5f, 0, 3.0f));
    LocalGeometry geometry;
    const float spacing = 0.45f;
    for (int i = 0; i < bars; ++i)
        geometry.addQuad(glm::vec3((float(i) - 0.5f * float(bars - 1)) * spacing - 0.15f, 0.0f, 0.0f),
                         glm::vec3(0.025f, 0, 0), glm::vec3(0, 1.6f, 0));
    scene.meshes.push_back(placeMesh(geometry, "bars", 1, 2, [travel](float t) {
        return glm::translate(glm::mat4(1.0f), glm::vec3(travel * t, 0.0f, 0.0f));
    }));
    return scene;
}

// A static textured scene seen by a camera that slides and turns: blur from camera motion only.
Scene makePan(OptionMap&) {
    Scene scene = defaultSceneFrame("pan");
    scene.background = glm::vec3(0.45f, 0.6f, 0.85f);
    scene.textures.push_back(checkerTexture(256, 16, {225, 225, 215}, {70, 80, 70}));
    scene.textures.push_back(gridTexture(128, 4, {200, 120, 80}, {60, 30, 20}));
    scene.textures.push_back(stripeTexture(128, 8, {240, 240, 240}, {40, 90, 160}));
    scene.materials = {texturedMaterial("ground", glm::vec3(1.0f), 0), texturedMaterial("brick", glm::vec3(1.0f), 1),
                       texturedMaterial("stripes", glm::vec3(1.0f), 2)};
    LocalGeometry ground;
    ground.addQuad(glm::vec3(0.0f, -1.0f, -10.0f), glm::vec3(20.0f, 0, 0), glm::vec3(0, 0, -15.0f), 24.0f);
    const auto still = [](float t) { return staticAt(glm::mat4(1.0f), t); };
    scene.meshes.push_back(placeMesh(ground, "ground", 0, 2, still));
    Rng rng(4242);
    for (int i = 0; i < 10; ++i) {
        LocalGeometry box;
        const glm::vec3 h(rng.uniform(0.3f, 0.8f), rng.uniform(0.3f, 1.2f), rng.uniform(0.3f, 0.8f));
        box.addBox(glm::vec3(rng.uniform(-6.0f, 6.0f), -1.0f + h.y, rng.uniform(-14.0f, -1.0f)), h);
        scene.meshes.push_back(placeMesh(box, "box" + std::to_string(i), std::uint32_t(1 + i % 2), 2, still));
    }
    scene.camera.open = CameraPose::lookAt(glm::vec3(-0.7f, 0.8f, 5.0f), glm::vec3(-0.9f, 0.0f, -3.0f));
    scene.camera.close = CameraPose::lookAt(glm::vec3(0.7f, 0.9f, 5.0f), glm::vec3(0.5f, 0.0f, -3.0f));
    return scene;
}

// Three translucent quads moving over each other and over an opaque moving cube.
Scene makeTranslucent(OptionMap&) {
    Scene scene = defaultSceneFrame("translucent");
    scene.textures.push_back(checkerTexture(128, 8, {230, 230, 230}, {50, 50, 50}));
    scene.materials.push_back(texturedMaterial("checker", glm::vec3(1.0f), 0));
    const std::array<glm::vec3, 3> colors{{{0.95f, 0.15f, 0.1f}, {0.1f, 0.85f, 0.2f}, {0.15f, 0.3f, 0.95f}}};
    const std::array<float, 3> opacities{{0.5f, 0.4f, 0.6f}};
    for (int i = 0; i < 3; ++i) {
        Material m;
        m.name = "glass" + std::to_string(i);
        m.baseColor = colors[i];
        m.opacity = opacities[i];
        m.doubleSided = true;
        scene.materials.push_back(m);
    }
    setStaticCamera(scene, glm::vec3(0.0f, 0.0f, 6.0f), glm::vec3(0.0f));
    scene.meshes.push_back(backdrop(glm::vec3(0.0f, 0.0f, -4.0f), 6.0f, 4.5f, 0, 3.0f));
    LocalGeometry cube;
    cube.addBox(glm::vec3(0.0f), glm::vec3(0.8f));
    scene.meshes.push_back(placeMesh(cube, "cube", 0, 2, [](float t) {
        glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(-0.6f + 1.2f * t, 0.0f, -1.5f));
        m = glm::rotate(m, glm::radians(25.0f + 35.0f * t), glm::vec3(0, 1, 0));
        return glm::rotate(m, glm::radians(20.0f), glm::vec3(1, 0, 0));
    }));
    const std::array<glm::vec3, 3> starts{{{-1.2f, 0.5f, 0.0f}, {1.0f, 0.3f, 0.6f}, {0.0f, -0.9f, 1.2f}}};
    const std::array<glm::vec3, 3> moves{{{1.4f, -0.3f, 0.0f}, {-1.2f, 0.0f, 0.0f}, {0.2f, 1.0f, 0.0f}}};
    for (int i = 0; i < 3; ++i) {
        LocalGeometry quad;
        quad.addQuad(glm::vec3(0.0f), glm::vec3(0.9f, 0, 0), glm::vec3(0, 0.7f, 0));
        const glm::vec3 start = starts[i], move = moves[i];
        scene.meshes.push_back(placeMesh(quad, "glass" + std::to_string(i), std::uint32_t(1 + i), 2, [=](float t) {
            return glm::translate(glm::mat4(1.0f), start + move * t);
        }));
    }
    return scene;
}

// Gribel et al. 2013's first figure: a textured triangle and a textured quad, each turning by
// `angle` degrees (120) about the view axis through its centre within the shutter, over a
// static backdrop. Linear keys skew them: their corners cut the chords of circles.
Scene makeSpin(OptionMap& options) {
    const MotionKeys keys = motionKeysOption(options);
    const float angle = glm::radians(float(options.getDouble("angle", 120.0, 0.0, 720.0)));
    Scene scene = defaultSceneFrame("spin");
    scene.textures.push_back(checkerTexture(256, 8, {245, 215, 60}, {40, 50, 150}));
    scene.textures.push_back(stripeTexture(256, 8, {240, 240, 240}, {200, 50, 40}));
    scene.textures.push_back(gridTexture(128, 8, {110, 115, 125}, {55, 58, 66}));
    scene.materials = {texturedMaterial("triangle", glm::vec3(1.0f), 0), texturedMaterial("quad", glm::vec3(1.0f), 1),
                       texturedMaterial("backdrop", glm::vec3(1.0f), 2)};
    for (int i = 0; i < 2; ++i) scene.materials[std::size_t(i)].doubleSided = true;
    setStaticCamera(scene, glm::vec3(0.0f, 0.0f, 6.0f), glm::vec3(0.0f));
    scene.meshes.push_back(backdrop(glm::vec3(0.0f, 0.0f, -1.5f), 6.0f, 4.5f, 2, 3.0f));
    LocalGeometry triangle;
    triangle.positions = {{-1.2f, -0.8f, 0.0f}, {1.2f, -0.8f, 0.0f}, {0.0f, 1.3f, 0.0f}};
    triangle.normals.assign(3, glm::vec3(0, 0, 1));
    triangle.uvs = {{0.0f, 1.0f}, {1.0f, 1.0f}, {0.5f, 0.0f}};
    triangle.triangles = {{0, 1, 2}};
    const auto turning = [angle](glm::vec3 centre, float start) {
        return [=](float t) {
            return glm::rotate(glm::translate(glm::mat4(1.0f), centre), start + angle * t, glm::vec3(0, 0, 1));
        };
    };
    scene.meshes.push_back(placeMesh(triangle, "triangle", 0, keys, turning(glm::vec3(-1.35f, 0.0f, 0.0f), 0.0f)));
    LocalGeometry quad;
    quad.addQuad(glm::vec3(0.0f), glm::vec3(0.9f, 0, 0), glm::vec3(0, 0.5f, 0));
    scene.meshes.push_back(placeMesh(quad, "quad", 1, keys, turning(glm::vec3(1.5f, 0.0f, 0.3f), 0.3f)));
    return scene;
}

// A cloth sheet swung fast around a ball (after the UNC clothball): a grid of cells x cells
// quads wrapped on a cylinder about the ball's vertical axis, sweeping `angle` degrees (150)
// around it while closing in from 1.9 to 1.15 radii, wrapping tighter and shrinking in height.
// Every vertex moves on a curve; linear keys cut towards the ball.
Scene makeClothball(OptionMap& options) {
    const MotionKeys keys = motionKeysOption(options);
    const int cells = options.getInt("cells", 24, 1, 256);
    const float sweep = glm::radians(float(options.getDouble("angle", 150.0, 0.0, 720.0)));
    Scene scene = defaultSceneFrame("clothball");
    scene.textures.push_back(checkerTexture(256, 8, {235, 235, 225}, {170, 40, 60}));
    scene.textures.push_back(gridTexture(128, 8, {90, 140, 200}, {30, 50, 90}));
    Material cloth = texturedMaterial("cloth", glm::vec3(1.0f), 0);
    cloth.doubleSided = true;
    scene.materials = {cloth, texturedMaterial("ball", glm::vec3(1.0f), 1)};
    setStaticCamera(scene, glm::vec3(0.0f, 0.6f, 5.5f), glm::vec3(0.0f));

    // The ball: a static UV sphere of radius 1.
    LocalGeometry ball;
    ball.addSphere(24, 48, glm::vec2(4.0f, 2.0f));
    scene.meshes.push_back(placeMesh(ball, "ball", 1, 2, [](float t) { return staticAt(glm::mat4(1.0f), t); }));

    // The sheet, deforming: each vertex is a function of its grid point and t.
    Mesh sheet;
    sheet.name = "cloth";
    sheet.material = 0;
    sheet.numKeys = keys.count;
    sheet.interpolation = keys.curve;
    const int side = cells + 1;
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) sheet.uvs.push_back({float(i) / float(cells), float(j) / float(cells)});
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const auto a = std::uint32_t(j * side + i), b = a + 1, c = a + std::uint32_t(side), d = c + 1;
            sheet.triangles.push_back({a, b, d});
            sheet.triangles.push_back({a, d, c});
        }
    const auto clothAt = [&](float a, float b, float t) {
        const float radius = 1.9f - 0.75f * t;
        const float phi = -0.9f + sweep * t + (a - 0.5f) * 1.6f * (1.2f - 0.4f * t);
        const float y = (0.5f - b) * 1.5f * (1.0f - 0.3f * t);
        return glm::vec3(radius * std::sin(phi), y, radius * std::cos(phi));
    };
    std::vector<glm::vec3> samples;
    for (int k = 0; k < keys.count; ++k)
        for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i) samples.push_back(clothAt(float(i) / float(cells), float(j) / float(cells), keyTime(k, keys.count)));
    // Normals from the grid's central differences at each key.
    for (int k = 0; k < keys.count; ++k)
        for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i) {
                const auto at = [&](int x, int y) {
                    return samples[std::size_t(k) * side * side + std::size_t(std::clamp(y, 0, cells)) * side + std::size_t(std::clamp(x, 0, cells))];
                };
                const glm::vec3 n = glm::cross(at(i + 1, j) - at(i - 1, j), at(i, j - 1) - at(i, j + 1));
                sheet.normals.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1));
            }
    sheet.positions = samples;
    if (keys.curve == MotionInterpolation::Bezier) {
        bezierControlPointsThroughSamples(sheet.positions, keys.count);
        bezierControlPointsThroughSamples(sheet.normals, keys.count);
    }
    scene.meshes.push_back(std::move(sheet));
    return scene;
}

// A UV sphere of about `triangles` triangles (960; rings r and 2r slices, 4r(r - 1) in all)
// translating along +x by `travel` radii (1.5) over the shutter, over a static backdrop: the
// thesis' Table 2 sphere, whose silhouette of motion is the great circle facing +x. squash=A
// (0) deforms it as it goes, stretched along x and flattened along y by A at shutter close.
Scene makeSphere(OptionMap& options) {
    const MotionKeys keys = motionKeysOption(options);
    const int wanted = options.getInt("triangles", 960, 24, 1 << 20);
    const float travel = float(options.getDouble("travel", 1.5, 0.0, 100.0));
    const float squash = float(options.getDouble("squash", 0.0, 0.0, 0.9));
    // About half a vertex per triangle per key: four million triangle poses are about 100 MB.
    constexpr long long kMaxTrianglePoses = 4000000;
    if (static_cast<long long>(wanted) * keys.count > kMaxTrianglePoses)
        throw Error("scene 'sphere': triangles * keys must be at most " + std::to_string(kMaxTrianglePoses) + ", got " +
                    std::to_string(wanted) + " * " + std::to_string(keys.count));
    const int rings = std::max(3, int(std::lround(0.5 + std::sqrt(0.25 + double(wanted) / 4.0))));
    Scene scene = defaultSceneFrame("sphere");
    scene.textures.push_back(checkerTexture(256, 8, {240, 240, 240}, {40, 110, 200}));
    scene.textures.push_back(gridTexture(128, 8, {110, 115, 125}, {55, 58, 66}));
    scene.materials = {texturedMaterial("sphere", glm::vec3(1.0f), 0), texturedMaterial("backdrop", glm::vec3(1.0f), 1)};
    setStaticCamera(scene, glm::vec3(0.0f, 0.8f, 6.0f), glm::vec3(0.0f));
    scene.meshes.push_back(backdrop(glm::vec3(0.0f, 0.0f, -2.0f), 7.0f, 5.0f, 1, 3.0f));
    LocalGeometry sphere;
    sphere.addSphere(rings, 2 * rings, glm::vec2(4.0f, 2.0f));
    scene.meshes.push_back(placeMesh(sphere, "sphere", 0, keys, [travel, squash](float t) {
        const glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(travel * (t - 0.5f), 0.0f, 0.0f));
        return glm::scale(m, glm::vec3(1.0f + squash * t, 1.0f - squash * t, 1.0f));
    }));
    return scene;
}

struct BuiltinScene {
    BuiltinSceneInfo info;
    Scene (*make)(OptionMap&);
};

const std::array<BuiltinScene, 10> kScenes{{
    {{"cubes", "n random textured cubes moving and rotating (Hong & Oh); options n=1000, seed=1, keys=2, curve=linear"}, makeCubes},
    {{"rotating-cube", "one textured cube rotating about x, y and z; options keys=2, curve=linear, speed=1"}, makeRotatingCube},
    {{"spin", "a textured triangle and quad turning about the view axis (Gribel 2013); options angle=120, keys=2, curve=linear"}, makeSpin},
    {{"clothball", "a cloth sheet swung fast around a ball, closing in; options cells=24, angle=150, keys=2, curve=linear"}, makeClothball},
    {{"sphere", "a UV sphere translating along +x over a backdrop (Jones 2004, Table 2); options triangles=960, travel=1.5, squash=0, keys=2, curve=linear"}, makeSphere},
    {{"crossing", "two triangles passing through each other in depth"}, makeCrossing},
    {{"twist", "a triangle flipping over, its t=0 and t=1 projections crossing"}, makeTwist},
    {{"fence", "thin bars moving fast over a textured wall; options bars=12, travel=0.3"}, makeFence},
    {{"pan", "static textured scene, moving camera"}, makePan},
    {{"translucent", "translucent moving quads over an opaque moving cube"}, makeTranslucent},
}};

}  // namespace

std::span<const BuiltinSceneInfo> builtinScenes() {
    static const std::array<BuiltinSceneInfo, kScenes.size()> infos = [] {
        std::array<BuiltinSceneInfo, kScenes.size()> result;
        for (std::size_t i = 0; i < kScenes.size(); ++i) result[i] = kScenes[i].info;
        return result;
    }();
    return infos;
}

Scene makeBuiltinScene(std::string_view name, OptionMap options) {
    for (const BuiltinScene& scene : kScenes) {
        if (scene.info.name != name) continue;
        options.setOwner("scene 'builtin:" + std::string(name) + "'");
        Scene result = scene.make(options);
        options.rejectUnknown();
        return result;
    }
    std::string known;
    for (const BuiltinScene& scene : kScenes) known += (known.empty() ? "" : ", ") + std::string(scene.info.name);
    throw Error("unknown built-in scene '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace streak
