#include "image/image_io.h"

#include "image/color.h"
#include "util/error.h"
#include "util/file_io.h"

#include <Iex.h>
#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
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

std::vector<char> encodeExr(const Image& image, const std::string& path) {
    Imf::Header header(image.width(), image.height());  // ZIP compression: lossless
    if (const std::optional<FramePlacement>& p = image.placement()) {
        // A region: the frame is the display window, the region the data window inside it.
        header.displayWindow() = Imath::Box2i({0, 0}, {p->frameWidth - 1, p->frameHeight - 1});
        header.dataWindow() = Imath::Box2i({p->x, p->y}, {p->x + image.width() - 1, p->y + image.height() - 1});
    }
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
