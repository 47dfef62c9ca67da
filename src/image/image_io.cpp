#include "image/image_io.h"

#include "image/color.h"
#include "image/deep_image.h"
#include "util/error.h"
#include "util/file_io.h"

#include <Iex.h>
#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineInputFile.h>
#include <ImfDeepScanLineOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace streak {

namespace {

// Helpers throw std::runtime_error carrying only the reason; writeImage/readImage add the path.

// streak::Error messages are one line; library messages occasionally are not.
std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// OpenEXR's encoder seeks back to patch its offset table, so it needs a seekable sink.
class MemoryOStream : public Imf::OStream {
public:
    explicit MemoryOStream(const std::string& name) : Imf::OStream(name.c_str()) {}

    void write(const char c[], int n) override {
        const std::size_t end = m_pos + std::size_t(n);
        if (end > m_bytes.size()) m_bytes.resize(end);
        std::memcpy(m_bytes.data() + m_pos, c, std::size_t(n));
        m_pos = end;
    }
    std::uint64_t tellp() override { return m_pos; }
    void seekp(std::uint64_t pos) override { m_pos = std::size_t(pos); }

    std::vector<char>& bytes() { return m_bytes; }

private:
    std::vector<char> m_bytes;
    std::size_t m_pos = 0;
};

class MemoryIStream : public Imf::IStream {
public:
    MemoryIStream(const std::string& name, const std::vector<char>& bytes)
        : Imf::IStream(name.c_str()), m_bytes(bytes) {}

    bool read(char c[], int n) override {
        if (n < 0 || m_pos > m_bytes.size() || std::size_t(n) > m_bytes.size() - m_pos)
            throw Iex::InputExc("unexpected end of file");
        std::memcpy(c, m_bytes.data() + m_pos, std::size_t(n));
        m_pos += std::size_t(n);
        return m_pos < m_bytes.size();
    }
    std::uint64_t tellg() override { return m_pos; }
    void seekg(std::uint64_t pos) override { m_pos = std::size_t(pos); }

private:
    const std::vector<char>& m_bytes;
    std::size_t m_pos = 0;
};

void appendBytes(void* context, void* data, int size) {
    auto* bytes = static_cast<std::vector<char>*>(context);
    const char* begin = static_cast<const char*>(data);
    bytes->insert(bytes->end(), begin, begin + size);
}

// PNG's colour is straight, not premultiplied: an image with alpha is divided by it (colour 0
// where nothing covers), and its alpha is stored linear, as the format says.
std::vector<char> encodePng(const Image& image) {
    const int channels = image.hasAlpha() ? 4 : 3;
    std::vector<std::uint8_t> codes;
    codes.reserve(image.pixels().size() * std::size_t(channels));
    for (std::size_t i = 0; i < image.pixels().size(); ++i) {
        glm::vec3 p = image.pixels()[i];
        if (image.hasAlpha()) {
            const float a = std::clamp(image.alpha()[i], 0.0f, 1.0f);
            p = a > 0.0f ? p / a : glm::vec3(0.0f);
        }
        codes.push_back(linearToSrgb8(p.x));
        codes.push_back(linearToSrgb8(p.y));
        codes.push_back(linearToSrgb8(p.z));
        if (image.hasAlpha()) codes.push_back(std::uint8_t(std::lround(std::clamp(image.alpha()[i], 0.0f, 1.0f) * 255.0f)));
    }
    std::vector<char> bytes;
    if (!stbi_write_png_to_func(appendBytes, &bytes, image.width(), image.height(), channels,
                                codes.data(), image.width() * channels))
        throw std::runtime_error("PNG encoding failed");
    return bytes;
}

// A header of the image's size and placement (a region: the data window inside the frame).
Imf::Header headerFor(int width, int height, const std::optional<FramePlacement>& placement) {
    Imf::Header header(width, height);
    if (placement) {
        header.displayWindow() = Imath::Box2i({0, 0}, {placement->frameWidth - 1, placement->frameHeight - 1});
        header.dataWindow() = Imath::Box2i({placement->x, placement->y}, {placement->x + width - 1, placement->y + height - 1});
    }
    return header;
}

std::vector<char> encodeExr(const Image& image, const std::string& path) {
    Imf::Header header = headerFor(image.width(), image.height(), image.placement());  // ZIP compression: lossless
    const Imath::Box2i dataWindow = header.dataWindow();
    for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    if (image.hasAlpha()) header.channels().insert("A", Imf::Channel(Imf::FLOAT));

    // Slice wants a non-const base pointer even for writing; it only reads through it.
    auto* first = const_cast<glm::vec3*>(image.pixels().data());
    const std::size_t xStride = sizeof(glm::vec3);
    const std::size_t yStride = xStride * std::size_t(image.width());
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("R", Imf::Slice::Make(Imf::FLOAT, &first->x, dataWindow, xStride, yStride));
    frameBuffer.insert("G", Imf::Slice::Make(Imf::FLOAT, &first->y, dataWindow, xStride, yStride));
    frameBuffer.insert("B", Imf::Slice::Make(Imf::FLOAT, &first->z, dataWindow, xStride, yStride));
    if (image.hasAlpha())
        frameBuffer.insert("A", Imf::Slice::Make(Imf::FLOAT, const_cast<float*>(image.alpha().data()), dataWindow, sizeof(float),
                                                 sizeof(float) * std::size_t(image.width())));
    for (const ImageChannel& c : image.channels()) {
        header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
        frameBuffer.insert(c.name, Imf::Slice::Make(Imf::FLOAT, const_cast<float*>(c.values.data()), dataWindow, sizeof(float),
                                                    sizeof(float) * std::size_t(image.width())));
    }
    for (const auto& [key, value] : image.metadata()) header.insert(key, Imf::StringAttribute(value));

    MemoryOStream stream(path);
    {
        // The offset table is written by the destructor, which swallows errors; in memory it
        // cannot fail, and the real file I/O below reports its own errors.
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frameBuffer);
        file.writePixels(image.height());
    }
    return std::move(stream.bytes());
}

