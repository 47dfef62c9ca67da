// Images through the public API: files, comparison, heatmaps.

#include "api/api_internal.h"

#include "image/cryptomatte.h"
#include "image/image_io.h"
#include "image/metrics.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace streak::api {

Image imageOf(const streak::Image& in) {
    Image out;
    out.width = in.width(), out.height = in.height();
    out.rgb.reserve(std::size_t(in.width()) * std::size_t(in.height()) * 3);
    for (const glm::vec3& p : in.pixels()) out.rgb.insert(out.rgb.end(), {p.x, p.y, p.z});
    out.alpha.assign(in.alpha().begin(), in.alpha().end());
    for (const ImageChannel& c : in.channels()) out.channels.push_back({c.name, c.values});
    out.metadata = in.metadata();
    if (const std::optional<FramePlacement>& p = in.placement()) out.x = p->x, out.y = p->y, out.frameWidth = p->frameWidth, out.frameHeight = p->frameHeight;
    return out;
}

streak::Image imageOf(const Image& in) {
    if (in.width <= 0 || in.height <= 0 || in.rgb.size() != std::size_t(in.width) * std::size_t(in.height) * 3)
        throw Error("image: rgb must be width x height x 3 floats");
    streak::Image out(in.width, in.height);
    for (std::size_t i = 0; i < out.pixels().size(); ++i) out.pixels()[i] = {in.rgb[3 * i], in.rgb[3 * i + 1], in.rgb[3 * i + 2]};
    if (in.hasAlpha() && in.alpha.size() != out.pixels().size()) throw Error("image: alpha must be width x height floats");
    out.setAlpha(in.alpha);
    for (const Image::Channel& c : in.channels) {
        if (c.values.size() != out.pixels().size()) throw Error("image: channel " + c.name + " must be width x height floats");
        out.addChannel(c.name, c.values);
    }
    for (const auto& [key, value] : in.metadata) out.setMetadata(key, value);
    if (in.isRegion()) out.place({in.x, in.y, in.frameWidth, in.frameHeight});
    return out;
}

DeepImage deepImageOf(const streak::DeepImage& in) {
    DeepImage out;
    out.width = in.width(), out.height = in.height();
    const std::span<const std::uint64_t> offsets = in.offsets();
    out.counts.reserve(offsets.size() - 1);
    for (std::size_t i = 0; i + 1 < offsets.size(); ++i) out.counts.push_back(std::uint32_t(offsets[i + 1] - offsets[i]));
    out.samples.reserve(in.numSamples());
    for (const DeepSample& s : in.allSamples()) out.samples.push_back({s.z, s.zBack, s.color.x, s.color.y, s.color.z, s.alpha});
    if (const std::optional<FramePlacement>& p = in.placement()) out.x = p->x, out.y = p->y, out.frameWidth = p->frameWidth, out.frameHeight = p->frameHeight;
    return out;
}

namespace {

streak::DeepImage deepImageOf(const DeepImage& in) {
    if (in.width <= 0 || in.height <= 0 || in.counts.size() != std::size_t(in.width) * std::size_t(in.height))
        throw Error("deep image: counts must be width x height");
    std::vector<std::vector<DeepSample>> perPixel(in.counts.size());
    std::size_t next = 0;
    for (std::size_t i = 0; i < in.counts.size(); ++i) {
        if (in.counts[i] > in.samples.size() - next) throw Error("deep image: the counts add up to more samples than it holds");
        for (std::uint32_t k = 0; k < in.counts[i]; ++k, ++next) {
            const DeepImage::Sample& s = in.samples[next];
            // The file says it is tidy: sorted by Z, none overlapping another, alphas in [0, 1].
            const bool isApart = k == 0 || (in.samples[next - 1].zBack <= s.z && in.samples[next - 1].z < s.z);
            if (!(std::isfinite(s.z) && std::isfinite(s.zBack) && s.z <= s.zBack && isApart && s.a >= 0.0f && s.a <= 1.0f))
                throw Error("deep image: pixel " + std::to_string(i % std::size_t(in.width)) + "," + std::to_string(i / std::size_t(in.width)) +
                            " is not tidy (samples sorted by Z, Z <= ZBack, none overlapping, alpha in [0, 1], finite)");
            perPixel[i].push_back({s.z, s.zBack, glm::vec3(s.r, s.g, s.b), s.a});
        }
    }
    if (next != in.samples.size()) throw Error("deep image: the counts add up to fewer samples than it holds");
    streak::DeepImage out(in.width, in.height);
    out.assign(perPixel);
    if (in.isRegion()) {
        if (in.x < 0 || in.y < 0 || std::int64_t(in.x) + in.width > in.frameWidth || std::int64_t(in.y) + in.height > in.frameHeight)
            throw Error("deep image: its region does not lie inside its frame");
        out.place({in.x, in.y, in.frameWidth, in.frameHeight});
    }
    return out;
}

}  // namespace

