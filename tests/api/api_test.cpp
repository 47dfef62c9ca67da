// The public API (include/streak/streak.h) as a user calls it: the user's own arrays with a
// closed-form image, loading, the registry, errors.

#include <streak/streak.h>

#include "support/gltf_samples.h"
#include "support/shared_scenes.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <limits>
#include <thread>

namespace sk = streak::api;

namespace {

// A white quad at depth 3 seen by a 90-degree camera over a 16x4 image, its right edge
// sweeping raster x from 2 to 14 over the shutter (the reference renderers' closed form).
sk::Scene sweepingQuad() {
    const float depth = 3.0f, aspect = 4.0f;
    auto x = [&](float raster) { return (2.0f * raster / 16.0f - 1.0f) * depth * aspect; };
    auto y = [&](float raster) { return (1.0f - 2.0f * raster / 4.0f) * depth; };
    sk::Mesh quad;
    for (const float dx : {0.0f, 12.0f})
        quad.positions.insert(quad.positions.end(), {x(-20 + dx), y(-1), -depth, x(-20 + dx), y(5), -depth, x(2 + dx), y(5), -depth,
                                                     x(2 + dx), y(-1), -depth});
    quad.indices = {0, 1, 2, 0, 2, 3};
    sk::Material white;
    white.doubleSided = true;
    sk::Camera camera;
    camera.open.position = {0, 0, 0};
    camera.open.target = {0, 0, -1};
    camera.close = camera.open;
    camera.verticalFovDegrees = 90.0f;
    return sk::Scene::fromArrays({quad}, {white}, camera);
}

}  // namespace

TEST(Api, ArraysGiveTheClosedFormCoverage) {
    const sk::Scene scene = sweepingQuad();
    EXPECT_EQ(scene.numTriangles(), 2u);
    for (const char* method : {"analytic", "motion-path"}) {
        SCOPED_TRACE(method);
        sk::RenderSettings settings;
        settings.method = method;
        settings.width = 16, settings.height = 4;
        settings.unlit = true;
        const sk::RenderResult result = sk::render(scene, settings);
        ASSERT_EQ(result.image.rgb.size(), 16u * 4u * 3u);
        for (int px = 0; px < 16; ++px)
            EXPECT_NEAR(result.image.at(px, 1, 0), std::clamp((14.0f - (px + 0.5f)) / 12.0f, 0.0f, 1.0f), 2e-4f) << px;
        EXPECT_EQ(result.stats.counters.at("triangles"), 2.0);
        EXPECT_NE(result.stats.json().find("\"triangles\": 2"), std::string::npos);
    }
    // Under a triangle curve: 1 - C((xc - 2) / 12), C(x) = 2x^2 up to 1/2.
    sk::RenderSettings settings;
    settings.method = "analytic", settings.width = 16, settings.height = 4, settings.unlit = true;
    const sk::Image curved = sk::render(scene.withShutter({"triangle", 1.0f}), settings).image;
    EXPECT_NEAR(curved.at(3, 0, 0), 1.0f - 2.0f * (1.5f / 12.0f) * (1.5f / 12.0f), 2e-4f);
}