std::vector<char> readFile(const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) throw std::runtime_error(errnoReason(errno));
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(file, std::fclose);

    std::vector<char> bytes;
    std::error_code ec;
    if (const auto size = std::filesystem::file_size(path, ec); !ec) bytes.reserve(size);
    char chunk[1 << 16];
    std::size_t n = 0;
    while ((n = std::fread(chunk, 1, sizeof(chunk), file)) > 0) bytes.insert(bytes.end(), chunk, chunk + n);
    if (std::ferror(file)) throw std::runtime_error(errnoReason(errno ? errno : EIO));  // e.g. a directory
    return bytes;
}

Image decodePng(const std::vector<char>& bytes) {
    static constexpr unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    // stb would also decode JPEG, BMP, ... behind a .png name; refuse rather than guess.
    if (bytes.size() < sizeof(signature) || std::memcmp(bytes.data(), signature, sizeof(signature)) != 0)
        throw std::runtime_error("not a PNG file");
    if (bytes.size() > std::size_t(INT_MAX)) throw std::runtime_error("file too large");

    const auto* buffer = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int length = int(bytes.size());
    int width = 0, height = 0, channels = 0;
    const bool sixteenBit = stbi_is_16_bit_from_memory(buffer, length);
    // Grey and alpha (2) or RGBA (4): the alpha comes in too.
    if (!stbi_info_from_memory(buffer, length, &width, &height, &channels)) channels = 3;
    const int wanted = channels == 2 || channels == 4 ? 4 : 3;
    void* data = sixteenBit ? static_cast<void*>(stbi_load_16_from_memory(buffer, length, &width, &height, &channels, wanted))
                            : static_cast<void*>(stbi_load_from_memory(buffer, length, &width, &height, &channels, wanted));
    if (!data) {
        const char* reason = stbi_failure_reason();
        throw std::runtime_error(std::string("corrupt PNG (") + (reason ? reason : "unknown error") + ")");
    }
    std::unique_ptr<void, void (*)(void*)> owner(data, stbi_image_free);

    Image image(width, height);
    auto pixels = image.pixels();
    std::vector<float> alpha(wanted == 4 ? pixels.size() : 0);
    const std::size_t n = std::size_t(wanted);
    if (sixteenBit) {
        const auto* codes = static_cast<const std::uint16_t*>(data);
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            for (int c = 0; c < 3; ++c) pixels[i][c] = srgbToLinear(codes[n * i + std::size_t(c)] / 65535.0f);
            if (!alpha.empty()) alpha[i] = codes[n * i + 3] / 65535.0f;
        }
    } else {
        const auto* codes = static_cast<const std::uint8_t*>(data);
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            for (int c = 0; c < 3; ++c) pixels[i][c] = srgb8ToLinear(codes[n * i + std::size_t(c)]);
            if (!alpha.empty()) alpha[i] = codes[n * i + 3] / 255.0f;
        }
    }
    // Straight colour in the file; premultiplied in an Image.
    for (std::size_t i = 0; i < alpha.size(); ++i) pixels[i] *= alpha[i];
    image.setAlpha(std::move(alpha));
    return image;
}