void writeDeepImage(const DeepImage& image, const std::string& path) { streak::writeDeepImage(deepImageOf(image), path); }
DeepImage readDeepImage(const std::string& path) { return deepImageOf(streak::readDeepImage(path)); }

Image stitch(const std::vector<Image>& regions) {
    if (regions.empty()) throw Error("stitch: no regions");
    // A whole frame is the region that covers it (a --region of the whole image reads back so).
    const auto frameWidth = [](const Image& r) { return r.isRegion() ? r.frameWidth : r.width; };
    const auto frameHeight = [](const Image& r) { return r.isRegion() ? r.frameHeight : r.height; };
    const auto placed = [](const Image& r) { return std::to_string(r.width) + "x" + std::to_string(r.height) + " at " + std::to_string(r.x) + "," + std::to_string(r.y); };
    const int width = frameWidth(regions.front()), height = frameHeight(regions.front());
    if (width > kMaxImageSize || height > kMaxImageSize)
        throw Error("stitch: a " + std::to_string(width) + "x" + std::to_string(height) + " frame is larger than streak renders (" + std::to_string(kMaxImageSize) + " pixels a side)");
    std::vector<streak::Image> in;
    std::uint64_t area = 0;
    for (const Image& r : regions) {
        std::vector<std::string> names, firstNames;
        for (const Image::Channel& c : r.channels) names.push_back(c.name);
        for (const Image::Channel& c : regions.front().channels) firstNames.push_back(c.name);
        if (names != firstNames)
            throw Error("stitch: region " + std::to_string(&r - regions.data() + 1) + " (" + placed(r) + ") has other passes than region 1");
        if (r.hasAlpha() != regions.front().hasAlpha())
            throw Error("stitch: region " + std::to_string(&r - regions.data() + 1) + " (" + placed(r) + ") " + (r.hasAlpha() ? "has" : "has no") +
                        " alpha and region 1 " + (r.hasAlpha() ? "has none" : "has"));
        if (frameWidth(r) != width || frameHeight(r) != height)
            throw Error("stitch: the regions belong to frames of different sizes (" + std::to_string(width) + "x" + std::to_string(height) + " and " +
                        std::to_string(frameWidth(r)) + "x" + std::to_string(frameHeight(r)) + ")");
        in.push_back(imageOf(r));  // checks the size and that it lies in its frame
        area += std::uint64_t(r.width) * std::uint64_t(r.height);
    }
    const std::uint64_t frameArea = std::uint64_t(width) * std::uint64_t(height);
    streak::Image frame(width, height);
    if (regions.front().hasAlpha()) frame.setUncovered();
    std::vector<std::vector<float>> passes(regions.front().channels.size());
    std::vector<int> owner(area == frameArea ? frameArea : 0, -1);
    for (std::size_t k = 0; k < in.size() && area == frameArea; ++k) {
        const FramePlacement p = in[k].placement().value_or(FramePlacement{0, 0, width, height});
        for (int y = 0; y < in[k].height(); ++y)
            for (int x = 0; x < in[k].width(); ++x) {
                int& o = owner[std::size_t(p.y + y) * std::size_t(width) + std::size_t(p.x + x)];
                if (o >= 0)
                    throw Error("stitch: regions " + std::to_string(o + 1) + " (" + placed(regions[std::size_t(o)]) + ") and " + std::to_string(k + 1) + " (" +
                                placed(regions[k]) + ") overlap at pixel " + std::to_string(p.x + x) + "," + std::to_string(p.y + y));
                o = int(k);
                frame.at(p.x + x, p.y + y) = in[k].at(x, y);
                const std::size_t to = std::size_t(p.y + y) * std::size_t(width) + std::size_t(p.x + x);
                if (frame.hasAlpha()) frame.alpha()[to] = in[k].alphaAt(x, y);
                for (std::size_t c = 0; c < passes.size(); ++c) {
                    if (passes[c].empty()) passes[c].assign(std::size_t(frameArea), 0.0f);
                    passes[c][to] = in[k].channels()[c].values[std::size_t(y) * std::size_t(in[k].width()) + std::size_t(x)];
                }
            }
    }
    // Regions that cover each pixel once have the frame's area; more overlap, fewer leave a gap.
    if (area != frameArea)
        throw Error("stitch: the regions' " + std::to_string(area) + " pixels " + (area > frameArea ? "overlap in" : "do not cover") + " the " +
                    std::to_string(width) + "x" + std::to_string(height) + " frame (" + std::to_string(frameArea) + " pixels)");
    for (std::size_t c = 0; c < passes.size(); ++c) frame.addChannel(regions.front().channels[c].name, std::move(passes[c]));
    for (const auto& [key, value] : regions.front().metadata) frame.setMetadata(key, value);
    return imageOf(frame);
}

