#include "image/metrics.h"

#include "image/color.h"
#include "util/error.h"

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace streak {

namespace {

std::string sizeText(const Image& image) {
    return std::to_string(image.width()) + "x" + std::to_string(image.height());
}

void checkComparable(const Image& a, const Image& b, const char* metric, bool allowEmpty) {
    if (a.width() != b.width() || a.height() != b.height())
        throw Error(std::string(metric) + ": image sizes differ (" + sizeText(a) + " vs " + sizeText(b) + ")");
    if (!allowEmpty && a.empty()) throw Error(std::string(metric) + ": images are empty");
}

// Rec. 601 luma of the display-space (encoded, clamped) RGB.
std::vector<float> encodedLuma(const Image& image) {
    std::vector<float> luma;
    luma.reserve(image.pixels().size());
    for (const glm::vec3& p : image.pixels()) {
        const glm::vec3 e = linearToSrgb(p);
        luma.push_back(0.299f * e.x + 0.587f * e.y + 0.114f * e.z);
    }
    return luma;
}

constexpr int kRadius = 5;  // 11 taps

std::array<float, 2 * kRadius + 1> gaussianKernel() {
    constexpr double sigma = 1.5;
    std::array<double, 2 * kRadius + 1> weights{};
    double sum = 0.0;
    for (int i = -kRadius; i <= kRadius; ++i) sum += weights[i + kRadius] = std::exp(-i * i / (2.0 * sigma * sigma));
    std::array<float, 2 * kRadius + 1> kernel{};
    for (std::size_t i = 0; i < kernel.size(); ++i) kernel[i] = float(weights[i] / sum);
    return kernel;
}

// Separable Gaussian blur. Samples outside the image take the nearest edge value, so every
// pixel gets a full window and images smaller than the window still work.
std::vector<float> blur(const std::vector<float>& plane, int width, int height) {
    static const auto kernel = gaussianKernel();
    std::vector<float> rows(plane.size());
    for (int y = 0; y < height; ++y) {
        const float* in = plane.data() + std::size_t(y) * width;
        float* out = rows.data() + std::size_t(y) * width;
        for (int x = 0; x < width; ++x) {
            float sum = 0.0f;
            for (int k = -kRadius; k <= kRadius; ++k) sum += kernel[k + kRadius] * in[std::clamp(x + k, 0, width - 1)];
            out[x] = sum;
        }
    }
    std::vector<float> result(plane.size());
    for (int y = 0; y < height; ++y) {
        float* out = result.data() + std::size_t(y) * width;
        for (int k = -kRadius; k <= kRadius; ++k) {
            const float weight = kernel[k + kRadius];
            const float* in = rows.data() + std::size_t(std::clamp(y + k, 0, height - 1)) * width;
            for (int x = 0; x < width; ++x) out[x] += weight * in[x];
        }
    }
    return result;
}

// Colour stops in display space, evenly spaced: black, blue, red, yellow, white.
glm::vec3 heatColor(float t) {
    static const std::array<glm::vec3, 5> stops = {glm::vec3(0, 0, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0),
                                                   glm::vec3(1, 1, 0), glm::vec3(1, 1, 1)};
    const float s = std::clamp(t, 0.0f, 1.0f) * float(stops.size() - 1);
    const int i = std::min(int(s), int(stops.size()) - 2);
    const glm::vec3 display = glm::mix(stops[i], stops[i + 1], s - float(i));
    // Image holds linear light; decode so a PNG of the heatmap shows the ramp as designed.
    return {srgbToLinear(display.x), srgbToLinear(display.y), srgbToLinear(display.z)};
}

// PSNR of the encoded RGB over every pixel, or (given a threshold) over the pixels where either
// image has an encoded channel above it.
ForegroundPsnr squaredErrorPsnr(const Image& a, const Image& b, std::optional<float> threshold) {
    double sumSquared = 0.0;
    ForegroundPsnr result;
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        const glm::vec3 ea = linearToSrgb(a.pixels()[i]), eb = linearToSrgb(b.pixels()[i]);
        if (threshold && !(std::max({ea.x, ea.y, ea.z, eb.x, eb.y, eb.z}) > *threshold)) continue;
        const glm::vec3 d = ea - eb;
        sumSquared += double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
        ++result.pixels;
    }
    if (sumSquared == 0.0) {
        result.psnr = std::numeric_limits<double>::infinity();
        return result;
    }
    const double mse = sumSquared / (3.0 * double(result.pixels));
    result.psnr = 10.0 * std::log10(1.0 / mse);
    return result;
}

}  // namespace

double psnr(const Image& a, const Image& b) {
    checkComparable(a, b, "psnr", false);
    return squaredErrorPsnr(a, b, std::nullopt).psnr;
}

ForegroundPsnr foregroundPsnr(const Image& a, const Image& b, float threshold) {
    checkComparable(a, b, "foregroundPsnr", false);
    return squaredErrorPsnr(a, b, threshold);
}

double ssim(const Image& a, const Image& b) {
    checkComparable(a, b, "ssim", false);
    constexpr double c1 = 0.01 * 0.01;  // (K1 L)^2, L = 1
    constexpr double c2 = 0.03 * 0.03;  // (K2 L)^2
    const int width = a.width(), height = a.height();

    const std::vector<float> x = encodedLuma(a);
    const std::vector<float> y = encodedLuma(b);
    std::vector<float> xx(x.size()), yy(x.size()), xy(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        xx[i] = x[i] * x[i];
        yy[i] = y[i] * y[i];
        xy[i] = x[i] * y[i];
    }
    const std::vector<float> muX = blur(x, width, height);
    const std::vector<float> muY = blur(y, width, height);
    const std::vector<float> meanXX = blur(xx, width, height);
    const std::vector<float> meanYY = blur(yy, width, height);
    const std::vector<float> meanXY = blur(xy, width, height);

    double sum = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double mx = muX[i], my = muY[i];
        const double varX = meanXX[i] - mx * mx;
        const double varY = meanYY[i] - my * my;
        const double covXY = meanXY[i] - mx * my;
        sum += ((2.0 * mx * my + c1) * (2.0 * covXY + c2)) / ((mx * mx + my * my + c1) * (varX + varY + c2));
    }
    return sum / double(x.size());
}

Image errorHeatmap(const Image& a, const Image& b, double* maxError) {
    checkComparable(a, b, "errorHeatmap", true);
    std::vector<float> error(a.pixels().size());
    float largest = 0.0f;
    for (std::size_t i = 0; i < error.size(); ++i) {
        const glm::vec3 d = glm::abs(linearToSrgb(a.pixels()[i]) - linearToSrgb(b.pixels()[i]));
        error[i] = (d.x + d.y + d.z) / 3.0f;
        largest = std::max(largest, error[i]);
    }
    if (maxError) *maxError = largest;

    Image heatmap(a.width(), a.height());
    if (largest > 0.0f) {
        auto pixels = heatmap.pixels();
        for (std::size_t i = 0; i < error.size(); ++i) pixels[i] = heatColor(error[i] / largest);
    }
    return heatmap;
}

}  // namespace streak
