#pragma once

// Images in and out of streak: linear-light RGB float, PNG/EXR files, and how two images differ.

#include "streak/error.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace streak::api {

// A linear-light RGB float image: width x height x 3 floats, row-major, top row first. With
// alpha (a render with RenderSettings::transparent, an EXR with A, a PNG with alpha): one value
// per pixel, each pixel's exact coverage, and rgb premultiplied by it (what shows over black).
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;
    std::vector<float> alpha;  ///< width x height, or empty: opaque
    bool hasAlpha() const { return !alpha.empty(); }
    // Passes (RenderSettings::passes; an EXR's other channels): width x height floats each, by
    // channel name ("Z", "CryptoObject00.r", ...), and the string attributes that describe them
    // (Cryptomatte's "cryptomatte/<key>/manifest", ...). Written to EXR only.
    struct Channel {
        std::string name;
        std::vector<float> values;
    };
    std::vector<Channel> channels;
    std::map<std::string, std::string> metadata;
    const Channel* channel(const std::string& name) const {
        for (const Channel& c : channels)
            if (c.name == name) return &c;
        return nullptr;
    }
    // A region of a larger frame (RenderSettings::region; an EXR whose data window lies inside
    // its display window): the frame's size, and the pixel of it where the image's top-left
    // pixel lies. frameWidth 0: the image is a whole frame.
    int x = 0, y = 0, frameWidth = 0, frameHeight = 0;
    bool isRegion() const { return frameWidth > 0; }
    float at(int x, int y, int channel) const { return rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3 + std::size_t(channel)]; }
};

// A deep image (RenderSettings::deep): per pixel, its visible surface layers front to back as
// deep samples, each lying from view depth z to zBack, with alpha a and colour premultiplied
// by it. Tidy (sorted, none overlapping), so compositing a pixel's samples front to back, each
// over what lies behind (OpenEXR's "Interpreting Deep Pixels"), gives the render's RGBA.
struct DeepImage {
    struct Sample {
        float z = 0.0f, zBack = 0.0f, r = 0.0f, g = 0.0f, b = 0.0f, a = 0.0f;
    };
    int width = 0, height = 0;
    std::vector<std::uint32_t> counts;  ///< width x height: each pixel's number of samples
    std::vector<Sample> samples;        ///< pixel by pixel (row-major, top row first), front to back
    // Placed in a frame as Image is (a region render).
    int x = 0, y = 0, frameWidth = 0, frameHeight = 0;
    bool isRegion() const { return frameWidth > 0; }
};
// A deep scanline EXR (R G B A Z ZBack, 32-bit float, ZIPS, deepImageState tidy: what Nuke's
// DeepRead takes); a failed write leaves nothing. Throws Error unless the path ends in .exr.
void writeDeepImage(const DeepImage& image, const std::string& path);
DeepImage readDeepImage(const std::string& path);

// PNG (sRGB 8-bit) or EXR (linear float) by the extension; a failed write leaves nothing. With
// alpha, RGBA: PNG's colour straight (divided by alpha), EXR's premultiplied.
void writeImage(const Image& image, const std::string& path);
Image readImage(const std::string& path);
// Joins regions of one frame (each placed in it: isRegion; a whole frame is the region covering
// it) into the whole frame, each pixel from the one region that holds it. Throws Error unless
// every region lies in a frame of one size and together they cover each of its pixels once,
// and all have alpha or none does.
Image stitch(const std::vector<Image>& regions);

// A Cryptomatte matte (Cryptomatte 1.1): per pixel, the coverage of the object or material
// `name` in the image's Cryptomatte type `type` ("CryptoObject", "CryptoMaterial"), summed
// over the ranks whose ID is the name's. Throws Error when the image has no such layers.
std::vector<float> cryptomatteMatte(const Image& image, const std::string& type, const std::string& name);
// The metadata key of a Cryptomatte layer (the first seven hex digits of its name's
// MurmurHash3): "cryptomatte/<key>/name" and the rest. A client renaming layers
// ("ViewLayer.CryptoObject", as Blender names its own) keys them anew with it.
std::string cryptomatteKey(const std::string& layerName);

// Throws Error unless the path ends in an image extension writeImage knows (.png, .exr), so a
// caller can refuse a bad output before a long render.
void checkImagePath(const std::string& path);

// How two images of one size differ, in display space (sRGB-encoded, clamped), as `streak
// compare` prints it: PSNR (dB; infinite when equal), SSIM, and the PSNR over the foreground,
// the pixels where a channel of either image is above the threshold.
struct Comparison {
    double psnr = 0.0;
    double ssim = 0.0;
    double foregroundPsnr = 0.0;
    std::size_t foregroundPixels = 0;
};
Comparison compare(const Image& a, const Image& b, float foregroundThreshold = 2.0f / 255.0f);

// How two images' passes differ, pass by pass, for the passes both have: alpha, each named
// channel but Cryptomatte's (over the pixels where both values are below 1e9, so depth's
// "nothing shows" is left out), and each name of each Cryptomatte type (its matte; types matched
// by the part of their name after the last '.', so Blender's "ViewLayer.CryptoObject" meets
// "CryptoObject"). RMS and largest absolute difference, and over how many pixels.
struct PassComparison {
    std::string pass;  ///< "alpha", "Z", "CryptoObject Cesium_Man", ...
    double rms = 0.0;
    double maxError = 0.0;
    std::size_t pixels = 0;
};
std::vector<PassComparison> comparePasses(const Image& a, const Image& b);

// A false-colour image of the per-pixel error (white: the largest, maxError).
struct Heatmap {
    Image image;
    double maxError = 0.0;
};
Heatmap errorHeatmap(const Image& a, const Image& b);

}  // namespace streak::api
