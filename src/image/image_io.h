#pragma once

#include "image/deep_image.h"
#include "image/image.h"

#include <string>

namespace streak {

enum class ImageFormat { Png, Exr };

// The format a path's extension names (.png or .exr, any case); throws Error otherwise.
ImageFormat imageFormatFromPath(const std::string& path);

// Writes PNG as sRGB-encoded 8-bit RGB and EXR as linear 32-bit float RGB; an image with alpha
// as RGBA (PNG straight, alpha linear; EXR premultiplied, as each format wants). Throws Error naming
// the path when it cannot be written; a failed write leaves no file behind.
// (The file is written beside path under a temporary name, then renamed over it.)
void writeImage(const Image& image, const std::string& path);

// Reads PNG (8-bit sRGB, decoded to linear; its alpha, if any, premultiplied in) or EXR (linear
// float; A, if any, as alpha). Throws Error
// naming the path when it is missing, unreadable or of an unknown format.
Image readImage(const std::string& path);

// A deep image as a deep scanline EXR (R G B A Z ZBack, float), declared tidy, a region's data
// window inside its frame; and back. Throws Error naming the path, as the flat ones do.
void writeDeepImage(const DeepImage& image, const std::string& path);
DeepImage readDeepImage(const std::string& path);

}  // namespace streak