Image decodeExr(const std::vector<char>& bytes, const std::string& path) {
    MemoryIStream stream(path, bytes);
    Imf::InputFile file(stream);
    const Imath::Box2i dataWindow = file.header().dataWindow();
    const std::int64_t width = std::int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
    const std::int64_t height = std::int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
    if (width <= 0 || height <= 0 || width > INT_MAX || height > INT_MAX)
        throw std::runtime_error("bad data window");

    Image image(static_cast<int>(width), static_cast<int>(height));
    glm::vec3* first = image.pixels().data();
    const std::size_t xStride = sizeof(glm::vec3);
    const std::size_t yStride = xStride * std::size_t(width);
    const Imf::ChannelList& channels = file.header().channels();
    const bool grey = !channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B") &&
                      channels.findChannel("Y");

    // Channels absent from the file are filled with 0; half and uint data convert to float.
    Imf::FrameBuffer frameBuffer;
    if (grey) {
        frameBuffer.insert("Y", Imf::Slice::Make(Imf::FLOAT, &first->x, dataWindow, xStride, yStride));
    } else {
        frameBuffer.insert("R", Imf::Slice::Make(Imf::FLOAT, &first->x, dataWindow, xStride, yStride));
        frameBuffer.insert("G", Imf::Slice::Make(Imf::FLOAT, &first->y, dataWindow, xStride, yStride));
        frameBuffer.insert("B", Imf::Slice::Make(Imf::FLOAT, &first->z, dataWindow, xStride, yStride));
    }
    // Every other float channel is a pass; string attributes named like Cryptomatte's come too.
    std::vector<ImageChannel> passes;
    for (Imf::ChannelList::ConstIterator c = channels.begin(); c != channels.end(); ++c) {
        const std::string name = c.name();
        // Subsampled channels (luminance/chroma images' RY, BY) are not passes: left out.
        if (name == "R" || name == "G" || name == "B" || name == "A" || (grey && name == "Y") || c.channel().xSampling != 1 ||
            c.channel().ySampling != 1)
            continue;
        passes.push_back({name, std::vector<float>(std::size_t(width) * std::size_t(height), 0.0f)});
    }
    for (ImageChannel& c : passes)
        frameBuffer.insert(c.name, Imf::Slice::Make(Imf::FLOAT, c.values.data(), dataWindow, sizeof(float), sizeof(float) * std::size_t(width)));
    std::vector<float> alpha;
    if (channels.findChannel("A")) {
        alpha.assign(std::size_t(width) * std::size_t(height), 0.0f);
        frameBuffer.insert("A", Imf::Slice::Make(Imf::FLOAT, alpha.data(), dataWindow, sizeof(float), sizeof(float) * std::size_t(width)));
    }
    file.setFrameBuffer(frameBuffer);
    file.readPixels(dataWindow.min.y, dataWindow.max.y);
    image.setAlpha(std::move(alpha));
    for (ImageChannel& c : passes) image.addChannel(std::move(c.name), std::move(c.values));
    for (Imf::Header::ConstIterator a = file.header().begin(); a != file.header().end(); ++a)
        if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&a.attribute()); text && std::string(a.name()).rfind("cryptomatte/", 0) == 0)
            image.setMetadata(a.name(), text->value());

    if (grey)
        for (glm::vec3& p : image.pixels()) p = glm::vec3(p.x);
    // A data window inside a larger display window (starting at 0, 0) is a region of that frame.
    const Imath::Box2i displayWindow = file.header().displayWindow();
    if (displayWindow != dataWindow && displayWindow.min == Imath::V2i(0, 0) && displayWindow.intersects(dataWindow.min) &&
        displayWindow.intersects(dataWindow.max))
        image.place({dataWindow.min.x, dataWindow.min.y, displayWindow.max.x + 1, displayWindow.max.y + 1});
    return image;
}

