#pragma once

// tinygltf is built once, in gltf_document.cpp, with these switches; every file that includes
// it goes through this header so that all see the same declarations. Images are decoded by
// streak (stb from libstb, on demand) and files are read through streak's own callbacks.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace streak::gltf {

// Where a document may read from and how much.
struct DocumentLimits {
    bool allowExternalFiles = true;             ///< resolve relative uris against the file's folder
    std::uint64_t maxFileBytes = 1ull << 31;    ///< the file itself and each external buffer or image
    std::size_t maxTexels = std::size_t(1) << 26;  ///< per decoded image (width * height)
};

// Document is a parsed glTF file: tinygltf's model, and the encoded (PNG/JPEG) bytes of each
// image that came from a uri. Images stored in buffer views are read from the model, after
// checking the view, only when decoded: tinygltf does not bound-check those views.
struct Document {
    tinygltf::Model model;
    std::vector<std::vector<std::uint8_t>> encodedImages;  ///< per image; empty if in a buffer view or unreadable
};

// Parses a .gltf (JSON) or .glb (binary, told apart by its magic) held in memory. External
// uris resolve against baseDir when the limits allow; data: uris always work. Every failure,
// tinygltf's or a required extension streak does not support, is an Error naming the
// problem (the caller adds the file name).
Document parseDocument(std::span<const std::uint8_t> bytes, const std::string& baseDir, const DocumentLimits& limits);

// Bytes as base64 (tinygltf's encoder), for data: uris.
std::string base64(std::span<const std::uint8_t> bytes);

// Reads a whole regular file of at most maxBytes; Error otherwise.
std::vector<std::uint8_t> readFileBytes(const std::string& path, std::uint64_t maxBytes);

struct DecodedImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  ///< 8-bit RGBA, top row first, as stored (sRGB for colour)
};

// Decodes image `index` (PNG or JPEG) to 8-bit RGBA. Error when it does not exist, could not
// be read, is not PNG or JPEG, is corrupt, or has more than limits.maxTexels texels.
DecodedImage decodeImage(const Document& document, int index, const DocumentLimits& limits);

}  // namespace streak::gltf