TEST(Api, BadArraysRaiseOneClearError) {
    const sk::Scene good = sweepingQuad();
    sk::Mesh mesh;
    mesh.positions = {0, 0, -1, 1, 0, -1, 0, 1, -1, 0, 0, -1, 1, 0, -1, 0, 1, -1};
    mesh.indices = {0, 1, 2};
    const sk::Material material;
    const sk::Camera camera;
    auto message = [&](const sk::Mesh& m) {
        try {
            sk::Scene::fromArrays({m}, {material}, camera);
        } catch (const streak::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    sk::Mesh wrongShape = mesh;
    wrongShape.positions.pop_back();
    EXPECT_NE(message(wrongShape).find("positions must be keys x vertices x 3"), std::string::npos);
    sk::Mesh nan = mesh;
    nan.positions[4] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(message(nan).find("finite"), std::string::npos);
    sk::Mesh outOfRange = mesh;
    outOfRange.indices[2] = 7;
    EXPECT_NE(message(outOfRange).find("index 7 is out of range"), std::string::npos);
    sk::Mesh badMaterial = mesh;
    badMaterial.material = 3;
    EXPECT_NE(message(badMaterial).find("material 3 does not exist"), std::string::npos);
    EXPECT_EQ(message(mesh), "no error");
    EXPECT_THROW(good.withShutter({"gaussian", 1.0f}), streak::Error);
    EXPECT_THROW(good.withShutter({"box", 0.0f}), streak::Error);
    sk::RenderSettings unknown;
    unknown.method = "nosuch";
    EXPECT_THROW(sk::render(good, unknown), streak::Error);
    sk::RenderSettings noMemory;
    noMemory.memoryBudgetMB = 0;
    EXPECT_THROW(sk::render(good, noMemory), streak::Error);
    EXPECT_THROW(sk::Scene::load("builtin:nosuch"), streak::Error);
}

TEST(Api, ListsTheMethodsAndLoadsScenes) {
    const std::vector<sk::Method> methods = sk::methods();
    EXPECT_TRUE(std::any_of(methods.begin(), methods.end(), [](const sk::Method& m) { return m.name == "analytic"; }));
    const sk::Scene cubes = sk::Scene::load("builtin:cubes?n=10");
    EXPECT_EQ(cubes.numTriangles(), 120u);
    sk::RenderSettings settings;
    settings.width = 32, settings.height = 24;
    const sk::Image a = sk::render(cubes, settings).image, b = sk::render(cubes, settings).image;
    EXPECT_TRUE(std::isinf(sk::compare(a, b).psnr));
}

// One Renderer renders again and again (a sequence, or warm repeats) what a fresh one renders,
// and reports its progress from 0 to 1.
TEST(Api, ARendererKeptBetweenRendersGivesTheSameImages) {
    const sk::Scene scene = sweepingQuad();
    sk::RenderSettings settings;
    settings.method = "accumulation", settings.options["samples"] = "16";
    settings.width = 16, settings.height = 4, settings.unlit = true;
    sk::Renderer renderer(settings);
    EXPECT_FALSE(renderer.trail().has_value());
    std::vector<double> progress;
    const sk::Image first = renderer.render(scene, [&](double f) { progress.push_back(f); }).image;
    const sk::RenderResult second = renderer.render(scene);
    EXPECT_TRUE(std::isinf(sk::compare(first, second.image).psnr));
    EXPECT_TRUE(std::isinf(sk::compare(first, sk::render(scene, settings).image).psnr));
    ASSERT_EQ(progress.size(), 16u);
    EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
    EXPECT_DOUBLE_EQ(progress.back(), 1.0);
    // The figures the command line's --stats writes.
    EXPECT_EQ(second.stats.info.at("method"), "accumulation");
    EXPECT_EQ(second.stats.info.at("shading"), "unlit");
    EXPECT_EQ(second.stats.counters.at("width"), 16.0);
    EXPECT_EQ(second.stats.info.at("camera_open_position"), "0,0,0");
    ASSERT_FALSE(second.stats.timesMs.empty());
    EXPECT_EQ(second.stats.timesMs.back().first, "render");
    settings.width = sk::kMaxImageSize + 1;
    EXPECT_THROW(sk::Renderer{settings}, streak::Error);
}

// A cancel callback is asked before the render and with each progress step, on the calling
// thread; once it says stop, the render throws Cancelled after the steps so far and no image
// comes back. Every CPU method that renders over time steps (tiles, instants, rows) stops.
TEST(Api, CancelStopsEveryMethodAtItsNextProgressStep) {
    const sk::Scene scene = sk::Scene::load("builtin:cubes?n=40");
    for (const char* method : {"motion-path", "analytic", "higher-order", "accumulation", "stochastic", "embree"}) {
        SCOPED_TRACE(method);
        sk::RenderSettings settings;
        settings.method = method, settings.width = 128, settings.height = 96;
        settings.threads = 1;  // every part on the calling thread, so every part is a step
        const std::thread::id caller = std::this_thread::get_id();
        int asked = 0, steps = 0;
        bool onCaller = true;
        sk::Renderer renderer(settings);
        EXPECT_THROW(renderer.render(scene, [&](double) { ++steps; }, [&] {
                         onCaller = onCaller && std::this_thread::get_id() == caller;
                         return ++asked > 3;
                     }),
                     streak::Cancelled);
        EXPECT_EQ(asked, 4);  // before the render, then with three steps; the third stops before its report
        EXPECT_EQ(steps, 2);
        EXPECT_TRUE(onCaller);
        // Told never to stop, the same renderer renders the image.
        const sk::Image image = renderer.render(scene, {}, [] { return false; }).image;
        EXPECT_TRUE(std::isinf(sk::compare(image, sk::render(scene, settings).image).psnr));
    }
    sk::RenderSettings settings;
    EXPECT_THROW(sk::Renderer(settings).render(scene, {}, [] { return true; }), streak::Cancelled);

    // The albedo and normal passes are renders of their own: each a third of the progress, and
    // cancelled as the beauty is.
    settings.width = 64, settings.height = 48, settings.threads = 1, settings.passes = {"albedo", "normal"};
    std::vector<double> progress;
    sk::Renderer(settings).render(scene, [&](double f) { progress.push_back(f); });
    EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
    EXPECT_DOUBLE_EQ(progress.back(), 1.0);
    EXPECT_TRUE(std::any_of(progress.begin(), progress.end(), [](double f) { return f > 0.34 && f < 0.66; }));
    double last = 0.0;
    EXPECT_THROW(sk::Renderer(settings).render(scene, [&](double f) { last = f; }, [&] { return last > 0.5; }), streak::Cancelled);
    EXPECT_GT(last, 0.5);
    EXPECT_LT(last, 0.7);
}

// The vector pass of a quad turning about the view axis by delta a frame, seen at frame 12. A
// surface point seen at pixel centre c (pixels, y up, from the image's centre) at time t sat at
// R(-w (t - 12)) c at frame 12 (w = delta a frame), so it was at R(-delta) of that a frame
// before and will be at R(delta) a frame after: X,Y = (R(-delta) - I) R(-w (t - 12)) c and
// Z,W = (I - R(delta)) R(-w (t - 12)) c (Cycles' signs), averaged over the shutter. With the
// shutter shut that is the turn of c itself. The samples' mean is the centre's value: the vector
// is linear in the point, and the n-rooks samples' mean offset is 0.
TEST(Api, TheVectorPassOfATurningQuadIsItsRotationAcrossFrames) {
    streak::test::TempDir dir;
    const std::string path = (dir.path() / "spin.gltf").string();
    {
        const std::vector<std::uint8_t> bytes = streak::test::spinningQuad(90.0).gltfBytes();
        std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    const double delta = 90.0 / 24.0 * std::numbers::pi / 180.0;  // the quad turns 90 degrees in 24 frames
    auto turned = [](double x, double y, double a) { return std::pair{x * std::cos(a) - y * std::sin(a), x * std::sin(a) + y * std::cos(a)}; };
    for (const double shutter : {0.0, 0.5})
        for (const char* method : {"analytic", "motion-path", "accumulation"}) {
            SCOPED_TRACE(std::string(method) + " shutter " + std::to_string(shutter));
            sk::LoadOptions load;
            load.frame = 12.0, load.shutterFrames = shutter, load.fps = 24.0, load.width = 64, load.height = 48;
            load.background = std::array<float, 3>{0.2f, 0.3f, 0.4f};  // taken out of the vector where nothing shows
            const sk::Scene scene = sk::Scene::load(path, load);
            sk::RenderSettings settings;
            settings.method = method, settings.width = 64, settings.height = 48, settings.aa = 4, settings.transparent = true;
            settings.options = std::string(method) == "accumulation" ? std::map<std::string, std::string>{{"samples", "64"}} : std::map<std::string, std::string>{};
            settings.passes = {"vector"};
            const sk::Image image = sk::render(scene, settings).image;
            auto channel = [&](const char* name) -> const std::vector<float>& { return image.channel(name)->values; };
            // Accumulation's 64 instants approximate the shutter's mean by a midpoint sum.
            const double tolerance = shutter > 0.0 && std::string(method) == "accumulation" ? 5e-3 : 2e-3;
            int checked = 0;
            for (int y = 0; y < 48; ++y)
                for (int x = 0; x < 64; ++x) {
                    const std::size_t i = std::size_t(y) * 64 + std::size_t(x);
                    if (image.alpha[i] < 1.0f) continue;
                    const double cx = x + 0.5 - 32.0, cy = 24.0 - (y + 0.5);
                    double ex = 0, ey = 0, ez = 0, ew = 0;
                    const int steps = shutter > 0.0 ? 2000 : 1;
                    for (int j = 0; j < steps; ++j) {
                        const double t = shutter * (j + 0.5) / steps;  // frames after 12
                        const auto [px, py] = turned(cx, cy, -delta * t);
                        const auto [bx, by] = turned(px, py, -delta);
                        const auto [ax, ay] = turned(px, py, delta);
                        ex += (bx - px) / steps, ey += (by - py) / steps, ez += (px - ax) / steps, ew += (py - ay) / steps;
                    }
                    EXPECT_NEAR(channel("vector.X")[i], ex, tolerance) << x << "," << y;
                    EXPECT_NEAR(channel("vector.Y")[i], ey, tolerance) << x << "," << y;
                    EXPECT_NEAR(channel("vector.Z")[i], ez, tolerance) << x << "," << y;
                    EXPECT_NEAR(channel("vector.W")[i], ew, tolerance) << x << "," << y;
                    ++checked;
                }
            EXPECT_GT(checked, 150);
            EXPECT_EQ(image.alpha[0], 0.0f);
            EXPECT_EQ(channel("vector.X")[0], 0.0f);  // nothing shows: no vector, the background taken out
            EXPECT_EQ(channel("vector.W")[0], 0.0f);
        }

    // A scene without frames, the GL twins and a trail method refuse it in one line naming why.
    sk::RenderSettings settings;
    settings.width = 64, settings.height = 48, settings.passes = {"vector"};
    auto message = [](const std::function<void()>& call) {
        try {
            call();
        } catch (const streak::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message([&] { sk::render(sk::Scene::load("builtin:spin"), settings); }).find("needs a scene with frames"), std::string::npos);
    settings.method = "motion-path-gl";
    EXPECT_NE(message([&] { sk::Renderer{settings}; }).find("does not write the vector pass"), std::string::npos);
    settings.method = "blur-shell";
    EXPECT_NE(message([&] { sk::Renderer{settings}; }).find("draws a trail"), std::string::npos);
}

// The arrays' names are the Cryptomatte names of their meshes and materials.
TEST(Api, ArrayNamesAreTheCryptomatteNames) {
    sk::Mesh mesh;
    mesh.positions = {-1, -1, 0, 1, -1, 0, 0, 1, 0, -1, -1, 0, 1, -1, 0, 0, 1, 0};
    mesh.indices = {0, 1, 2};
    mesh.name = "Suzanne";
    sk::Material material;
    material.name = "Skin";
    material.doubleSided = true;
    const sk::Scene scene = sk::Scene::fromArrays({mesh}, {material}, sk::Camera{});
    sk::RenderSettings settings;
    settings.width = 32, settings.height = 24, settings.passes = {"object_id", "material_id"};
    const sk::Image image = sk::render(scene, settings).image;
    std::string manifests;
    for (const auto& [key, value] : image.metadata)
        if (key.ends_with("/manifest")) manifests += value;
    EXPECT_NE(manifests.find("\"Suzanne\""), std::string::npos) << manifests;
    EXPECT_NE(manifests.find("\"Skin\""), std::string::npos) << manifests;
}

// A region render is the whole render's pixels there, placed in the frame, and stitch() joins
// regions back into the whole frame, refusing regions that overlap or leave a pixel out.
TEST(Api, RegionsAreTheWholeFramesPixelsAndStitchBack) {
    const sk::Scene scene = sk::Scene::load("builtin:cubes?n=20");
    sk::RenderSettings settings;
    settings.method = "analytic", settings.width = 40, settings.height = 30, settings.aa = 2;
    const sk::Image whole = sk::render(scene, settings).image;
    EXPECT_FALSE(whole.isRegion());
    std::vector<sk::Image> parts;
    for (const sk::Region r : {sk::Region{0, 0, 40, 7}, sk::Region{0, 7, 23, 30}, sk::Region{23, 7, 40, 30}}) {
        settings.region = r;
        const sk::RenderResult result = sk::render(scene, settings);
        const sk::Image& part = result.image;
        ASSERT_TRUE(part.isRegion());
        EXPECT_EQ(part.x, r.x0); EXPECT_EQ(part.y, r.y0); EXPECT_EQ(part.frameWidth, 40); EXPECT_EQ(part.frameHeight, 30);
        ASSERT_EQ(part.width, r.x1 - r.x0); ASSERT_EQ(part.height, r.y1 - r.y0);
        EXPECT_EQ(result.stats.info.at("region"), std::to_string(r.x0) + "," + std::to_string(r.y0) + "," + std::to_string(r.x1) + "," + std::to_string(r.y1));
        for (int y = 0; y < part.height; ++y)
            for (int x = 0; x < part.width; ++x)
                for (int c = 0; c < 3; ++c) ASSERT_EQ(part.at(x, y, c), whole.at(part.x + x, part.y + y, c));
        parts.push_back(part);
    }
    const sk::Image stitched = sk::stitch({parts[2], parts[0], parts[1]});
    EXPECT_FALSE(stitched.isRegion());
    EXPECT_EQ(stitched.rgb, whole.rgb);
    EXPECT_THROW(sk::stitch({parts[0], parts[1]}), streak::Error);            // a gap
    EXPECT_THROW(sk::stitch({parts[0], parts[1], parts[2], parts[1]}), streak::Error);  // an overlap
    EXPECT_EQ(sk::stitch({whole}).rgb, whole.rgb);                           // a whole frame covers itself
    EXPECT_THROW(sk::stitch({whole, parts[0]}), streak::Error);
    settings.region = sk::Region{0, 0, 41, 30};
    EXPECT_THROW(sk::Renderer{settings}, streak::Error);
    settings.region = sk::Region{5, 5, 5, 9};
    EXPECT_THROW(sk::Renderer{settings}, streak::Error);
}

// Display-space differences in closed form: one of two pixels off by a whole level in every
// channel is MSE 1/2 (3.01 dB) over the image and MSE 1 (0 dB) over the foreground, that pixel.
TEST(Api, TransparentPassesAndMattesThroughThePublicApi) {
    // builtin:crossing (two triangles, no other object): with a transparent background each
    // object's Cryptomatte matte is its coverage, and the two sum to the alpha.
    const sk::Scene scene = sk::Scene::load("builtin:crossing");
    sk::RenderSettings settings;
    settings.method = "motion-path", settings.width = 48, settings.height = 36, settings.aa = 2, settings.transparent = true;
    settings.passes = {"object_id", "depth"};
    const sk::Image image = sk::render(scene, settings).image;
    ASSERT_TRUE(image.hasAlpha());
    ASSERT_NE(image.channel("Z"), nullptr);
    std::vector<float> sum(image.alpha.size(), 0.0f);
    for (const sk::Image::Channel& c : image.channels) ASSERT_EQ(c.values.size(), image.alpha.size()) << c.name;
    for (const std::string name : {"front-to-back", "back-to-front"}) {  // the scene's two meshes
        const std::vector<float> matte = sk::cryptomatteMatte(image, "CryptoObject", name);
        EXPECT_GT(*std::max_element(matte.begin(), matte.end()), 0.99f) << name;
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += matte[i];
    }
    double worst = 0.0;
    for (std::size_t i = 0; i < sum.size(); ++i) worst = std::max(worst, double(std::abs(sum[i] - image.alpha[i])));
    EXPECT_LT(worst, 1e-5);
    EXPECT_GT(*std::max_element(image.alpha.begin(), image.alpha.end()), 0.99f);
    EXPECT_THROW(sk::cryptomatteMatte(image, "CryptoMaterial", "red"), streak::Error);  // material_id was not asked for
    // The albedo pass is the unlit render of the same visibility over a transparent background,
    // for any method: here, to the bit.
    for (const char* method : {"motion-path", "stochastic"}) {
        sk::RenderSettings lit = settings, unlit = settings;
        lit.method = unlit.method = method, lit.passes = {"albedo"}, unlit.passes = {}, unlit.unlit = true;
        const sk::Image withAlbedo = sk::render(scene, lit).image, albedo = sk::render(scene, unlit).image;
        ASSERT_NE(withAlbedo.channel("albedo.G"), nullptr) << method;
        for (std::size_t i = 0; i < albedo.alpha.size(); ++i)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(withAlbedo.channel(std::string("albedo.") + "RGB"[c])->values[i], albedo.rgb[3 * i + std::size_t(c)]) << method;
        EXPECT_NE(withAlbedo.rgb, albedo.rgb) << method;  // the beauty stays lit
    }
    settings.method = "post-filter";
    EXPECT_THROW(sk::Renderer{settings}, streak::Error);  // writes no passes
    settings.method = "motion-path", settings.passes = {"normals"};
    EXPECT_THROW(sk::Renderer{settings}, streak::Error);

}

TEST(Api, DeepImageThroughThePublicApi) {
    // builtin:crossing, two triangles crossing in depth as they move: each pixel's deep samples,
    // front to back, composite to the image's RGBA; a region's are the whole frame's there; the
    // file reads back as written.
    const sk::Scene scene = sk::Scene::load("builtin:crossing");
    sk::RenderSettings settings;
    settings.method = "higher-order", settings.width = 48, settings.height = 36, settings.aa = 2, settings.transparent = true, settings.deep = true;
    const sk::RenderResult result = sk::render(scene, settings);
    ASSERT_TRUE(result.deep);
    const sk::DeepImage& deep = *result.deep;
    ASSERT_EQ(deep.counts.size(), std::size_t(48 * 36));
    std::size_t next = 0, layered = 0;
    for (std::size_t i = 0; i < deep.counts.size(); ++i) {
        float r = 0.0f, a = 0.0f;
        for (std::uint32_t k = 0; k < deep.counts[i]; ++k, ++next) {
            const sk::DeepImage::Sample& s = deep.samples[next];
            r += (1.0f - a) * s.r, a += (1.0f - a) * s.a;
        }
        layered += deep.counts[i] > 1;
        ASSERT_NEAR(r, result.image.rgb[3 * i], 1e-5f) << i;
        ASSERT_NEAR(a, result.image.alpha[i], 1e-5f) << i;
    }
    EXPECT_EQ(next, deep.samples.size());
    EXPECT_GT(layered, 0u);  // where the two cross
    EXPECT_EQ(result.stats.counters.at("deep_samples"), double(deep.samples.size()));

    settings.region = sk::Region{8, 4, 40, 30};
    const sk::DeepImage region = *sk::render(scene, settings).deep;
    EXPECT_EQ(region.width, 32);
    EXPECT_EQ(region.x, 8);
    EXPECT_EQ(region.frameWidth, 48);
    EXPECT_EQ(region.counts[0], deep.counts[4 * 48 + 8]);
    streak::test::TempDir dir;
    sk::writeDeepImage(region, dir.file("region.exr"));
    const sk::DeepImage back = sk::readDeepImage(dir.file("region.exr"));
    EXPECT_EQ(back.counts, region.counts);
    EXPECT_EQ(back.y, 4);
    ASSERT_EQ(back.samples.size(), region.samples.size());
    for (std::size_t k = 0; k < back.samples.size(); ++k) EXPECT_EQ(back.samples[k].a, region.samples[k].a);

    // A deep image written from the API must be tidy, as the file says it is.
    sk::DeepImage untidy = region;
    std::size_t first = 0;
    while (first < untidy.counts.size() && untidy.counts[first] < 2) ++first;
    ASSERT_LT(first, untidy.counts.size());
    std::size_t at = 0;
    for (std::size_t i = 0; i < first; ++i) at += untidy.counts[i];
    std::swap(untidy.samples[at], untidy.samples[at + 1]);
    EXPECT_THROW(sk::writeDeepImage(untidy, dir.file("untidy.exr")), streak::Error);
    EXPECT_FALSE(std::filesystem::exists(dir.file("untidy.exr")));

    settings.region.reset();
    settings.deepSamples = 0;
    EXPECT_THROW(sk::Renderer{settings}, streak::Error);
    settings.deepSamples = 16, settings.method = "post-filter";
    EXPECT_THROW(sk::Renderer{settings}, streak::Error);  // writes no deep image
}

TEST(Api, ComparesInClosedFormAndDrawsTheHeatmap) {
    sk::Image black{2, 1, std::vector<float>(6, 0.0f)};
    sk::Image onePixel = black;
    std::fill(onePixel.rgb.begin(), onePixel.rgb.begin() + 3, 1.0f);
    const sk::Comparison c = sk::compare(black, onePixel);
    EXPECT_NEAR(c.psnr, 10.0 * std::log10(2.0), 1e-6);
    EXPECT_EQ(c.foregroundPixels, 1u);
    EXPECT_NEAR(c.foregroundPsnr, 0.0, 1e-6);
    const sk::Heatmap map = sk::errorHeatmap(black, onePixel);
    EXPECT_GT(map.maxError, 0.0);
    EXPECT_GT(map.image.at(0, 0, 0) + map.image.at(0, 0, 1) + map.image.at(0, 0, 2),
              map.image.at(1, 0, 0) + map.image.at(1, 0, 1) + map.image.at(1, 0, 2));
    EXPECT_THROW(sk::checkImagePath("out.jpg"), streak::Error);
    EXPECT_NO_THROW(sk::checkImagePath("out.exr"));
}

// Loading with every option the command line has: the shutter and background land in the
// scene, the camera flags in the figures.
TEST(Api, LoadOptionsReachTheScene) {
    sk::LoadOptions load;
    load.shutter = {"triangle", 1.0f};
    load.background = std::array<float, 3>{0.25f, 0.5f, 1.0f};
    const sk::Scene scene = sk::Scene::load("builtin:cubes?n=1", load);
    sk::RenderSettings settings;
    settings.width = 8, settings.height = 6, settings.method = "analytic";
    const sk::RenderResult result = sk::render(scene, settings);
    EXPECT_EQ(result.stats.info.at("shutter_curve"), "triangle");
    EXPECT_EQ(result.stats.info.at("scene"), "builtin:cubes?n=1");
    EXPECT_EQ(result.stats.timesMs.front().first, "load");
    EXPECT_FLOAT_EQ(result.image.at(0, 0, 2), 1.0f);  // a corner of background
    EXPECT_FLOAT_EQ(result.image.at(0, 0, 0), 0.25f);
    load.background = std::array<float, 3>{-1.0f, 0.0f, 0.0f};
    EXPECT_THROW(sk::Scene::load("builtin:spin", load), streak::Error);
    load.background.reset();
    load.motionCurve = "spline";
    EXPECT_THROW(sk::Scene::load("builtin:spin", load), streak::Error);
    EXPECT_TRUE(sk::isGltfFile("model.glb"));
    EXPECT_FALSE(sk::isGltfFile("builtin:spin"));
    const std::vector<sk::SceneInfo> scenes = sk::builtinScenes();
    EXPECT_TRUE(std::any_of(scenes.begin(), scenes.end(), [](const sk::SceneInfo& s) { return s.name == "fence"; }));
}

// A trail method renders a glTF scene only as loaded over its trail; the shell built from that
// trail is written as glTF and loads back with every triangle.
TEST(Api, TrailsAndTheBlurShell) {
    const std::string fox = streak::test::sharedScene("Fox/glTF-Binary/Fox.glb");
    if (!std::filesystem::exists(fox)) GTEST_SKIP() << "no shared scenes at " << fox;
    sk::RenderSettings settings;
    settings.method = "blur-shell", settings.width = 32, settings.height = 24;
    sk::Renderer renderer(settings);
    ASSERT_TRUE(renderer.trail().has_value());
    sk::LoadOptions load;
    load.frame = 12, load.width = 32, load.height = 24;
    EXPECT_THROW(renderer.render(sk::Scene::load(fox, load)), streak::Error);
    load.trail = renderer.trail();
    const sk::Scene trail = sk::Scene::load(fox, load);
    const sk::RenderResult result = renderer.render(trail);
    EXPECT_GT(result.stats.counters.at("shell_triangles"), 0.0);
    EXPECT_EQ(result.stats.info.at("trail"), "0.3,0.5 s");

    const sk::BlurShell shell = sk::blurShell(trail, {});
    EXPECT_GT(shell.strips, 0u);
    EXPECT_EQ(double(shell.triangles), result.stats.counters.at("shell_triangles"));
    EXPECT_THROW(sk::blurShell(trail, {{"length", "0.5"}}), streak::Error);  // loaded over another trail
    EXPECT_THROW(sk::blurShellTrail({{"nosuch", "1"}}), streak::Error);
    streak::test::TempDir dir;
    for (const char* name : {"shell.glb", "shell.gltf"}) {
        const std::string path = (dir.path() / name).string();
        shell.scene.writeGltf(path);
        EXPECT_EQ(sk::Scene::load(path).numTriangles(), shell.scene.numTriangles()) << name;
    }
    EXPECT_THROW(shell.scene.writeGltf((dir.path() / "shell.obj").string()), streak::Error);
}