// The deep channels, in the order DeepSample holds them.
struct DeepChannel {
    const char* name;
    std::size_t offset;  ///< in DeepSample
};
const DeepChannel kDeepChannels[] = {{"Z", offsetof(DeepSample, z)},          {"ZBack", offsetof(DeepSample, zBack)},
                                     {"R", offsetof(DeepSample, color)},      {"G", offsetof(DeepSample, color) + sizeof(float)},
                                     {"B", offsetof(DeepSample, color) + 2 * sizeof(float)}, {"A", offsetof(DeepSample, alpha)}};

// Deep scanline (what Nuke's DeepRead takes), ZIPS-compressed (lossless; deep data allows no
// block compression), declared tidy: each pixel's samples are sorted and none overlap.
std::vector<char> encodeDeepExr(const DeepImage& image, const std::string& path) {
    Imf::Header header = headerFor(image.width(), image.height(), image.placement());
    header.setType(Imf::DEEPSCANLINE);
    header.compression() = Imf::ZIPS_COMPRESSION;
    Imf::addDeepImageState(header, Imf::DIS_TIDY);
    const Imath::Box2i dataWindow = header.dataWindow();
    const std::size_t width = std::size_t(image.width()), pixels = width * std::size_t(image.height());
    std::vector<unsigned int> counts(pixels);
    std::span<const std::uint64_t> offsets = image.offsets();
    for (std::size_t i = 0; i < pixels; ++i) counts[i] = static_cast<unsigned int>(offsets[i + 1] - offsets[i]);
    // Per channel, per pixel: where its first sample's value lies (the slices' base is the
    // data window's origin, as Slice::Make places a flat one).
    const std::ptrdiff_t origin = std::ptrdiff_t(dataWindow.min.y) * std::ptrdiff_t(width) + dataWindow.min.x;
    std::vector<std::vector<char*>> pointers(std::size(kDeepChannels), std::vector<char*>(pixels));
    auto* samples = reinterpret_cast<char*>(const_cast<DeepSample*>(image.allSamples().data()));
    Imf::DeepFrameBuffer frameBuffer;
    frameBuffer.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data() - origin), sizeof(unsigned int),
                                                  sizeof(unsigned int) * width));
    for (std::size_t c = 0; c < std::size(kDeepChannels); ++c) {
        header.channels().insert(kDeepChannels[c].name, Imf::Channel(Imf::FLOAT));
        for (std::size_t i = 0; i < pixels; ++i) pointers[c][i] = samples + offsets[i] * sizeof(DeepSample) + kDeepChannels[c].offset;
        frameBuffer.insert(kDeepChannels[c].name, Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(pointers[c].data() - origin), sizeof(char*),
                                                                 sizeof(char*) * width, sizeof(DeepSample)));
    }
    MemoryOStream stream(path);
    {
        Imf::DeepScanLineOutputFile file(stream, header);
        file.setFrameBuffer(frameBuffer);
        file.writePixels(image.height());
    }
    return std::move(stream.bytes());
}

