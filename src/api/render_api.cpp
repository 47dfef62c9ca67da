// Rendering through the public API: the registry's methods kept as Renderers, and the figures
// of each render as the command line's --stats reports them.

#include "api/api_internal.h"

#include "methods/registry.h"
#include "raster/clip.h"
#include "scene/shutter.h"

#include <glm/trigonometric.hpp>
#include <tbb/global_control.h>

#include <array>
#include <cstdio>
#include <initializer_list>

namespace streak::api {

static_assert(kMaxImageSize == raster::kMaxImageSize, "the public size limit is the rasterizer's");
static_assert(kDefaultMemoryBudgetMB == int(streak::kDefaultMemoryBudgetMB), "the public default budget is the methods'");

namespace {

// The camera the scene is rendered through, in the scene's world (glTF: +y up): each pose's
// position and worldFromCamera rotation (w,x,y,z; the camera looks down its -z with +y up), the
// vertical field of view and the near plane.
void reportCamera(const streak::Camera& camera, RenderStats& stats) {
    for (const auto& [name, pose] : {std::pair{"open", &camera.open}, std::pair{"close", &camera.close}}) {
        const glm::vec3& p = pose->position;
        const glm::quat& q = pose->worldFromCamera;
        stats.setInfo(std::string("camera_") + name + "_position", numberList({p.x, p.y, p.z}));
        stats.setInfo(std::string("camera_") + name + "_rotation_wxyz", numberList({q.w, q.x, q.y, q.z}));
    }
    stats.setInfo("camera_vertical_fov_deg", numberList({glm::degrees(camera.verticalFov)}));
    stats.setInfo("camera_znear", numberList({camera.zNear}));
}

// The caller's progress and cancel callbacks. A cancel is thrown from the reporting thread (the
// caller's), which unwinds the method's parallel loops as any exception does. A render that is
// several method renders (the beauty, then the albedo and normal passes) reports each as its
// stage of the whole.
class CallbackProgress final : public ProgressReporter {
public:
    CallbackProgress(const std::function<void(double)>& progress, const std::function<bool()>& cancel) : m_progress(progress), m_cancel(cancel) {}
    void update(double fraction) override {
        checkCancel();
        if (m_progress) m_progress((m_stage + fraction) / m_stages);
    }
    void checkCancel() const {
        if (m_cancel && m_cancel()) throw Cancelled();
    }
    void setStage(int stage, int stages) { m_stage = stage, m_stages = stages; }

private:
    const std::function<void(double)>& m_progress;
    const std::function<bool()>& m_cancel;
    double m_stage = 0.0, m_stages = 1.0;
};

Stats statsOf(const RenderStats& in) {
    Stats out;
    for (const auto& [phase, seconds] : in.phases()) out.timesMs.emplace_back(phase, seconds * 1000.0);
    out.counters = in.counters();
    out.info = in.info();
    return out;
}

// One channel of a shaded pass: its name, and the scale of the colour component it takes.
struct PassChannel {
    const char* name;
    float scale = 1.0f;
};

// A pass that is the same visibility shaded another way (a render of the method again, with the
// same samples), over a transparent background: the albedo (unlit), the normal, or one half of
// the vector. Each pixel's coverage-weighted value, premultiplied as the colour is (the vector:
// divided by the coverage), into the channels layer.<name>, one per colour component. Timed as
// "<layer> render" (the vector's two renders add up there).
void addShadedPass(streak::Renderer& method, const streak::RenderSettings& settings, ShadingMode mode, const char* layer,
                   std::initializer_list<PassChannel> channels, const std::string& methodName, const streak::Scene& scene, streak::Image& image,
                   RenderStats& stats, ProgressReporter* progress) {
    streak::RenderSettings shaded = settings;
    shaded.shading = mode;
    shaded.passes = PassRequest();
    // Signed values have no display colour to judge contrast by: adaptive sampling would refine
    // their edges by chance, so normals and vectors take every sample (the albedo refines by its
    // own contrast).
    const bool isSigned = mode == ShadingMode::Normal || isVectorPass(mode);
    if (isSigned) shaded.adaptiveThreshold = 0.0f;
    RenderStats passStats;
    RenderContext context{passStats, progress};
    PhaseTimer timer(stats, std::string(layer) + " render");
    streak::Image pass = method.render(scene, shaded, context);
    if (!pass.hasAlpha()) throw RenderFailure("method " + methodName + " gave no coverage for the " + layer + " pass");
    if (!isSigned) pass = withTransparentBackground(std::move(pass), scene.background);
    int c = 0;
    for (const PassChannel& channel : channels) {
        std::vector<float> values(pass.pixels().size());
        for (std::size_t i = 0; i < values.size(); ++i) {
            // Normals and vectors may be negative: the background's share is taken out without clamping.
            const float alpha = pass.alpha()[i], background = isSigned ? scene.background[c] * (1.0f - alpha) : 0.0f;
            values[i] = channel.scale * (pass.pixels()[i][c] - background);
            // The vector is the mean motion of what shows, not premultiplied: Cycles divides its
            // motion pass by its weight, and Vector Blur reads it so at edges.
            if (isVectorPass(mode)) values[i] = alpha > 0.0f ? values[i] / alpha : 0.0f;
        }
        image.addChannel(std::string(layer) + "." + channel.name, std::move(values));
        ++c;
    }
}

}  // namespace

std::string numberList(std::initializer_list<double> values) {
    std::string text;
    for (const double value : values) {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%.9g", value);
        if (!text.empty()) text += ',';
        text += buffer;
    }
    return text;
}

std::string Stats::json() const {
    RenderStats stats;
    for (const auto& [phase, ms] : timesMs) stats.addTime(phase, ms / 1000.0);
    for (const auto& [name, value] : counters) stats.setCounter(name, value);
    for (const auto& [name, value] : info) stats.setInfo(name, value);
    return stats.toJson();
}

std::vector<Method> methods() {
    std::vector<Method> out;
    for (const MethodInfo& info : registeredMethods()) out.push_back({std::string(info.name), std::string(info.description)});
    return out;
}

struct Renderer::Impl {
    RenderSettings settings;
    streak::RenderSettings layerSettings;
    std::unique_ptr<streak::Renderer> method;
    bool albedo = false;  ///< the albedo pass: another render, unlit
    bool normal = false;  ///< the normal pass: another render, shading normals
    bool vector = false;  ///< the vector pass: two more renders, of the scene with its frame motion
};

// The GL twins shade in their own shaders, which know no frame motion.
static bool isGlMethod(const std::string& name) { return name.size() > 3 && name.ends_with("-gl"); }

Renderer::Renderer(const RenderSettings& settings) : m_impl(std::make_unique<Impl>()) {
    if (settings.width <= 0 || settings.height <= 0 || settings.width > kMaxImageSize || settings.height > kMaxImageSize)
        throw Error("render: width and height must be in [1, " + std::to_string(kMaxImageSize) + "], got " + std::to_string(settings.width) +
                    "x" + std::to_string(settings.height));
    if (settings.aa < 1 || settings.aa > 16) throw Error("render: aa must be in [1, 16], got " + std::to_string(settings.aa));
    if (!(settings.adaptive >= 0.0f && settings.adaptive <= 1.0f))
        throw Error("render: adaptive must be a threshold in [0, 1] (0: off), got " + std::to_string(settings.adaptive));
    if (!(settings.adaptiveFull >= 0.0f && settings.adaptiveFull <= 1.0f))
        throw Error("render: adaptiveFull must be a contrast in [0, 1] (0: three times adaptive), got " + std::to_string(settings.adaptiveFull));
    if (settings.adaptiveFull > 0.0f && !(settings.adaptive > 0.0f))
        throw Error("render: adaptiveFull grades what adaptive refines, so it needs adaptive on, got adaptive " + std::to_string(settings.adaptive));
    if (settings.adaptive > 0.0f && settings.aa < 2)
        throw Error("render: adaptive refines pixels to aa x aa samples, so it needs aa 2 or more, got aa " + std::to_string(settings.aa));
    if (settings.threads < 0) throw Error("render: threads must be 0 (all cores) or more, got " + std::to_string(settings.threads));
    if (settings.memoryBudgetMB < 1) throw Error("render: memoryBudgetMB must be 1 or more, got " + std::to_string(settings.memoryBudgetMB));
    if (const std::optional<Region>& r = settings.region;
        r && !(r->x0 >= 0 && r->y0 >= 0 && r->x0 < r->x1 && r->y0 < r->y1 && r->x1 <= settings.width && r->y1 <= settings.height))
        throw Error("render: region " + std::to_string(r->x0) + "," + std::to_string(r->y0) + "," + std::to_string(r->x1) + "," + std::to_string(r->y1) +
                    " (x0,y0,x1,y1: pixels [x0, x1) x [y0, y1)) is not a rectangle inside the " + std::to_string(settings.width) + "x" +
                    std::to_string(settings.height) + " image");
    OptionMap options;
    for (const auto& [key, value] : settings.options) options.set(key, value);
    m_impl->method = createRenderer(settings.method, options);
    m_impl->settings = settings;
    streak::RenderSettings& s = m_impl->layerSettings;
    s.width = settings.width, s.height = settings.height, s.aa = settings.aa;
    s.isGridPattern = settings.sampleGrid;
    s.adaptiveThreshold = settings.adaptive;
    s.adaptiveFullContrast = settings.adaptiveFull;
    s.shading = settings.unlit ? ShadingMode::Unlit : ShadingMode::Phong;
    s.seed = settings.seed;
    s.memoryBudgetMB = std::uint64_t(settings.memoryBudgetMB);
    if (const std::optional<Region>& r = settings.region) s.region = raster::PixelBounds{r->x0, r->y0, r->x1 - 1, r->y1 - 1};
    for (const std::string& pass : settings.passes) {
        if (pass == "depth") s.passes.depth = true;
        else if (pass == "object_id") s.passes.objectId = true;
        else if (pass == "material_id") s.passes.materialId = true;
        else if (pass == "albedo") m_impl->albedo = true;
        else if (pass == "normal") m_impl->normal = true;
        else if (pass == "vector") m_impl->vector = true;
        else throw Error("render: unknown pass '" + pass + "' (depth, object_id, material_id, albedo, normal, vector)");
    }
    if (m_impl->vector && isGlMethod(settings.method))
        throw Error("method " + settings.method + " does not write the vector pass: its shaders have no frame motion (the CPU methods write it)");
    if (m_impl->vector && m_impl->method->animationTrail())
        throw Error("method " + settings.method + " draws a trail, which has no frames around a shutter: the vector pass is the shutter methods'");
    if (settings.cryptomatteRanks < 1 || settings.cryptomatteRanks > 64)
        throw Error("render: cryptomatteRanks must be in [1, 64], got " + std::to_string(settings.cryptomatteRanks));
    s.passes.cryptoRanks = settings.cryptomatteRanks;
    if (settings.deepSamples < 1 || settings.deepSamples > 1024)
        throw Error("render: deepSamples must be in [1, 1024], got " + std::to_string(settings.deepSamples));
    s.passes.deep = settings.deep;
    s.passes.deepSamples = settings.deepSamples;
    s.passes.deepBackground = !settings.transparent;
    if (settings.adaptive > 0.0f && !m_impl->method->refinesAdaptively())
        throw Error("method " + settings.method + " takes every sample of every pixel: adaptive antialiasing is motion-path's, analytic's and higher-order's");
    if (s.passes.any() && !m_impl->method->writesPasses())
        throw Error("method " + settings.method + " does not write the depth, Cryptomatte and deep passes (" +
                    std::string(s.passes.depth ? "depth" : s.passes.objectId ? "object_id" : s.passes.materialId ? "material_id" : "deep") +
                    "): motion-path, analytic, higher-order and motion-path-gl write them exactly, embree, accumulation and stochastic sampled");
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

std::optional<Trail> Renderer::trail() const {
    const std::optional<AnimationTrail> trail = m_impl->method->animationTrail();
    if (!trail) return std::nullopt;
    return Trail{trail->lengthSeconds, trail->keys};
}

RenderResult Renderer::render(const Scene& scene, const std::function<void(double)>& progress, const std::function<bool()>& cancel) {
    const Scene::Impl& in = scene.impl();
    const RenderSettings& settings = m_impl->settings;
    if (const std::optional<Trail> trail = this->trail(); trail && !in.canShowTrail(*trail))
        throw Error("method " + settings.method + " draws a trail: load the glTF scene over it (LoadOptions::trail = Renderer::trail())");

    RenderStats stats = in.loadStats;
    stats.setInfo("scene", in.spec);
    stats.setInfo("method", settings.method);
    stats.setInfo("shading", settings.unlit ? "unlit" : "phong");
    stats.setCounter("width", settings.width);
    stats.setCounter("height", settings.height);
    stats.setCounter("aa", settings.aa);
    stats.setCounter("sample_grid", settings.sampleGrid ? 1 : 0);
    stats.setCounter("transparent", settings.transparent ? 1 : 0);
    stats.setCounter("deep", settings.deep ? 1 : 0);
    if (!settings.passes.empty()) {
        std::string passes;
        for (const std::string& p : settings.passes) passes += (passes.empty() ? "" : ",") + p;
        stats.setInfo("passes", passes);
    }
    stats.setCounter("triangles", double(in.scene.numTriangles()));
    stats.setCounter("skipped_triangles", double(in.cleanup.numSkipped()));
    stats.setCounter("skipped_nonfinite", double(in.cleanup.numNonFinite));
    stats.setCounter("skipped_degenerate", double(in.cleanup.numDegenerate));
    stats.setInfo("shutter_curve", in.scene.shutter.curve.name());
    stats.setInfo("shutter_position", in.shutterPosition);
    stats.setCounter("rolling_shutter", in.scene.shutter.rollingDuration);
    reportCamera(in.scene.camera, stats);

    std::optional<tbb::global_control> threadLimit;
    if (settings.threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(settings.threads));
    CallbackProgress reporter(progress, cancel);
    reporter.checkCancel();
    RenderContext context{stats, progress || cancel ? &reporter : nullptr};
    const int stages = 1 + (m_impl->albedo ? 1 : 0) + (m_impl->normal ? 1 : 0) + (m_impl->vector ? 2 : 0);  // the beauty, then each shaded pass
    // The vector pass's scene (its frames loaded) before anything renders: a scene without
    // frames is bad input, found at once.
    std::optional<streak::Scene> framed;
    if (m_impl->vector) {
        PhaseTimer timer(stats, "vector frames");
        framed = in.withFrameMotion(float(settings.width) / float(settings.height));
    }
    reporter.setStage(0, stages);
    RenderResult result;
    {
        PhaseTimer timer(stats, "render");
        streak::Image image = m_impl->method->render(in.scene, m_impl->layerSettings, context);
        if (!settings.transparent) image.setAlpha({});
        else if (!image.hasAlpha()) throw RenderFailure("method " + settings.method + " gave no coverage for a transparent background");
        else image = withTransparentBackground(std::move(image), in.scene.background);
        int stage = 0;
        auto nextStage = [&] {
            reporter.checkCancel();
            reporter.setStage(++stage, stages);
            return context.progress;
        };
        if (m_impl->albedo)
            addShadedPass(*m_impl->method, m_impl->layerSettings, ShadingMode::Unlit, "albedo", {{"R"}, {"G"}, {"B"}}, settings.method, in.scene, image,
                          stats, nextStage());
        if (m_impl->normal)
            addShadedPass(*m_impl->method, m_impl->layerSettings, ShadingMode::Normal, "normal", {{"X"}, {"Y"}, {"Z"}}, settings.method, in.scene, image,
                          stats, nextStage());
        if (framed) {
            // NDC to pixels, y up as Blender's raster (half the image per NDC unit).
            const float sx = 0.5f * float(settings.width), sy = 0.5f * float(settings.height);
            addShadedPass(*m_impl->method, m_impl->layerSettings, ShadingMode::VectorPrevious, "vector", {{"X", sx}, {"Y", sy}}, settings.method, *framed,
                          image, stats, nextStage());
            addShadedPass(*m_impl->method, m_impl->layerSettings, ShadingMode::VectorNext, "vector", {{"Z", sx}, {"W", sy}}, settings.method, *framed,
                          image, stats, nextStage());
        }
        const std::optional<Region>& r = settings.region;
        if (r) image = image.region(r->x0, r->y0, r->x1, r->y1);
        result.image = imageOf(image);
        if (settings.deep) {
            if (!image.deep()) throw RenderFailure("method " + settings.method + " gave no deep image");
            result.deep = deepImageOf(*image.deep());
            stats.setCounter("deep_samples", double(result.deep->samples.size()));  // the region's, once cropped
        }
    }
    if (const std::optional<Region>& r = settings.region)
        stats.setInfo("region", std::to_string(r->x0) + "," + std::to_string(r->y0) + "," + std::to_string(r->x1) + "," + std::to_string(r->y1));
    result.stats = statsOf(stats);
    return result;
}

RenderResult render(const Scene& scene, const RenderSettings& settings) { return Renderer(settings).render(scene); }

}  // namespace streak::api
