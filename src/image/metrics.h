#pragma once

#include "image/image.h"

#include <cstddef>

namespace streak {

// Metrics compare what a person sees: both images are sRGB-encoded and clamped to [0,1] first
// (the values a PNG holds), so a PNG and the EXR it came from measure alike. Sizes must match
// (Error otherwise).

// Peak signal-to-noise ratio over the R, G and B channels, peak 1, in dB; +infinity when the
// images are identical.
double psnr(const Image& a, const Image& b);

// PSNR over the foreground only: the pixels where either image has a channel above
// `threshold` once encoded (2/255 by default: above 2 in sRGB 8-bit). A mostly black frame
// around a small object would otherwise inflate PSNR by its count of identical black pixels.
// `pixels` is how many pixels were counted; with none the PSNR is +infinity (nothing differs).
struct ForegroundPsnr {
    double psnr = 0.0;
    std::size_t pixels = 0;
};
ForegroundPsnr foregroundPsnr(const Image& a, const Image& b, float threshold = 2.0f / 255.0f);

// Mean structural similarity (Wang et al. 2004) of the luma (Rec. 601 weights of the encoded
// RGB), 11x11 Gaussian window with sigma 1.5, K1 = 0.01, K2 = 0.03; 1 for identical images.
// Windows reaching past the border take the nearest edge pixel, so every pixel counts and
// images smaller than the window work.
double ssim(const Image& a, const Image& b);

// A false-colour image of the per-pixel error: mean absolute difference of the encoded RGB,
// divided by the largest such difference (black = equal, through blue and red to yellow/white
// = the largest). maxError receives that largest difference, if given.
Image errorHeatmap(const Image& a, const Image& b, double* maxError = nullptr);

}  // namespace streak
