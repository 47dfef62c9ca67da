// Images through the public API: files, comparison, heatmaps.

#include "api/api_internal.h"

#include "image/image_io.h"
#include "image/metrics.h"

namespace streak::api {

Image imageOf(const streak::Image& in) {
    Image out;
    out.width = in.width(), out.height = in.height();
    out.rgb.reserve(std::size_t(in.width()) * std::size_t(in.height()) * 3);
    for (const glm::vec3& p : in.pixels()) out.rgb.insert(out.rgb.end(), {p.x, p.y, p.z});
    return out;
}

streak::Image imageOf(const Image& in) {
    if (in.width <= 0 || in.height <= 0 || in.rgb.size() != std::size_t(in.width) * std::size_t(in.height) * 3)
        throw Error("image: rgb must be width x height x 3 floats");
    streak::Image out(in.width, in.height);
    for (std::size_t i = 0; i < out.pixels().size(); ++i) out.pixels()[i] = {in.rgb[3 * i], in.rgb[3 * i + 1], in.rgb[3 * i + 2]};
    return out;
}

void writeImage(const Image& image, const std::string& path) { streak::writeImage(imageOf(image), path); }
Image readImage(const std::string& path) { return imageOf(streak::readImage(path)); }
void checkImagePath(const std::string& path) { imageFormatFromPath(path); }

Comparison compare(const Image& a, const Image& b, float foregroundThreshold) {
    if (a.width != b.width || a.height != b.height) throw Error("compare: the images' sizes differ");
    if (!(foregroundThreshold >= 0.0f && foregroundThreshold < 1.0f)) throw Error("compare: the foreground threshold must be in [0, 1)");
    const streak::Image x = imageOf(a), y = imageOf(b);
    const ForegroundPsnr foreground = foregroundPsnr(x, y, foregroundThreshold);
    return {psnr(x, y), ssim(x, y), foreground.psnr, foreground.pixels};
}

Heatmap errorHeatmap(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) throw Error("heatmap: the images' sizes differ");
    Heatmap out;
    out.image = imageOf(streak::errorHeatmap(imageOf(a), imageOf(b), &out.maxError));
    return out;
}

}  // namespace streak::api
