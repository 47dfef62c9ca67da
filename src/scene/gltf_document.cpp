// tinygltf's implementation lives in this one file (see gltf_document.h for its switches).
#define TINYGLTF_IMPLEMENTATION
#include "scene/gltf_document.h"

#include "scene/gltf_accessor.h"
#include "util/error.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

namespace streak::gltf {

namespace {

// The required extensions streak implements; any other in extensionsRequired is an error.
const std::set<std::string> kSupportedRequiredExtensions{"KHR_texture_transform"};

// tinygltf's messages span lines; an Error is one line.
std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.empty() ? "unknown error" : text;
}

struct ParseContext {
    const DocumentLimits* limits = nullptr;
    std::vector<std::vector<std::uint8_t>>* encodedImages = nullptr;
};

bool fileExists(const std::string& path, void* user) {
    const auto* context = static_cast<const ParseContext*>(user);
    std::error_code ec;
    return context->limits->allowExternalFiles && std::filesystem::is_regular_file(path, ec);
}

std::string expandFilePath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    const auto* context = static_cast<const ParseContext*>(user);
    if (!context->limits->allowExternalFiles) {
        if (err) *err += "external file '" + path + "' is not allowed here";
        return false;
    }
    try {
        *out = readFileBytes(path, context->limits->maxFileBytes);
        return true;
    } catch (const Error& e) {
        if (err) *err += e.what();
        return false;
    }
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "streak never writes glTF files";
    return false;
}

// tinygltf hands every image over at parse time. Uri images are copied, still encoded, and
// decoded only if a material uses them. For buffer-view images tinygltf passes a pointer it
// never checked against the buffer, so those bytes are not touched here (see decodeImage).
bool keepEncodedImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int, const unsigned char* bytes,
                      int size, void* user) {
    auto* context = static_cast<ParseContext*>(user);
    if (index < 0) return false;
    if (std::size_t(index) >= context->encodedImages->size()) context->encodedImages->resize(std::size_t(index) + 1);
    if (image->bufferView < 0 && bytes != nullptr && size > 0)
        (*context->encodedImages)[std::size_t(index)].assign(bytes, bytes + size);
    return true;
}

bool startsWith(std::span<const std::uint8_t> bytes, std::span<const std::uint8_t> magic) {
    return bytes.size() >= magic.size() && std::equal(magic.begin(), magic.end(), bytes.begin());
}

// tinygltf copies "extras" and "extensions" values recursively, so a deeply nested file would
// overflow the stack. glTF itself needs a handful of levels.
constexpr int kMaxJsonDepth = 128;

void checkJsonDepth(std::span<const std::uint8_t> json) {
    int depth = 0;
    bool isInString = false, isEscaped = false;
    for (const std::uint8_t c : json) {
        if (isInString) {
            if (isEscaped) isEscaped = false;
            else if (c == '\\') isEscaped = true;
            else if (c == '"') isInString = false;
        } else if (c == '"') {
            isInString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth) throw Error("JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

// The JSON of a .glb: its first chunk, as far as the bytes go (tinygltf checks the rest).
std::span<const std::uint8_t> glbJsonChunk(std::span<const std::uint8_t> bytes) {
    if (bytes.size() < 20) return {};
    const std::uint32_t length = std::uint32_t(bytes[12]) | std::uint32_t(bytes[13]) << 8 | std::uint32_t(bytes[14]) << 16 |
                                 std::uint32_t(bytes[15]) << 24;
    return bytes.subspan(20, std::min<std::size_t>(length, bytes.size() - 20));
}

}  // namespace

std::vector<std::uint8_t> readFileBytes(const std::string& path, std::uint64_t maxBytes) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw Error("cannot read '" + path + "': not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw Error("cannot read '" + path + "': " + ec.message());
    if (size > maxBytes) throw Error("'" + path + "' is larger than " + std::to_string(maxBytes) + " bytes");
    std::vector<std::uint8_t> bytes(size);
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)) || in.gcount() != std::streamsize(size))
        throw Error("cannot read '" + path + "'");
    return bytes;
}