DeepImage decodeDeepExr(const std::vector<char>& bytes, const std::string& path) {
    MemoryIStream stream(path, bytes);
    Imf::DeepScanLineInputFile file(stream);
    const Imath::Box2i dataWindow = file.header().dataWindow(), displayWindow = file.header().displayWindow();
    const std::int64_t width = std::int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
    const std::int64_t height = std::int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
    if (width <= 0 || height <= 0 || width > INT_MAX || height > INT_MAX) throw std::runtime_error("bad data window");
    // Z and A are what make deep data; ZBack, when absent, is Z (a point sample), and a missing
    // colour is black.
    for (const char* name : {"Z", "A"})
        if (!file.header().channels().findChannel(name)) throw std::runtime_error(std::string("no deep channel ") + name);
    const bool hasZBack = file.header().channels().findChannel("ZBack") != nullptr;
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const std::ptrdiff_t origin = std::ptrdiff_t(dataWindow.min.y) * std::ptrdiff_t(width) + dataWindow.min.x;
    std::vector<unsigned int> counts(pixels);
    Imf::DeepFrameBuffer frameBuffer;
    frameBuffer.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data() - origin), sizeof(unsigned int),
                                                  sizeof(unsigned int) * std::size_t(width)));
    std::vector<std::vector<char*>> pointers(std::size(kDeepChannels), std::vector<char*>(pixels));
    for (std::size_t c = 0; c < std::size(kDeepChannels); ++c)
        frameBuffer.insert(kDeepChannels[c].name, Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(pointers[c].data() - origin), sizeof(char*),
                                                                 sizeof(char*) * std::size_t(width), sizeof(DeepSample)));
    file.setFrameBuffer(frameBuffer);
    file.readPixelSampleCounts(dataWindow.min.y, dataWindow.max.y);
    std::vector<std::vector<DeepSample>> perPixel(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        perPixel[i].resize(counts[i]);
        auto* first = reinterpret_cast<char*>(perPixel[i].data());
        for (std::size_t c = 0; c < std::size(kDeepChannels); ++c) pointers[c][i] = first + kDeepChannels[c].offset;
    }
    file.readPixels(dataWindow.min.y, dataWindow.max.y);
    if (!hasZBack)
        for (std::vector<DeepSample>& samples : perPixel)
            for (DeepSample& s : samples) s.zBack = s.z;
    DeepImage image{int(width), int(height)};
    image.assign(perPixel);
    if (displayWindow != dataWindow && displayWindow.min == Imath::V2i(0, 0) && displayWindow.intersects(dataWindow.min) &&
        displayWindow.intersects(dataWindow.max))
        image.place({dataWindow.min.x, dataWindow.min.y, displayWindow.max.x + 1, displayWindow.max.y + 1});
    return image;
}

}  // namespace

ImageFormat imageFormatFromPath(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension == ".png") return ImageFormat::Png;
    if (extension == ".exr") return ImageFormat::Exr;
    if (extension.empty()) throw Error(path + ": no image extension (expected .png or .exr)");
    throw Error(path + ": unknown image extension '" + extension + "' (expected .png or .exr)");
}

void writeImage(const Image& image, const std::string& path) {
    const ImageFormat format = imageFormatFromPath(path);
    if (image.empty()) throw Error("cannot write " + path + ": image is empty");
    try {
        const std::vector<char> bytes = format == ImageFormat::Png ? encodePng(image) : encodeExr(image, path);
        writeFileAtomically(path, bytes);
    } catch (const std::exception& e) {
        throw Error("cannot write " + path + ": " + oneLine(e.what()));
    }
}

void writeDeepImage(const DeepImage& image, const std::string& path) {
    if (imageFormatFromPath(path) != ImageFormat::Exr) throw Error("cannot write " + path + ": a deep image is written to EXR (.exr)");
    if (image.width() <= 0 || image.height() <= 0) throw Error("cannot write " + path + ": deep image is empty");
    try {
        writeFileAtomically(path, encodeDeepExr(image, path));
    } catch (const std::exception& e) {
        throw Error("cannot write " + path + ": " + oneLine(e.what()));
    }
}

DeepImage readDeepImage(const std::string& path) {
    if (imageFormatFromPath(path) != ImageFormat::Exr) throw Error("cannot read " + path + ": a deep image is read from EXR (.exr)");
    try {
        return decodeDeepExr(readFile(path), path);
    } catch (const std::exception& e) {
        throw Error("cannot read " + path + ": " + oneLine(e.what()));
    }
}

Image readImage(const std::string& path) {
    const ImageFormat format = imageFormatFromPath(path);
    try {
        const std::vector<char> bytes = readFile(path);
        return format == ImageFormat::Png ? decodePng(bytes) : decodeExr(bytes, path);
    } catch (const std::exception& e) {
        throw Error("cannot read " + path + ": " + oneLine(e.what()));
    }
}

}  // namespace streak
