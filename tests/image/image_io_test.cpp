#include "image/image_io.h"

#include "image/color.h"
#include "util/error.h"

#include "support/temp_dir.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <half.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace streak {
namespace {

using test::TempDir;

// Runs fn, expecting streak::Error whose message contains every one of needles.
template <typename Fn>
void expectError(Fn&& fn, const std::vector<std::string>& needles) {
    try {
        fn();
        ADD_FAILURE() << "no streak::Error thrown";
    } catch (const Error& e) {
        const std::string message = e.what();
        for (const std::string& needle : needles) EXPECT_NE(message.find(needle), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// 16x16 pixels whose R, G and B codes between them use every 8-bit code.
std::vector<std::uint8_t> allCodes() {
    std::vector<std::uint8_t> codes;
    for (int i = 0; i < 256; ++i) {
        codes.push_back(std::uint8_t(i));
        codes.push_back(std::uint8_t(255 - i));
        codes.push_back(std::uint8_t((i * 37 + 11) % 256));
    }
    return codes;
}

TEST(ImageIo, FormatFromExtension) {
    EXPECT_EQ(imageFormatFromPath("a.png"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFromPath("dir/A.PNG"), ImageFormat::Png);
    EXPECT_EQ(imageFormatFromPath("out.exr"), ImageFormat::Exr);
    EXPECT_EQ(imageFormatFromPath("x.png/out.Exr"), ImageFormat::Exr);
    expectError([] { imageFormatFromPath("render.tiff"); }, {"render.tiff", ".tiff"});
    expectError([] { imageFormatFromPath("render"); }, {"render", "extension"});
    expectError([] { imageFormatFromPath("png"); }, {"png"});
}

TEST(ImageIo, PngRoundTripKeepsCodes) {
    TempDir dir;
    const std::vector<std::uint8_t> codes = allCodes();
    Image image(16, 16);
    for (int i = 0; i < 256; ++i)
        image.pixels()[i] = {srgb8ToLinear(codes[3 * i]), srgb8ToLinear(codes[3 * i + 1]), srgb8ToLinear(codes[3 * i + 2])};

    const std::string path = dir.file("codes.png");
    writeImage(image, path);
    const Image back = readImage(path);
    ASSERT_EQ(back.width(), 16);
    ASSERT_EQ(back.height(), 16);
    for (int i = 0; i < 256; ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(linearToSrgb8(back.pixels()[i][c]), codes[3 * i + c]) << "pixel " << i << " channel " << c;
    for (int i = 0; i < 256; ++i) EXPECT_EQ(back.pixels()[i], image.pixels()[i]) << "pixel " << i;
}

TEST(ImageIo, PngKeepsOrientationAndShape) {
    TempDir dir;
    Image image(5, 3);
    image.at(0, 0) = glm::vec3(1, 0, 0);  // top left
    image.at(4, 2) = glm::vec3(0, 0, 1);  // bottom right
    image.at(4, 0) = glm::vec3(0, 1, 0);  // top right
    const std::string path = dir.file("shape.png");
    writeImage(image, path);
    const Image back = readImage(path);
    ASSERT_EQ(back.width(), 5);
    ASSERT_EQ(back.height(), 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) EXPECT_EQ(back.at(x, y), image.at(x, y)) << x << "," << y;
}

TEST(ImageIo, PngQuantizesAndClamps) {
    TempDir dir;
    Image image(4, 1);
    image.at(0, 0) = glm::vec3(0.3f, 0.01f, 0.77f);
    image.at(1, 0) = glm::vec3(2.0f, -1.0f, 1.0f);
    image.at(2, 0) = glm::vec3(1e-6f, 0.999f, 0.5f);
    const std::string path = dir.file("quantized.png");
    writeImage(image, path);
    const Image back = readImage(path);
    for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(back.at(x, 0)[c], srgb8ToLinear(linearToSrgb8(image.at(x, 0)[c]))) << x << "," << c;
    EXPECT_EQ(back.at(1, 0), glm::vec3(1.0f, 0.0f, 1.0f));
}

TEST(ImageIo, PngGreyAndAlphaInputs) {
    TempDir dir;
    const std::uint8_t grey[] = {0, 128, 255};
    const std::string greyPath = dir.file("grey.png");
    ASSERT_TRUE(stbi_write_png(greyPath.c_str(), 3, 1, 1, grey, 3));
    const Image greyImage = readImage(greyPath);
    ASSERT_EQ(greyImage.width(), 3);
    for (int x = 0; x < 3; ++x) EXPECT_EQ(greyImage.at(x, 0), glm::vec3(srgb8ToLinear(grey[x])));

    const std::uint8_t rgba[] = {10, 20, 30, 0, 200, 100, 50, 128};
    const std::string rgbaPath = dir.file("alpha.png");
    ASSERT_TRUE(stbi_write_png(rgbaPath.c_str(), 2, 1, 4, rgba, 8));
    // Straight colour in the file, premultiplied in the image: what shows over black.
    const Image rgbaImage = readImage(rgbaPath);
    ASSERT_TRUE(rgbaImage.hasAlpha());
    EXPECT_EQ(rgbaImage.alphaAt(0, 0), 0.0f);
    EXPECT_EQ(rgbaImage.alphaAt(1, 0), 128.0f / 255.0f);
    EXPECT_EQ(rgbaImage.at(0, 0), glm::vec3(0.0f));
    EXPECT_EQ(rgbaImage.at(1, 0), glm::vec3(srgb8ToLinear(200), srgb8ToLinear(100), srgb8ToLinear(50)) * (128.0f / 255.0f));
}

TEST(ImageIo, ExrKeepsPassChannelsAndCryptomatteMetadataAndRegionsCropThem) {
    Image image(3, 2, glm::vec3(0.5f));
    image.addChannel("Z", {1, 2, 3, 4, 5, 6});
    image.addChannel("CryptoObject00.r", {0.25f, 0, 0, 0, 0, -7.5f});
    image.setMetadata("cryptomatte/abcdef0/manifest", R"({"a":"3e800000"})");
    TempDir dir;
    writeImage(image, dir.file("passes.exr"));
    const Image back = readImage(dir.file("passes.exr"));
    ASSERT_EQ(back.channels().size(), 2u);
    for (const ImageChannel& c : back.channels()) {
        const ImageChannel& original = c.name == "Z" ? image.channels()[0] : image.channels()[1];
        EXPECT_EQ(c.name, original.name);
        EXPECT_EQ(c.values, original.values);
    }
    EXPECT_EQ(back.metadata().at("cryptomatte/abcdef0/manifest"), R"({"a":"3e800000"})");
    const Image right = image.region(1, 0, 3, 2);
    ASSERT_EQ(right.channels().size(), 2u);
    EXPECT_EQ(right.channels()[0].values, (std::vector<float>{2, 3, 5, 6}));
    EXPECT_EQ(right.metadata(), image.metadata());
    // A pass may not take the colour's names, nor come twice.
    EXPECT_THROW(image.addChannel("A", std::vector<float>(6)), Error);
    EXPECT_THROW(image.addChannel("Z", std::vector<float>(6)), Error);
    EXPECT_THROW(image.addChannel("Y2", std::vector<float>(5)), Error);
}

TEST(ImageIo, AlphaIsStraightInPngAndPremultipliedInExr) {
    // A premultiplied image: half-covered mid grey, a full cover, and nothing.
    Image image(3, 1);
    image.at(0, 0) = glm::vec3(0.25f, 0.1f, 0.05f);
    image.at(1, 0) = glm::vec3(0.8f, 0.6f, 0.4f);
    image.setAlpha({0.5f, 1.0f, 0.0f});
    TempDir dir;

    // EXR: R G B A as they are, premultiplied, and back to the bit.
    writeImage(image, dir.file("a.exr"));
    {
        Imf::InputFile file(dir.file("a.exr").c_str());
        EXPECT_NE(file.header().channels().findChannel("A"), nullptr);
    }
    const Image exr = readImage(dir.file("a.exr"));
    ASSERT_TRUE(exr.hasAlpha());
    for (int x = 0; x < 3; ++x) {
        EXPECT_EQ(exr.at(x, 0), image.at(x, 0));
        EXPECT_EQ(exr.alphaAt(x, 0), image.alphaAt(x, 0));
    }

    // PNG: four channels, colour divided by alpha before sRGB encoding, alpha linear.
    writeImage(image, dir.file("a.png"));
    int width = 0, height = 0, channels = 0;
    unsigned char* codes = stbi_load(dir.file("a.png").c_str(), &width, &height, &channels, 0);
    ASSERT_NE(codes, nullptr);
    EXPECT_EQ(channels, 4);
    EXPECT_EQ(codes[0], linearToSrgb8(0.5f));
    EXPECT_EQ(codes[1], linearToSrgb8(0.2f));
    EXPECT_EQ(codes[3], 128);
    EXPECT_EQ(codes[4], linearToSrgb8(0.8f));
    EXPECT_EQ(codes[7], 255);
    EXPECT_EQ(codes[8], 0);
    EXPECT_EQ(codes[11], 0);
    stbi_image_free(codes);

    // An image without alpha stays three channels.
    Image opaque(1, 1, glm::vec3(0.5f));
    writeImage(opaque, dir.file("o.png"));
    EXPECT_FALSE(readImage(dir.file("o.png")).hasAlpha());
    writeImage(opaque, dir.file("o.exr"));
    EXPECT_FALSE(readImage(dir.file("o.exr")).hasAlpha());
}

TEST(ImageIo, ExrRoundTripIsExact) {
    TempDir dir;
    const std::vector<float> values = {0.0f, 1.0f, 0.5f, 1e-8f, 3.75f, 12345.678f, -0.25f, 0.1f, 65504.0f, 1e20f};
    Image image(7, 3);
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        image.pixels()[i] = {values[i % values.size()], values[(i + 3) % values.size()], values[(i * 7) % values.size()]};

    const std::string path = dir.file("exact.exr");
    writeImage(image, path);
    const Image back = readImage(path);
    ASSERT_EQ(back.width(), 7);
    ASSERT_EQ(back.height(), 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 7; ++x) EXPECT_EQ(back.at(x, y), image.at(x, y)) << x << "," << y;
}

// Writes an EXR with the given channels; each channel's value at (x, y) is fill(channel, x, y).
template <typename Fill>
void writeRawExr(const std::string& path, Imath::Box2i dataWindow, const std::vector<std::string>& names,
                 Imf::PixelType type, Fill fill) {
    const int width = dataWindow.max.x - dataWindow.min.x + 1;
    const int height = dataWindow.max.y - dataWindow.min.y + 1;
    Imf::Header header(dataWindow, dataWindow);
    for (const std::string& name : names) header.channels().insert(name, Imf::Channel(type));
    std::vector<std::vector<float>> floats(names.size(), std::vector<float>(std::size_t(width) * height));
    std::vector<std::vector<half>> halves(names.size(), std::vector<half>(std::size_t(width) * height));
    Imf::FrameBuffer frameBuffer;
    for (std::size_t c = 0; c < names.size(); ++c) {
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                floats[c][std::size_t(y) * width + x] = fill(names[c], x, y);
                halves[c][std::size_t(y) * width + x] = half(fill(names[c], x, y));
            }
        const void* base = type == Imf::HALF ? static_cast<const void*>(halves[c].data()) : floats[c].data();
        const std::size_t size = type == Imf::HALF ? sizeof(half) : sizeof(float);
        frameBuffer.insert(names[c], Imf::Slice::Make(type, base, dataWindow, size, size * width));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(height);
}

TEST(ImageIo, ExrReadsHalfChannels) {
    TempDir dir;
    const std::string path = dir.file("half.exr");
    // Values exactly representable in half.
    auto fill = [](const std::string& name, int x, int y) { return float(name[0] - 'A') * 0.5f + x * 0.25f + y * 2.0f; };
    writeRawExr(path, Imath::Box2i({0, 0}, {3, 1}), {"R", "G", "B"}, Imf::HALF, fill);
    const Image image = readImage(path);
    ASSERT_EQ(image.width(), 4);
    ASSERT_EQ(image.height(), 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) EXPECT_EQ(image.at(x, y), glm::vec3(fill("R", x, y), fill("G", x, y), fill("B", x, y)));
}

TEST(ImageIo, ExrMissingChannelsAreZero) {
    TempDir dir;
    const std::string path = dir.file("rg.exr");
    writeRawExr(path, Imath::Box2i({0, 0}, {1, 1}), {"R", "G", "A"}, Imf::FLOAT,
                [](const std::string& name, int x, int y) { return name == "A" ? 9.0f : 1.5f + x + y; });
    const Image image = readImage(path);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) EXPECT_EQ(image.at(x, y), glm::vec3(1.5f + x + y, 1.5f + x + y, 0.0f));
}

TEST(ImageIo, ExrLuminanceOnlyIsGrey) {
    TempDir dir;
    const std::string path = dir.file("y.exr");
    writeRawExr(path, Imath::Box2i({0, 0}, {2, 0}), {"Y"}, Imf::HALF,
                [](const std::string&, int x, int) { return 0.25f * x; });
    const Image image = readImage(path);
    ASSERT_EQ(image.width(), 3);
    ASSERT_EQ(image.height(), 1);
    for (int x = 0; x < 3; ++x) EXPECT_EQ(image.at(x, 0), glm::vec3(0.25f * x));
}

TEST(ImageIo, ExrDataWindowOffset) {
    TempDir dir;
    const std::string path = dir.file("offset.exr");
    writeRawExr(path, Imath::Box2i({-3, 10}, {0, 11}), {"R", "G", "B"}, Imf::FLOAT,
                [](const std::string& name, int x, int y) { return float(name[0]) + 10.0f * x + 100.0f * y; });
    const Image image = readImage(path);
    ASSERT_EQ(image.width(), 4);
    ASSERT_EQ(image.height(), 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_EQ(image.at(x, y), glm::vec3('R', 'G', 'B') + glm::vec3(10.0f * x + 100.0f * y));
}

// A region of a frame (a border render) is written as its data window inside the frame's
// display window, as compositors read it, and read back placed; PNG, which has no windows, gets
// the region's pixels alone. An image that does not fit its frame is refused.
TEST(ImageIo, ExrRegionKeepsItsPlaceInTheFrame) {
    TempDir dir;
    Image frame(10, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 10; ++x) frame.at(x, y) = glm::vec3(0.01f * x, 0.1f * y, 0.5f);
    const Image region = frame.region(5, 4, 8, 6);
    ASSERT_TRUE(region.placement().has_value());
    writeImage(region, dir.file("region.exr"));
    {
        Imf::InputFile raw(dir.file("region.exr").c_str());
        EXPECT_EQ(raw.header().displayWindow(), Imath::Box2i({0, 0}, {9, 7}));
        EXPECT_EQ(raw.header().dataWindow(), Imath::Box2i({5, 4}, {7, 5}));
    }
    const Image back = readImage(dir.file("region.exr"));
    ASSERT_EQ(back.width(), 3);
    ASSERT_EQ(back.height(), 2);
    ASSERT_TRUE(back.placement().has_value());
    EXPECT_EQ(back.placement()->x, 5); EXPECT_EQ(back.placement()->y, 4);
    EXPECT_EQ(back.placement()->frameWidth, 10); EXPECT_EQ(back.placement()->frameHeight, 8);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) EXPECT_EQ(back.at(x, y), frame.at(5 + x, 4 + y));
    EXPECT_FALSE(readImage((writeImage(frame, dir.file("frame.exr")), dir.file("frame.exr"))).placement().has_value());
    writeImage(region, dir.file("region.png"));
    EXPECT_EQ(readImage(dir.file("region.png")).width(), 3);

    Image loose(3, 2);
    expectError([&] { loose.place({8, 0, 10, 8}); }, {"does not lie inside a 10x8 frame"});
    expectError([&] { (void)frame.region(5, 4, 11, 6); }, {"not inside the 10x8 image"});
}

TEST(ImageIo, OverwritesExistingFile) {
    TempDir dir;
    for (const std::string name : {"over.png", "over.exr"}) {
        const std::string path = dir.file(name);
        writeImage(Image(2, 2, glm::vec3(1.0f)), path);
        writeImage(Image(3, 1, glm::vec3(0.0f)), path);
        const Image back = readImage(path);
        EXPECT_EQ(back.width(), 3);
        EXPECT_EQ(back.at(2, 0), glm::vec3(0.0f));
    }
    EXPECT_EQ(dir.entries().size(), 2u);
}

TEST(ImageIo, UnwritablePathThrowsAndLeavesNothing) {
    TempDir dir;
    const Image image(2, 2, glm::vec3(0.5f));
    for (const std::string name : {"out.png", "out.exr"}) {
        const std::string missing = (dir.path() / "no-such-dir" / name).string();
        expectError([&] { writeImage(image, missing); }, {"cannot write", missing});
        // A directory in the way of the target: the temporary file is written, then the
        // rename fails; it must be cleaned up.
        const std::string blocked = dir.file("blocked-" + name);
        std::filesystem::create_directory(blocked);
        expectError([&] { writeImage(image, blocked); }, {"cannot write", blocked});
        EXPECT_TRUE(std::filesystem::is_directory(blocked));
        EXPECT_TRUE(std::filesystem::is_empty(blocked));
    }
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "no-such-dir"));
    std::vector<std::string> entries = dir.entries();
    std::sort(entries.begin(), entries.end());
    EXPECT_EQ(entries, (std::vector<std::string>{"blocked-out.exr", "blocked-out.png"}));
}

TEST(ImageIo, EmptyImageIsNotWritten) {
    TempDir dir;
    const std::string path = dir.file("empty.png");
    expectError([&] { writeImage(Image(), path); }, {"cannot write", path});
    EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageIo, UnknownExtensionThrows) {
    TempDir dir;
    const std::string path = dir.file("out.jpg");
    expectError([&] { writeImage(Image(1, 1), path); }, {path, ".jpg"});
    EXPECT_TRUE(dir.entries().empty());
    writeBytes(path, "not really a jpeg");
    expectError([&] { readImage(path); }, {path, ".jpg"});
}

TEST(ImageIo, MissingFileThrows) {
    TempDir dir;
    for (const std::string name : {"missing.png", "missing.exr"}) {
        const std::string path = dir.file(name);
        expectError([&] { readImage(path); }, {"cannot read", path});
    }
}

TEST(ImageIo, DirectoryThrows) {
    TempDir dir;
    const std::string path = dir.file("dir.png");
    std::filesystem::create_directory(path);
    expectError([&] { readImage(path); }, {"cannot read", path});
}

TEST(ImageIo, CorruptFileThrows) {
    TempDir dir;
    for (const std::string name : {"garbage.png", "garbage.exr"}) {
        const std::string path = dir.file(name);
        writeBytes(path, "this is not an image at all");
        expectError([&] { readImage(path); }, {"cannot read", path});
        writeBytes(path, "");
        expectError([&] { readImage(path); }, {"cannot read", path});
    }
}

TEST(ImageIo, TruncatedFileThrows) {
    TempDir dir;
    Image image(64, 64);
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        image.pixels()[i] = glm::vec3(float(i % 97) / 97.0f, float(i % 13) / 13.0f, float(i % 7) / 7.0f);
    for (const std::string name : {"cut.png", "cut.exr"}) {
        const std::string path = dir.file(name);
        writeImage(image, path);
        const std::string bytes = readBytes(path);
        writeBytes(path, bytes.substr(0, bytes.size() / 2));
        expectError([&] { readImage(path); }, {"cannot read", path});
    }
}

TEST(ImageIo, PngIsNotSniffedFromOtherFormats) {
    TempDir dir;
    // A valid EXR under a .png name must be refused, not decoded by guesswork.
    const std::string exr = dir.file("real.exr");
    writeImage(Image(2, 2), exr);
    const std::string png = dir.file("fake.png");
    std::filesystem::copy_file(exr, png);
    expectError([&] { readImage(png); }, {"cannot read", png});
}

}  // namespace
}  // namespace streak