Document parseDocument(std::span<const std::uint8_t> bytes, const std::string& baseDir, const DocumentLimits& limits) {
    if (bytes.size() > limits.maxFileBytes || bytes.size() > UINT_MAX)
        throw Error("larger than " + std::to_string(std::min<std::uint64_t>(limits.maxFileBytes, UINT_MAX)) + " bytes");
    Document document;
    ParseContext context{&limits, &document.encodedImages};
    tinygltf::TinyGLTF parser;
    parser.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &context});
    parser.SetImageLoader(&keepEncodedImage, &context);
    std::string err, warn;
    bool ok = false;
    constexpr std::array<std::uint8_t, 4> kGlbMagic{'g', 'l', 'T', 'F'};
    const bool isGlb = startsWith(bytes, kGlbMagic);
    checkJsonDepth(isGlb ? glbJsonChunk(bytes) : bytes);
    try {
        if (isGlb)
            ok = parser.LoadBinaryFromMemory(&document.model, &err, &warn, bytes.data(), unsigned(bytes.size()), baseDir);
        else
            ok = parser.LoadASCIIFromString(&document.model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                            unsigned(bytes.size()), baseDir);
    } catch (const std::bad_alloc&) {
        throw Error("out of memory while parsing");
    } catch (const std::exception& e) {
        throw Error(std::string("cannot parse: ") + oneLine(e.what()));
    }
    if (!ok) throw Error("cannot parse: " + oneLine(err));
    for (const std::string& extension : document.model.extensionsRequired)
        if (!kSupportedRequiredExtensions.count(extension))
            throw Error("requires extension " + extension + ", which streak does not support");
    document.encodedImages.resize(document.model.images.size());
    return document;
}

DecodedImage decodeImage(const Document& document, int index, const DocumentLimits& limits) {
    const auto& images = document.model.images;
    if (index < 0 || std::size_t(index) >= images.size()) throw Error("image " + std::to_string(index) + " does not exist");
    const tinygltf::Image& image = images[std::size_t(index)];
    const std::string what = "image " + std::to_string(index) + (image.uri.empty() || image.uri.starts_with("data:") ? "" : " '" + image.uri + "'");
    std::span<const std::uint8_t> bytes;
    if (image.bufferView >= 0) bytes = AccessorReader(document.model, 0).bufferView(image.bufferView, what);
    else if (std::size_t(index) < document.encodedImages.size()) bytes = document.encodedImages[std::size_t(index)];
    if (bytes.empty()) throw Error(what + ": missing or could not be read");

    constexpr std::array<std::uint8_t, 8> kPngMagic{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    constexpr std::array<std::uint8_t, 3> kJpegMagic{0xff, 0xd8, 0xff};
    if (!startsWith(bytes, kPngMagic) && !startsWith(bytes, kJpegMagic)) throw Error(what + ": not a PNG or JPEG image");
    if (bytes.size() > std::size_t(INT_MAX)) throw Error(what + ": too large");
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels) || width <= 0 || height <= 0)
        throw Error(what + ": corrupt image (" + oneLine(stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")");
    if (std::uint64_t(width) * std::uint64_t(height) > limits.maxTexels)
        throw Error(what + ": " + std::to_string(width) + "x" + std::to_string(height) + " is over the limit of " +
                    std::to_string(limits.maxTexels) + " texels");
    int decodedWidth = 0, decodedHeight = 0;
    stbi_uc* pixels = stbi_load_from_memory(bytes.data(), int(bytes.size()), &decodedWidth, &decodedHeight, &channels, 4);
    if (!pixels) throw Error(what + ": corrupt image (" + oneLine(stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")");
    DecodedImage decoded;
    if (decodedWidth == width && decodedHeight == height) {
        decoded.width = width;
        decoded.height = height;
        decoded.rgba.assign(pixels, pixels + std::size_t(width) * std::size_t(height) * 4);
    }
    stbi_image_free(pixels);
    if (decoded.rgba.empty()) throw Error(what + ": corrupt image (its size changed while decoding)");
    return decoded;
}

std::string base64(std::span<const std::uint8_t> bytes) {
    return tinygltf::base64_encode(bytes.data(), static_cast<unsigned int>(bytes.size()));
}

}  // namespace streak::gltf
