// A moving, deforming mesh built in code and rendered with two methods: the exact analytic
// method and accumulation's 256 shutter instants, which it should match.
//
//   moving_mesh [out_prefix]   writes out_prefix-analytic.png and out_prefix-accumulation.png

#include <streak/streak.h>

#include <cstdio>
#include <string>

namespace sk = streak::api;

int main(int argc, char** argv) {
    const std::string prefix = argc > 1 ? argv[1] : "moving_mesh";
    try {
        // A 2x2 quad that slides right by 1.5 and stretches its top edge over the shutter: two
        // key poses of its four vertices (key-major), with uvs for a checker texture.
        sk::Mesh quad;
        quad.keys = 2;
        quad.positions = {-1.5f, -1, 0,  0.5f, -1, 0,  0.5f, 1, 0,  -1.5f, 1, 0,   // t = 0
                           0.0f, -1, 0,  2.0f, -1, 0,  2.5f, 1, 0,  -0.5f, 1, 0};  // t = 1
        quad.uvs = {0, 1, 1, 1, 1, 0, 0, 0};
        quad.indices = {0, 1, 2, 0, 2, 3};
        sk::Texture checker;
        checker.width = checker.height = 8;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                const std::uint8_t v = (x + y) % 2 ? 230 : 40;
                checker.rgba8.insert(checker.rgba8.end(), {v, v, v, 255});
            }
        sk::Material material;
        material.texture = 0;
        material.doubleSided = true;
        sk::Camera camera;  // at (0, 0, 5) looking at the origin
        const sk::Scene scene = sk::Scene::fromArrays({quad}, {material}, camera, {checker}, {0.1f, 0.1f, 0.15f});

        sk::RenderSettings settings;
        settings.width = 320, settings.height = 240;
        settings.method = "analytic";
        const sk::Image exact = sk::render(scene, settings).image;
        settings.method = "accumulation";
        settings.options["samples"] = "256";
        const sk::Image reference = sk::render(scene, settings).image;
        sk::writeImage(exact, prefix + "-analytic.png");
        sk::writeImage(reference, prefix + "-accumulation.png");
        std::printf("%zu triangles; analytic vs accumulation (256 instants): %.1f dB\n", scene.numTriangles(),
                    sk::compare(exact, reference).psnr);
    } catch (const streak::Error& e) {
        std::fprintf(stderr, "moving_mesh: %s\n", e.what());
        return 2;
    }
    return 0;
}
