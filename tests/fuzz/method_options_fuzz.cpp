// libFuzzer target: a method's options as the command line gives them (`-m METHOD --option
// KEY=VALUE ...`, fuzz/fuzz_inputs.h has the input format), through the registry:
// createRenderer(method, options) must return a renderer or throw streak::Error. Every method
// is created, the GL ones too (their factories read options and touch no GL); the renderer of a
// CPU method then renders a tiny built-in scene (8 x 8 pixels unless the input sets a size),
// which must give an image of that size with finite pixels or throw Error. Anything else (a
// crash, a sanitizer report, another exception, a leak, a hang, a huge allocation) is a finding.
//
// Only the render is bounded, to a few milliseconds under the sanitizers: at most
// fuzz::kMaxImageSamples pixel samples (width x height x aa^2), and for a method that takes
// `samples` (accumulation's passes, stochastic's times a pixel: up to 1 << 20, 256 and 8 by
// default) only when the input sets it to at most kMaxRenderSamples; else it is created only.
// Likewise higher-order's `check-visibility` (up to 20000 brute-force checks over every
// triangle of a tile) renders only up to kMaxVisibilityChecks.

#include "fuzz/fuzz_inputs.h"
#include "methods/registry.h"
#include "scene/scene_loader.h"
#include "util/error.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>

namespace {

using namespace streak;

constexpr int kMaxRenderSamples = 4;
constexpr int kMaxVisibilityChecks = 64;

// One thread: renders are tiny, and a report's stack is then the render's own.
const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);

// The scenes of fuzz::kRenderScenes, validated, and the methods that take `samples`; found
// before the first input, where a spec that no longer loads stops the run (an uncaught Error)
// instead of skipping every render.
std::map<std::string_view, Scene> renderScenes;
std::set<std::string, std::less<>> methodsWithSamples;

struct Render {
    RenderSettings settings{.width = 8, .height = 8};
    std::string_view scene = fuzz::kRenderScenes[0].name;
};

// Applies one @SETTING line to `render`; false for a value out of range or an unknown setting.
bool applySetting(std::string_view line, Render& render) {
    const auto after = [&](std::string_view prefix) -> std::optional<std::string_view> {
        if (!line.starts_with(prefix)) return std::nullopt;
        return line.substr(prefix.size());
    };
    if (line == fuzz::kGrid) return render.settings.isGridPattern = true;
    if (line == fuzz::kUnlit) return render.settings.shading = ShadingMode::Unlit, true;
    if (const auto v = after(fuzz::kAa)) {
        const auto aa = fuzz::parseInt(*v);
        render.settings.aa = aa.value_or(0);
        return aa && *aa >= 1 && *aa <= fuzz::kMaxAa;
    }
    if (const auto v = after(fuzz::kSize)) {
        const std::size_t x = v->find('x');
        const auto w = fuzz::parseInt(v->substr(0, x)), h = x == std::string_view::npos ? w : fuzz::parseInt(v->substr(x + 1));
        render.settings.width = w.value_or(0), render.settings.height = h.value_or(0);
        return w && h && *w >= 1 && *h >= 1 && *w <= fuzz::kMaxImageSamples && *h <= fuzz::kMaxImageSamples;
    }
    if (const auto v = after(fuzz::kSeed)) {
        const auto seed = fuzz::parseInt(*v);
        render.settings.seed = std::uint64_t(seed.value_or(0));
        return seed.has_value();
    }
    if (const auto v = after(fuzz::kScene)) {
        for (const fuzz::RenderScene& s : fuzz::kRenderScenes)
            if (s.name == *v) return render.scene = s.name, true;
    }
    return false;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    for (const fuzz::RenderScene& s : fuzz::kRenderScenes) {
        Scene scene = loadScene(std::string(s.spec));
        validateScene(scene);
        renderScenes.emplace(s.name, std::move(scene));
    }
    for (const MethodInfo& method : registeredMethods()) {
        OptionMap options;
        options.set("samples", "1");
        try {
            createRenderer(method.name, options);
            methodsWithSamples.emplace(method.name);
        } catch (const Error&) {
        }
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::string_view first = text.substr(0, text.find('\n'));
    text.remove_prefix(std::min(text.size(), first.size() + 1));
    const std::size_t q = first.find('?');
    const std::string_view method = first.substr(0, q);
    Render render;
    std::optional<int> samples, visibilityChecks;
    std::unique_ptr<Renderer> renderer;
    try {
        OptionMap options = q == std::string_view::npos ? OptionMap() : OptionMap::parseQuery(first.substr(q + 1), "options");
        // Read from a copy: a getter marks its key as taken, so the method would accept it.
        if (options.has("samples")) samples = fuzz::parseInt(OptionMap(options).getString("samples", ""));
        // An unparsed count counts as over the bound.
        if (options.has("check-visibility"))
            visibilityChecks = fuzz::parseInt(OptionMap(options).getString("check-visibility", "")).value_or(kMaxVisibilityChecks + 1);
        while (!text.empty()) {
            const std::string_view line = text.substr(0, text.find('\n'));
            text.remove_prefix(std::min(text.size(), line.size() + 1));
            if (line.starts_with('@')) {
                if (!applySetting(line, render)) return -1;  // not a render this target makes
                continue;
            }
            // apps/streak/main.cpp: "--option must be KEY=VALUE" where there is no key.
            const std::size_t equals = line.find('=');
            if (equals == std::string_view::npos || equals == 0) return 0;
            options.set(std::string(line.substr(0, equals)), std::string(line.substr(equals + 1)));
            if (line.substr(0, equals) == "samples") samples = fuzz::parseInt(line.substr(equals + 1));
            if (line.substr(0, equals) == "check-visibility")
                visibilityChecks = fuzz::parseInt(line.substr(equals + 1)).value_or(kMaxVisibilityChecks + 1);
        }
        const RenderSettings& r = render.settings;
        if (r.width * r.height * r.aa * r.aa > fuzz::kMaxImageSamples) return -1;
        renderer = createRenderer(method, std::move(options));
    } catch (const Error&) {
        return 0;
    }
    if (!renderer) fuzz::finding("createRenderer returned no renderer for " + std::string(method));
    if (method.ends_with("-gl")) return 0;
    if (methodsWithSamples.contains(method) && !(samples && *samples <= kMaxRenderSamples)) return 0;
    if (visibilityChecks && *visibilityChecks > kMaxVisibilityChecks) return 0;
    Image image;
    try {
        RenderStats stats;
        RenderContext context{stats, nullptr};
        image = renderer->render(renderScenes.at(render.scene), render.settings, context);
    } catch (const Error&) {
        return 0;
    }
    if (image.width() != render.settings.width || image.height() != render.settings.height)
        fuzz::finding("the image of " + std::string(method) + " is not the size asked for");
    for (const glm::vec3& p : image.pixels())
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            fuzz::finding("a pixel of " + std::string(method) + " is not finite");
    return 0;
}