std::string cryptomatteKey(const std::string& layerName) { return streak::cryptomatteKey(layerName); }

std::vector<float> cryptomatteMatte(const Image& image, const std::string& type, const std::string& name) {
    const float id = cryptomatteId(name);
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    std::vector<float> matte(pixels, 0.0f);
    // Lower-case channels as the specification and Blender write them; upper case read too.
    auto find = [&](int rank, bool isCoverage) {
        std::string name = cryptomatteChannel(type, rank, isCoverage);
        if (const Image::Channel* c = image.channel(name)) return c;
        name.back() = char(std::toupper(static_cast<unsigned char>(name.back())));
        return image.channel(name);
    };
    int ranks = 0;
    for (;; ++ranks) {
        const Image::Channel* ids = find(ranks, false);
        const Image::Channel* coverage = find(ranks, true);
        if (!ids || !coverage) break;
        for (std::size_t i = 0; i < pixels; ++i)
            if (ids->values[i] == id) matte[i] += coverage->values[i];
    }
    if (ranks == 0) throw Error("cryptomatte: the image has no " + type + " layers (" + cryptomatteChannel(type, 0, false) + ", ...)");
    return matte;
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

namespace {

// The Cryptomatte types of an image: {short type name ("CryptoObject"): (full type name, {name: id})}.
std::map<std::string, std::pair<std::string, std::map<std::string, float>>> cryptomatteTypes(const Image& image) {
    std::map<std::string, std::pair<std::string, std::map<std::string, float>>> types;
    for (const auto& [key, value] : image.metadata) {
        const std::string suffix = "/name";
        if (key.rfind("cryptomatte/", 0) != 0 || key.size() < suffix.size() || key.compare(key.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const auto manifest = image.metadata.find(key.substr(0, key.size() - suffix.size()) + "/manifest");
        std::map<std::string, float> names;
        if (manifest != image.metadata.end())
            for (const std::string& name : cryptomatteManifestNames(manifest->second)) names[name] = cryptomatteId(name);
        types[value.substr(value.rfind('.') + 1)] = {value, names};
    }
    return types;
}

void addDifference(std::vector<PassComparison>& out, const std::string& pass, const std::vector<float>& a, const std::vector<float>& b,
                   bool skipEmpty) {
    PassComparison c;
    c.pass = pass;
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (skipEmpty && !(a[i] < 1e9f && b[i] < 1e9f)) continue;
        const double d = double(a[i]) - double(b[i]);
        sum += d * d, c.maxError = std::max(c.maxError, std::abs(d)), ++c.pixels;
    }
    c.rms = c.pixels ? std::sqrt(sum / double(c.pixels)) : 0.0;
    out.push_back(c);
}

}  // namespace

std::vector<PassComparison> comparePasses(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) throw Error("compare: the images' sizes differ");
    std::vector<PassComparison> out;
    if (a.hasAlpha() && b.hasAlpha()) addDifference(out, "alpha", a.alpha, b.alpha, false);
    const auto typesA = cryptomatteTypes(a), typesB = cryptomatteTypes(b);
    auto isCryptomatte = [&](const std::string& channel) {
        for (const auto& [shortName, type] : typesA)
            if (channel.rfind(type.first, 0) == 0) return true;
        return false;
    };
    for (const Image::Channel& c : a.channels)
        if (const Image::Channel* other = b.channel(c.name); other && !isCryptomatte(c.name)) addDifference(out, c.name, c.values, other->values, true);
    for (const auto& [shortName, type] : typesA) {
        const auto other = typesB.find(shortName);
        if (other == typesB.end()) continue;
        try {
            for (const auto& [name, id] : type.second)
                if (other->second.second.count(name))
                    addDifference(out, shortName + " " + name, cryptomatteMatte(a, type.first, name), cryptomatteMatte(b, other->second.first, name), false);
        } catch (const Error&) {
            // Metadata naming a type whose layers are missing: nothing of it to compare.
        }
    }
    return out;
}

Heatmap errorHeatmap(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) throw Error("heatmap: the images' sizes differ");
    Heatmap out;
    out.image = imageOf(streak::errorHeatmap(imageOf(a), imageOf(b), &out.maxError));
    return out;
}

}  // namespace streak::api
