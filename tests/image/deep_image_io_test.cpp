// Deep EXR through streak (image_io.h) and back through OpenEXR itself: its deep reader and its
// own deep compositing (CompositeDeepScanLine, the library's "Interpreting Deep Pixels").

#include "image/deep_image.h"
#include "image/image_io.h"
#include "util/error.h"

#include "support/temp_dir.h"

#include <ImathBox.h>
#include <ImfCompositeDeepScanLine.h>
#include <ImfDeepScanLineInputFile.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfStandardAttributes.h>
#include <glm/vec4.hpp>
#include <gtest/gtest.h>

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace streak {
namespace {

using test::TempDir;

// A 3 x 2 deep image: an empty pixel, one opaque sample, two side by side with the background,
// a volume sample, and the rest.
DeepImage sampleImage() {
    std::vector<std::vector<DeepSample>> pixels(6);
    pixels[1] = {{1.0f, 1.0f, glm::vec3(0.2f, 0.4f, 0.6f), 1.0f}};
    pixels[2] = {{2.0f, 2.0f, glm::vec3(0.3f), 0.3f}, {3.0f, 3.5f, glm::vec3(0.25f / 0.7f, 0.0f, 0.0f), 0.5f / 0.7f}, {1e10f, 1e10f, glm::vec3(0.5f), 1.0f}};
    pixels[3] = {{4.0f, 6.0f, glm::vec3(0.0f, 0.1f, 0.0f), 0.25f}};
    pixels[4] = {{0.5f, 0.75f, glm::vec3(0.1f), 0.1f}, {0.75f, 2.0f, glm::vec3(0.45f), 0.5f}};
    pixels[5] = {{7.0f, 7.0f, glm::vec3(1.0f), 1.0f}};
    DeepImage image(3, 2);
    image.assign(pixels);
    return image;
}

glm::vec4 over(std::span<const DeepSample> samples) {
    glm::vec4 out(0.0f);
    for (const DeepSample& s : samples) out += (1.0f - out.w) * glm::vec4(s.color, s.alpha);
    return out;
}

// The file flattened by OpenEXR: RGBA per pixel of its data window.
std::vector<glm::vec4> compositeByOpenExr(const std::string& path, Imath::Box2i& dataWindow) {
    Imf::DeepScanLineInputFile file(path.c_str());
    dataWindow = file.header().dataWindow();
    const int width = dataWindow.max.x - dataWindow.min.x + 1, height = dataWindow.max.y - dataWindow.min.y + 1;
    std::vector<glm::vec4> out(std::size_t(width) * std::size_t(height));
    Imf::CompositeDeepScanLine composite;
    composite.addSource(&file);
    Imf::FrameBuffer frameBuffer;
    const char* names[] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; ++c)
        frameBuffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, &out[0][c], dataWindow, sizeof(glm::vec4), sizeof(glm::vec4) * std::size_t(width)));
    composite.setFrameBuffer(frameBuffer);
    composite.readPixels(dataWindow.min.y, dataWindow.max.y);
    return out;
}

TEST(DeepImageIo, OpenExrReadsAndCompositesWhatStreakWrites) {
    TempDir dir;
    const DeepImage image = sampleImage();
    writeDeepImage(image, dir.file("deep.exr"));
    Imath::Box2i window;
    const std::vector<glm::vec4> flat = compositeByOpenExr(dir.file("deep.exr"), window);
    EXPECT_EQ(window, Imath::Box2i({0, 0}, {2, 1}));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            const glm::vec4 expected = over(image.samples(x, y));
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(flat[std::size_t(y) * 3 + std::size_t(x)][c], expected[c], 1e-6f) << x << "," << y << " " << c;
        }
    // Pixel 2's three samples side by side: 0.3 + 0.25 of colour over 0.2 of a 0.5 background.
    EXPECT_NEAR(flat[2].x, 0.3f + 0.25f + 0.2f * 0.5f, 1e-6f);
    EXPECT_NEAR(flat[2].w, 1.0f, 1e-6f);
    Imf::DeepScanLineInputFile file(dir.file("deep.exr").c_str());
    ASSERT_TRUE(Imf::hasDeepImageState(file.header()));
    EXPECT_EQ(Imf::deepImageState(file.header()), Imf::DIS_TIDY);
    EXPECT_EQ(file.header().compression(), Imf::ZIPS_COMPRESSION);
}

TEST(DeepImageIo, RoundTripIsExactAndARegionKeepsItsPlace) {
    TempDir dir;
    const DeepImage image = sampleImage();
    writeDeepImage(image, dir.file("deep.exr"));
    const DeepImage back = readDeepImage(dir.file("deep.exr"));
    ASSERT_EQ(back.width(), 3);
    ASSERT_EQ(back.height(), 2);
    EXPECT_FALSE(back.placement());
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            const std::span<const DeepSample> a = image.samples(x, y), b = back.samples(x, y);
            ASSERT_EQ(a.size(), b.size());
            for (std::size_t k = 0; k < a.size(); ++k) {
                EXPECT_EQ(a[k].z, b[k].z);
                EXPECT_EQ(a[k].zBack, b[k].zBack);
                EXPECT_EQ(a[k].alpha, b[k].alpha);
                EXPECT_EQ(a[k].color, b[k].color);
            }
        }
    // Pixels [1, 3) x [1, 2): the data window inside the 3 x 2 display window.
    const DeepImage region = image.region(1, 1, 3, 2);
    writeDeepImage(region, dir.file("region.exr"));
    Imath::Box2i window;
    const std::vector<glm::vec4> flat = compositeByOpenExr(dir.file("region.exr"), window);
    EXPECT_EQ(window, Imath::Box2i({1, 1}, {2, 1}));
    ASSERT_EQ(flat.size(), 2u);
    EXPECT_NEAR(flat[0].y, over(image.samples(1, 1)).y, 1e-6f);
    EXPECT_NEAR(flat[1].x, 1.0f, 1e-6f);
    const DeepImage regionBack = readDeepImage(dir.file("region.exr"));
    ASSERT_TRUE(regionBack.placement());
    EXPECT_EQ(regionBack.placement()->x, 1);
    EXPECT_EQ(regionBack.placement()->frameWidth, 3);
    EXPECT_EQ(regionBack.samples(1, 0).size(), 1u);
}

TEST(DeepImageIo, BadPathsThrowOneLineAndWriteNothing) {
    TempDir dir;
    for (const std::string& path : {dir.file("deep.png"), dir.file("missing/deep.exr")}) {
        try {
            writeDeepImage(sampleImage(), path);
            ADD_FAILURE() << "no error for " << path;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
        EXPECT_FALSE(std::filesystem::exists(path));
    }
    EXPECT_THROW(readDeepImage(dir.file("none.exr")), Error);
}

}  // namespace
}  // namespace streak
