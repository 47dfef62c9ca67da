// streak: the command line. The only place where an Error becomes one stderr line and exit 2.

#include "image/image_io.h"
#include "image/metrics.h"
#include "methods/registry.h"
#include "raster/clip.h"
#include "scene/blur_shell.h"
#include "scene/builtin_scenes.h"
#include "scene/camera.h"
#include "scene/gltf_writer.h"
#include "scene/scene_loader.h"
#include "scene/shutter.h"
#include "util/error.h"

#include <CLI/CLI.hpp>
#include <glm/trigonometric.hpp>
#include <tbb/global_control.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

namespace streak {
namespace {

constexpr int kExitBadInput = 2;

// A one-line progress bar on stderr, drawn only when stderr is a terminal.
class TerminalProgress final : public ProgressReporter {
public:
    TerminalProgress() : m_enabled(isatty(STDERR_FILENO) != 0) {}
    ~TerminalProgress() override {
        if (m_drawn) std::fprintf(stderr, "\r%60s\r", "");
    }
    void update(double fraction) override {
        if (!m_enabled) return;
        const auto now = std::chrono::steady_clock::now();
        if (fraction < 1.0 && m_drawn && now - m_last < std::chrono::milliseconds(100)) return;
        m_last = now;
        m_drawn = true;
        const int width = 40, filled = int(fraction * width + 0.5);
        std::fprintf(stderr, "\r[%s%s] %3d%%", std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
                     int(fraction * 100.0 + 0.5));
        std::fflush(stderr);
    }

private:
    bool m_enabled;
    bool m_drawn = false;
    std::chrono::steady_clock::time_point m_last;
};

// Throws Error unless `path` could be created: a known extension in an existing, writable folder.
void checkWritable(const std::string& path, bool mustBeImage) {
    if (mustBeImage) imageFormatFromPath(path);
    const std::filesystem::path parent = std::filesystem::absolute(path).parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(parent, ec)) throw Error("cannot write " + path + ": folder " + parent.string() + " does not exist");
    if (std::filesystem::is_directory(path, ec)) throw Error("cannot write " + path + ": it is a folder");
    if (access(parent.c_str(), W_OK) != 0) throw Error("cannot write " + path + ": folder is not writable");
}

void writeTextFile(const std::string& path, const std::string& text) {
    const std::string temporary = path + ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary);
        out << text;
        if (!out) {
            std::filesystem::remove(temporary);
            throw Error("cannot write " + path);
        }
    }
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::filesystem::remove(temporary);
        throw Error("cannot write " + path + ": " + ec.message());
    }
}

// "x,y,z" for the camera flags; negative values need the --flag=-1,2,3 form.
glm::vec3 parseVec3(const std::string& text, const std::string& flag) {
    glm::vec3 v;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%f,%f,%f%c", &v.x, &v.y, &v.z, &extra) != 3 || !std::isfinite(v.x) || !std::isfinite(v.y) ||
        !std::isfinite(v.z))
        throw Error(flag + " must be three numbers x,y,z (write --flag=-1,2,3 for negative ones), got '" + text + "'");
    return v;
}

glm::vec3 parseColor(const std::string& text) {
    glm::vec3 c;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%f,%f,%f%c", &c.x, &c.y, &c.z, &extra) != 3 || !std::isfinite(c.x) || !std::isfinite(c.y) ||
        !std::isfinite(c.z) || c.x < 0 || c.y < 0 || c.z < 0)
        throw Error("--background must be three non-negative numbers r,g,b, got '" + text + "'");
    return c;
}

struct RenderArgs {
    std::string scene = "builtin:cubes";
    std::string method = "motion-path";
    std::string output = "streak.png";
    int width = 1024;
    int height = 768;
    std::optional<int> samples;
    std::optional<int> maxFragments;
    std::optional<int> maxIntervals;
    std::optional<int> maskBits;
    std::optional<int> textureSamples;
    std::optional<int> sort;
    std::optional<int> curveSegments;
    std::optional<int> tapsPerTexel;
    std::optional<int> gpuMemory;
    std::vector<std::string> options;
    int aa = 1;
    bool sampleGrid = false;
    std::string shading = "phong";
    std::optional<std::string> background;
    std::uint64_t seed = 0;
    int threads = 0;
    int repeat = 1;
    std::optional<std::string> sequence;  ///< --frames A:B[:STEP]
    std::string stats;
    // Every scene: the shutter's curve and rolling window; glTF: where it sits around the frame.
    std::optional<std::string> shutterCurve;
    std::optional<double> rollingShutter;
    std::optional<std::string> shutterPosition;
    // glTF scenes only: the shutter in animation frames, the animation, its sampling, the camera.
    std::optional<double> frame;
    std::optional<double> shutter;
    std::optional<double> fps;
    std::optional<std::string> animation;
    std::optional<int> motionKeys;
    std::optional<std::string> motionCurve;
    std::optional<int> motionFitSamples;
    std::optional<double> keyTolerance;
    std::optional<int> camera;
    std::optional<std::string> cameraPos;
    std::optional<std::string> cameraTarget;
    std::optional<std::string> cameraUp;
    std::optional<std::string> cameraPosEnd;
    std::optional<std::string> cameraTargetEnd;
    std::optional<float> fov;
};

// The glTF options from the flags; Error for a flag given with a built-in scene or a camera
// flag without the ones it needs.
GltfOptions gltfOptions(const RenderArgs& args) {
    const bool isGltf = isGltfSpec(args.scene);
    const std::pair<const char*, bool> flags[] = {
        {"--frame", args.frame.has_value()}, {"--shutter", args.shutter.has_value()}, {"--fps", args.fps.has_value()},
        {"--animation", args.animation.has_value()}, {"--motion-keys", args.motionKeys.has_value()},
        {"--motion-curve", args.motionCurve.has_value()}, {"--motion-fit-samples", args.motionFitSamples.has_value()}, {"--key-tolerance", args.keyTolerance.has_value()}, {"--camera", args.camera.has_value()},
        {"--camera-pos", args.cameraPos.has_value()}, {"--camera-target", args.cameraTarget.has_value()},
        {"--camera-up", args.cameraUp.has_value()}, {"--camera-pos-end", args.cameraPosEnd.has_value()},
        {"--camera-target-end", args.cameraTargetEnd.has_value()}, {"--fov", args.fov.has_value()}};
    for (const auto& [flag, given] : flags)
        if (given && !isGltf) throw Error(std::string(flag) + " applies to glTF scenes (.gltf, .glb) only");
    GltfOptions options;
    options.frame = args.frame.value_or(options.frame);
    options.shutter = args.shutter.value_or(options.shutter);
    options.fps = args.fps.value_or(options.fps);
    options.animation = args.animation.value_or("");
    options.motionKeys = args.motionKeys.value_or(options.motionKeys);
    if (args.motionKeys && *args.motionKeys == 0) throw Error("--motion-keys must be in [2, 256], got 0");
    options.motionFitSamples = args.motionFitSamples.value_or(options.motionFitSamples);
    if (args.motionFitSamples && *args.motionFitSamples < 0) throw Error("--motion-fit-samples must be 0 or more, got " + std::to_string(*args.motionFitSamples));
    if (args.motionCurve) {
        if (*args.motionCurve == "bezier") options.motionCurve = MotionInterpolation::Bezier;
        else if (*args.motionCurve != "linear") throw Error("--motion-curve must be linear or bezier, got '" + *args.motionCurve + "'");
    }
    options.keyTolerancePixels = args.keyTolerance.value_or(options.keyTolerancePixels);
    options.imageHeight = args.height;
    options.camera = args.camera;
    options.aspect = float(args.width) / float(args.height);
    const bool hasLookAtFlag = args.cameraUp || args.cameraPosEnd || args.cameraTargetEnd || args.fov;
    if (args.cameraPos.has_value() != args.cameraTarget.has_value() || (hasLookAtFlag && !args.cameraPos))
        throw Error("an explicit camera needs both --camera-pos and --camera-target");
    if (args.cameraPos) {
        if (args.camera) throw Error("--camera and --camera-pos cannot both be given");
        GltfLookAt look;
        look.position = parseVec3(*args.cameraPos, "--camera-pos");
        look.target = parseVec3(*args.cameraTarget, "--camera-target");
        if (args.cameraUp) look.up = parseVec3(*args.cameraUp, "--camera-up");
        if (args.cameraPosEnd) look.positionEnd = parseVec3(*args.cameraPosEnd, "--camera-pos-end");
        if (args.cameraTargetEnd) look.targetEnd = parseVec3(*args.cameraTargetEnd, "--camera-target-end");
        look.verticalFovDegrees = args.fov.value_or(look.verticalFovDegrees);
        options.lookAt = look;
    }
    return options;
}

// "x,y,z,..." with every digit a float holds, so another renderer can rebuild the camera.
template <typename... T>
std::string numberList(T... values) {
    std::string text;
    for (const double value : {double(values)...}) {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%.9g", value);
        text += (text.empty() ? "" : ",") + std::string(buffer);
    }
    return text;
}

// Loads the trail a method shows (blur-shell) instead of the shutter: a glTF scene over
// [T - length, T], T = --frame / --fps, with one key pose per update time. The animation holds
// its first pose before it starts, so a trail reaching back past 0 s moves only from there
// (trail_before_start_seconds). Built-in scenes have no clock: their shutter is the trail.
void applyTrail(const RenderArgs& args, const AnimationTrail& trail, const std::string& who, GltfOptions& gltf, RenderStats& stats) {
    for (const auto& [flag, given] : {std::pair{"--shutter", args.shutter.has_value()}, std::pair{"--motion-keys", args.motionKeys.has_value()},
                                      std::pair{"--motion-curve", args.motionCurve.has_value()}})
        if (given) throw Error(std::string(flag) + " does not apply to " + who + ": its trail is length seconds with one key per update");
    if (!isGltfSpec(args.scene)) {
        stats.setInfo("trail", "the built-in scene's shutter");
        return;
    }
    const double end = gltf.frame / gltf.fps;
    gltf.frame -= trail.lengthSeconds * gltf.fps;
    gltf.shutter = trail.lengthSeconds * gltf.fps;
    gltf.motionKeys = trail.keys;
    stats.setInfo("trail", numberList(end - trail.lengthSeconds, end) + " s");
    stats.setCounter("trail_before_start_seconds", std::max(0.0, trail.lengthSeconds - end));
}

// The camera the scene was rendered through (glTF camera, explicit or framing; built-in), in the
// scene's world (glTF: +y up): each pose's position and worldFromCamera rotation (w,x,y,z; the
// camera looks down its -z with +y up), the vertical field of view and the near plane.
void reportCamera(const Camera& camera, RenderStats& stats) {
    for (const auto& [name, pose] : {std::pair{"open", &camera.open}, std::pair{"close", &camera.close}}) {
        const glm::vec3& p = pose->position;
        const glm::quat& q = pose->worldFromCamera;
        stats.setInfo(std::string("camera_") + name + "_position", numberList(p.x, p.y, p.z));
        stats.setInfo(std::string("camera_") + name + "_rotation_wxyz", numberList(q.w, q.x, q.y, q.z));
    }
    stats.setInfo("camera_vertical_fov_deg", numberList(glm::degrees(camera.verticalFov)));
    stats.setInfo("camera_znear", numberList(camera.zNear));
}

// The --option KEY=VALUE flags, into `options`.
void addOptionFlags(const std::vector<std::string>& flags, OptionMap& options) {
    for (const std::string& option : flags) {
        const std::size_t equals = option.find('=');
        if (equals == std::string::npos || equals == 0) throw Error("--option must be KEY=VALUE, got '" + option + "'");
        options.set(option.substr(0, equals), option.substr(equals + 1));
    }
}

std::string lowercaseExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

// The frames a render makes: --frames A:B[:STEP] (a sequence), else the one frame of --frame.
struct FrameList {
    std::vector<double> frames;
    bool isSequence = false;
};

FrameList frameList(const RenderArgs& args, const GltfOptions& gltf) {
    FrameList list;
    if (!args.sequence) {
        list.frames.push_back(gltf.frame);
        return list;
    }
    if (!isGltfSpec(args.scene)) throw Error("--frames A:B applies to glTF scenes (.gltf, .glb) only: a built-in scene has no clock");
    if (args.frame) throw Error("--frame and --frames A:B cannot both be given");
    long first = 0, last = 0, step = 1;
    char extra = 0;
    const int n = std::sscanf(args.sequence->c_str(), "%ld:%ld:%ld%c", &first, &last, &step, &extra);
    const bool hasStep = args.sequence->find(':') != args.sequence->rfind(':');
    if ((n != 2 && n != 3) || (n == 2 && hasStep) || step < 1 || last < first || (last - first) / step >= 100000)
        throw Error("--frames must be A:B or A:B:STEP, whole frames with A <= B and STEP >= 1 (at most 100000 frames; --repeat N renders one frame N times), got '" + *args.sequence + "'");
    for (long f = first; f <= last; f += step) list.frames.push_back(double(f));
    list.isSequence = true;
    return list;
}

// `pattern` with its one %d (or %0Nd) replaced by the frame number; a pattern without one is
// the path itself, allowed only for a single frame.
std::string framePath(const std::string& pattern, double frame, bool isSequence, const std::string& flag) {
    std::string out;
    int conversions = 0;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out += pattern[i];
            continue;
        }
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            out += '%', ++i;
            continue;
        }
        std::size_t j = i + 1;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
        const std::string width = pattern.substr(i + 1, j - i - 1);
        if (j >= pattern.size() || pattern[j] != 'd' || width.size() > 2 || (!width.empty() && width[0] != '0'))
            throw Error(flag + " '" + pattern + "': the only conversion a frame pattern takes is %d or %0Nd (write %% for a %)");
        char number[32];
        std::snprintf(number, sizeof number, ("%" + width + "ld").c_str(), long(std::lround(frame)));
        out += number;
        ++conversions;
        i = j;
    }
    if (conversions > 1) throw Error(flag + " '" + pattern + "' has more than one %d");
    if (conversions == 0 && isSequence) throw Error(flag + " '" + pattern + "' needs a %d (e.g. out_%04d.png) to name each frame of --frames");
    return out;
}

// The shutter flags that shape the exposure (curve, rolling), honoured by every method.
Shutter shutterOf(const RenderArgs& args) {
    Shutter shutter;
    if (args.shutterCurve) shutter.curve = ShutterCurve::parse(*args.shutterCurve);
    if (args.rollingShutter) shutter.rollingDuration = checkRollingDuration(*args.rollingShutter);
    return shutter;
}

void reportShutter(const Shutter& shutter, ShutterPosition position, RenderStats& stats) {
    stats.setInfo("shutter_curve", shutter.curve.name());
    stats.setInfo("shutter_position", shutterPositionName(position));
    stats.setCounter("rolling_shutter", shutter.rollingDuration);
}

// Maps one frame's progress into the sequence's single bar.
class FrameProgress final : public ProgressReporter {
public:
    FrameProgress(ProgressReporter& whole, double offset, double scale) : m_whole(whole), m_offset(offset), m_scale(scale) {}
    void update(double fraction) override { m_whole.update(m_offset + m_scale * fraction); }

private:
    ProgressReporter& m_whole;
    double m_offset, m_scale;
};

int runRender(const RenderArgs& args) {
    using Clock = std::chrono::steady_clock;
    if (args.width <= 0 || args.height <= 0 || args.width > raster::kMaxImageSize || args.height > raster::kMaxImageSize)
        throw Error("--width and --height must be in [1, " + std::to_string(raster::kMaxImageSize) + "], got " +
                    std::to_string(args.width) + "x" + std::to_string(args.height));
    if (args.aa < 1 || args.aa > 16) throw Error("--aa must be in [1, 16], got " + std::to_string(args.aa));
    if (args.repeat < 1) throw Error("--repeat must be 1 or more, got " + std::to_string(args.repeat));
    if (args.threads < 0) throw Error("--threads must be 0 (all cores) or more, got " + std::to_string(args.threads));
    if (args.samples && *args.samples <= 0) throw Error("--samples must be positive, got " + std::to_string(*args.samples));
    RenderSettings settings;
    settings.width = args.width;
    settings.height = args.height;
    settings.aa = args.aa;
    settings.isGridPattern = args.sampleGrid;
    settings.seed = args.seed;
    if (args.shading == "phong") settings.shading = ShadingMode::Phong;
    else if (args.shading == "unlit") settings.shading = ShadingMode::Unlit;
    else throw Error("--shading must be phong or unlit, got '" + args.shading + "'");

    OptionMap methodOptions;
    // Method-specific flags become the method's options; a method rejects those it does not take.
    const std::pair<const char*, const std::optional<int>*> methodFlags[] = {
        {"samples", &args.samples}, {"max-fragments", &args.maxFragments}, {"max-intervals", &args.maxIntervals},
        {"mask-bits", &args.maskBits}, {"texture-samples", &args.textureSamples}, {"sort", &args.sort},
        {"curve-segments", &args.curveSegments}, {"taps-per-texel", &args.tapsPerTexel}, {"gpu-memory", &args.gpuMemory}};
    for (const auto& [key, value] : methodFlags)
        if (value->has_value()) methodOptions.set(key, std::to_string(**value));
    addOptionFlags(args.options, methodOptions);
    std::unique_ptr<Renderer> renderer = createRenderer(args.method, methodOptions);
    const GltfOptions gltf = gltfOptions(args);
    const Shutter shutter = shutterOf(args);
    const ShutterPosition position = parseShutterPosition(args.shutterPosition.value_or("start"));
    if (args.shutterPosition && !isGltfSpec(args.scene)) throw Error("--shutter-position applies to glTF scenes (.gltf, .glb) only");
    const std::optional<AnimationTrail> trail = renderer->animationTrail();
    if (trail && (args.shutterPosition || args.shutterCurve || args.rollingShutter))
        throw Error("the shutter flags do not apply to method " + args.method + ": it draws a trail, not a shutter average");
    const FrameList list = frameList(args, gltf);
    std::vector<std::string> outputs, statsPaths;
    const bool isStatsPerFrame = args.stats.find('%') != std::string::npos;
    for (const double frame : list.frames) {
        outputs.push_back(framePath(args.output, frame, list.isSequence, "-o"));
        checkWritable(outputs.back(), true);
        if (isStatsPerFrame) {
            statsPaths.push_back(framePath(args.stats, frame, list.isSequence, "--stats"));
            checkWritable(statsPaths.back(), false);
        }
    }
    if (!args.stats.empty() && !isStatsPerFrame) checkWritable(args.stats, false);

    std::optional<tbb::global_control> threadLimit;
    if (args.threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(args.threads));

    TerminalProgress progress;
    std::vector<std::string> frameJson;
    for (std::size_t f = 0; f < list.frames.size(); ++f) {
        const auto start = Clock::now();
        RenderStats stats;
        GltfOptions frameGltf = gltf;
        frameGltf.frame = list.frames[f];
        if (trail) applyTrail(args, *trail, "method " + args.method, frameGltf, stats);
        else frameGltf.frame = shutterOpenFrame(position, frameGltf.frame, frameGltf.shutter);

        Scene scene;
        SceneCleanup cleanup;
        {
            PhaseTimer timer(stats, "load");
            scene = loadScene(args.scene, frameGltf, &stats);
            if (args.background) scene.background = parseColor(*args.background);
            scene.shutter = shutter;
            cleanup = validateScene(scene);
        }
        stats.setInfo("scene", args.scene);
        stats.setInfo("method", args.method);
        stats.setInfo("shading", args.shading);
        if (list.isSequence) stats.setCounter("frame", list.frames[f]);
        stats.setCounter("width", args.width);
        stats.setCounter("height", args.height);
        stats.setCounter("aa", args.aa);
        stats.setCounter("sample_grid", args.sampleGrid ? 1 : 0);
        stats.setCounter("triangles", double(scene.numTriangles()));
        stats.setCounter("skipped_triangles", double(cleanup.numSkipped()));
        stats.setCounter("skipped_nonfinite", double(cleanup.numNonFinite));
        stats.setCounter("skipped_degenerate", double(cleanup.numDegenerate));
        reportShutter(scene.shutter, position, stats);
        reportCamera(scene.camera, stats);

        // Renders before the last warm up what a renderer keeps between renders (GL programs and
        // the driver's compiled code, caches); the image and stats are the last's.
        stats.setCounter("repeat", args.repeat);
        Image image;
        for (int r = 0; r < args.repeat; ++r) {
            const bool isLast = r + 1 == args.repeat;
            RenderStats warmUp;
            const double share = 1.0 / (double(list.frames.size()) * args.repeat);
            FrameProgress frameProgress(progress, (double(f) * args.repeat + r) * share, share);
            RenderContext context{isLast ? stats : warmUp, &frameProgress};
            PhaseTimer timer(context.stats, "render");
            image = renderer->render(scene, settings, context);
        }
        writeImage(image, outputs[f]);
        stats.addTime("total", std::chrono::duration<double>(Clock::now() - start).count());
        if (isStatsPerFrame) {
            try {
                writeTextFile(statsPaths[f], stats.toJson());
            } catch (const Error&) {
                std::filesystem::remove(outputs[f]);  // all or nothing, per frame
                throw;
            }
        } else if (!args.stats.empty()) {
            frameJson.push_back(stats.toJson());
        }
    }
    if (!args.stats.empty() && !isStatsPerFrame) {
        std::string text = frameJson.front();
        if (list.isSequence) {
            text = "{\"frames\": [\n";
            for (std::size_t f = 0; f < frameJson.size(); ++f) text += (f ? ",\n" : "") + frameJson[f];
            text += "\n]}\n";
        }
        try {
            writeTextFile(args.stats, text);
        } catch (const Error&) {
            if (!list.isSequence) std::filesystem::remove(outputs.front());  // all or nothing
            throw;
        }
    }
    return 0;
}

std::string decibels(double value) {
    if (std::isinf(value)) return "inf";
    std::ostringstream out;
    out << std::fixed << std::setprecision(4) << value;
    return out.str();
}

int runCompare(const std::string& a, const std::string& b, const std::string& heatmap, double foregroundLevel) {
    if (!heatmap.empty()) checkWritable(heatmap, true);
    if (!(foregroundLevel >= 0.0 && foregroundLevel < 255.0))
        throw Error("--foreground-threshold must be in [0, 255) (sRGB 8-bit levels), got " + std::to_string(foregroundLevel));
    const Image imageA = readImage(a);
    const Image imageB = readImage(b);
    if (imageA.width() != imageB.width() || imageA.height() != imageB.height())
        throw Error("cannot compare " + a + " (" + std::to_string(imageA.width()) + "x" + std::to_string(imageA.height()) + ") with " +
                    b + " (" + std::to_string(imageB.width()) + "x" + std::to_string(imageB.height()) + "): sizes differ");
    const double p = psnr(imageA, imageB);
    const double s = ssim(imageA, imageB);
    const ForegroundPsnr foreground = foregroundPsnr(imageA, imageB, float(foregroundLevel / 255.0));
    std::ostringstream out;
    out.precision(4);
    out << std::fixed << "PSNR: " << decibels(p) << " dB\nSSIM: " << s << "\n";
    out << "foreground PSNR: " << decibels(foreground.psnr) << " dB (" << foreground.pixels << " pixels)\n";
    if (!heatmap.empty()) {
        double maxError = 0.0;
        writeImage(errorHeatmap(imageA, imageB, &maxError), heatmap);
        out << "heatmap: " << heatmap << " (white = " << maxError << " largest error)\n";
    }
    std::cout << out.str();
    return 0;
}

int runExport(const std::string& spec, const std::string& path) {
    if (lowercaseExtension(path) != ".glb") throw Error("cannot write " + path + ": export writes glTF binary (.glb) only");
    checkWritable(path, false);
    Scene scene = loadScene(spec, GltfOptions{}, nullptr);
    validateScene(scene);
    const std::vector<std::uint8_t> bytes = writeGltfBinary(scene);
    writeTextFile(path, std::string(bytes.begin(), bytes.end()));
    return 0;
}

// `streak shell`: the blur shell at T = --frame / --fps and the mesh there, as glTF, so the
// trail can be seen from any angle while the animation is paused (Jones 2004, section 3.3).
int runShell(const RenderArgs& args) {
    OptionMap options("shell");
    addOptionFlags(args.options, options);
    const BlurShellOptions shellOptions = BlurShellOptions::read(options);
    options.rejectUnknown();
    const std::string extension = lowercaseExtension(args.output);
    if (extension != ".glb" && extension != ".gltf") throw Error("cannot write " + args.output + ": shell writes glTF (.glb or .gltf)");
    checkWritable(args.output, false);
    GltfOptions gltf = gltfOptions(args);
    RenderStats stats;
    applyTrail(args, AnimationTrail{shellOptions.lengthSeconds, shellOptions.subdivisions + 1}, "shell", gltf, stats);
    Scene scene = loadScene(args.scene, gltf, &stats);
    validateScene(scene);
    const BlurShell shell = buildBlurShell(scene, shellOptions);
    const ShellScene out = makeShellScene(scene, shell);
    std::size_t triangles = 0;
    for (std::size_t m = out.firstShellMesh; m < out.scene.meshes.size(); ++m) triangles += out.scene.meshes[m].triangles.size();
    if (extension == ".gltf") {
        writeTextFile(args.output, writeGltfText(out.scene));
    } else {
        const std::vector<std::uint8_t> bytes = writeGltfBinary(out.scene);
        writeTextFile(args.output, std::string(bytes.begin(), bytes.end()));
    }
    std::cout << "shell: " << shell.numStrips << " strips, " << triangles << " triangles (" << shell.silhouetteEdges
              << " silhouette edges at the last update) -> " << args.output << "\n";
    return 0;
}

int runScenes() {
    for (const BuiltinSceneInfo& info : builtinScenes()) std::cout << "builtin:" << info.name << "  " << info.description << "\n";
    return 0;
}

int runMethods() {
    for (const MethodInfo& info : registeredMethods()) std::cout << info.name << "  " << info.description << "\n";
    return 0;
}

// The glTF flags (animation, sampling, camera) of the commands that load a scene.
void addGltfFlags(CLI::App* app, RenderArgs& args) {
    app->add_option("--frame", args.frame, "glTF: the shutter opens at this animation frame (0); blur-shell, shell: the trail ends here");
    app->add_option("--shutter", args.shutter, "glTF: frames the shutter stays open (0.5)");
    app->add_option("--fps", args.fps, "glTF: frames per second of animation time (24)");
    app->add_option("--animation", args.animation, "glTF: animation name or index (the first)");
    app->add_option("--motion-keys", args.motionKeys,
                       "glTF: key poses sampled over the shutter (default: as many as keep the keys within --key-tolerance of the animation, up to 33)");
    app->add_option("--motion-curve", args.motionCurve,
                       "glTF: linear (piecewise linear keys) or bezier (the keys, 3 or 4, become the control points of the curve through them)");
    app->add_option("--motion-fit-samples", args.motionFitSamples,
                       "glTF, --motion-curve bezier: fit the curve by least squares to N evenly spaced poses (default 4 (K - 1) + 1 for --motion-keys K); 0: the curve through the K poses");
    app->add_option("--key-tolerance", args.keyTolerance, "glTF: screen pixels the chosen motion keys may stray from the animation (0.125)");
    app->add_option("--camera", args.camera, "glTF: camera index (the first camera a node places; else the scene is framed from +z)");
    app->add_option("--camera-pos", args.cameraPos, "glTF: explicit camera position x,y,z (--camera-pos=-1,2,3 for negatives)");
    app->add_option("--camera-target", args.cameraTarget, "glTF: explicit camera target x,y,z");
    app->add_option("--camera-up", args.cameraUp, "glTF: explicit camera up x,y,z (0,1,0)");
    app->add_option("--camera-pos-end", args.cameraPosEnd, "glTF: camera position at shutter close (moves linearly)");
    app->add_option("--camera-target-end", args.cameraTargetEnd, "glTF: camera target at shutter close");
    app->add_option("--fov", args.fov, "glTF: explicit camera vertical field of view in degrees (45)");
}

int run(int argc, char** argv) {
    CLI::App app{"streak: analytic motion blur of moving and deforming triangle meshes"};
    app.require_subcommand(1);

    RenderArgs renderArgs;
    CLI::App* render = app.add_subcommand("render", "render a scene with motion blur over the shutter [0,1]");
    render->add_option("scene", renderArgs.scene, "scene: builtin:NAME[?key=value&...] (see 'streak scenes') or a glTF 2.0 file (.gltf, .glb)")
        ->capture_default_str();
    render->add_option("-m,--method", renderArgs.method, "motion-blur method (see 'streak methods')")->capture_default_str();
    render->add_option("-o,--output", renderArgs.output, "output image: .png (sRGB 8-bit) or .exr (linear float)")->capture_default_str();
    render->add_option("--width", renderArgs.width, "image width in pixels")->capture_default_str();
    render->add_option("--height", renderArgs.height, "image height in pixels")->capture_default_str();
    render->add_option("--samples", renderArgs.samples, "time samples (accumulation: 256 shutter times; stochastic: 8 per pixel)");
    render->add_option("--max-fragments", renderArgs.maxFragments, "motion-path: fragment budget per pixel sample (4096; the paper's 150 is motion-path-gl's default)");
    render->add_option("--max-intervals", renderArgs.maxIntervals, "motion-path: interval budget per pixel sample (2048; the paper's 90 is motion-path-gl's default); analytic: compression budget K (0: unlimited)");
    render->add_option("--mask-bits", renderArgs.maskBits, "motion-path: time slices per mask, 32|64|128|256 (128)");
    render->add_option("--texture-samples", renderArgs.textureSamples, "motion-path: at most this many texture taps per interval (32)");
    render->add_option("--sort", renderArgs.sort, "motion-path: depth-time sort of intervals, 1 (on) or 0 (nearest-first only) (1)");
    render->add_option("--taps-per-texel", renderArgs.tapsPerTexel,
                       "motion-path: texture taps per texel of the footprint's mip level along an interval's uv path (2)");
    render->add_option("--curve-segments", renderArgs.curveSegments,
                       "motion-path: linear segments per key segment for curved screen motion (moving camera, Bezier keys) (4)");
    render->add_option("--gpu-memory", renderArgs.gpuMemory,
                       "GL methods: MB the per-sample lists may grow to before the per-sample budget applies (1024)");
    render->add_option("--option", renderArgs.options, "a method option KEY=VALUE (repeatable; see the method's options)");
    render->add_option("--aa", renderArgs.aa, "spatial anti-aliasing: N x N sub-pixel samples (n-rooks: each its own row and column), box filter")->capture_default_str();
    render->add_flag("--sample-grid", renderArgs.sampleGrid, "place the --aa samples on the regular N x N grid instead of n-rooks");
    render->add_option("--shading", renderArgs.shading, "phong (one directional light + ambient) or unlit (albedo)")->capture_default_str();
    render->add_option("--background", renderArgs.background, "background colour r,g,b in linear [0,1] (default: the scene's)");
    render->add_option("--seed", renderArgs.seed, "seed of random sampling")->capture_default_str();
    render->add_option("--threads", renderArgs.threads, "worker threads (0: all cores)")->capture_default_str();
    render->add_option("--repeat", renderArgs.repeat, "render each frame this many times; times and counters are the last's (warm: GL programs built)")
        ->capture_default_str();
    render->add_option("--frames", renderArgs.sequence,
                       "glTF: render the frames A:B[:STEP] (frame F gets the shutter at F), each to -o with its %d (e.g. out_%04d.png)");
    render->add_option("--stats", renderArgs.stats,
                       "write figures of the render (times, counters) as JSON to this file (a sequence: one file per frame with %d, else one {\"frames\": [...]})");
    render->add_option("--shutter-curve", renderArgs.shutterCurve,
                       "the shutter's opening over its open time (Blender: Shutter Curve): box, triangle, trapezoid:A (ramps of A at both ends) or T0:W0,T1:W1,... (piecewise linear, T from 0 to 1) (box)");
    render->add_option("--rolling-shutter", renderArgs.rollingShutter,
                       "rolling shutter (Blender: Rolling Shutter Duration): each row is open for this share D in (0, 1] of the shutter, rows starting top first over the other 1 - D (1: global)");
    render->add_option("--shutter-position", renderArgs.shutterPosition,
                       "glTF: where the shutter sits around --frame F (Blender: Shutter Position): start [F, F+S], center [F-S/2, F+S/2] or end [F-S, F] (start)");
    addGltfFlags(render, renderArgs);

    std::string compareA, compareB, heatmap;
    double foregroundLevel = 2.0;
    CLI::App* compare = app.add_subcommand(
        "compare", "print PSNR (dB), SSIM and foreground PSNR (over the pixels where either image is above the threshold) of two images of the same size");
    compare->add_option("a", compareA, "first image (.png or .exr)")->required();
    compare->add_option("b", compareB, "second image (.png or .exr)")->required();
    compare->add_option("--heatmap", heatmap, "write a false-colour image of the per-pixel error");
    compare->add_option("--foreground-threshold", foregroundLevel,
                        "foreground: pixels where a channel of either image is above this, in sRGB 8-bit levels")
        ->capture_default_str();

    std::string exportScene, exportPath;
    CLI::App* exportCommand = app.add_subcommand(
        "export", "write a scene as glTF 2.0 binary (.glb): motion keys as morph targets over the animation's first second "
                  "(render it with --frame 0 --shutter 24 --fps 24)");
    exportCommand->add_option("scene", exportScene, "scene: builtin:NAME[?key=value&...] or a glTF file (its default shutter)")->required();
    exportCommand->add_option("output", exportPath, "output file (.glb)")->required();

    RenderArgs shellArgs;
    shellArgs.output = "shell.glb";
    CLI::App* shellCommand = app.add_subcommand(
        "shell", "write the blur shell (Jones 2004) at T = --frame / --fps and the mesh there as glTF 2.0, to view the trail from any angle");
    shellCommand->add_option("scene", shellArgs.scene, "scene: builtin:NAME[?key=value&...] (its shutter is the trail) or a glTF file")->required();
    shellCommand->add_option("-o,--output", shellArgs.output, "output file (.glb or .gltf)")->capture_default_str();
    shellCommand->add_option("--option", shellArgs.options, "a blur-shell option KEY=VALUE: length, subdivisions, alpha, fade (repeatable)");
    shellCommand->add_option("--width", shellArgs.width, "image width, for the aspect of a framing camera")->capture_default_str();
    shellCommand->add_option("--height", shellArgs.height, "image height, for the aspect of a framing camera")->capture_default_str();
    addGltfFlags(shellCommand, shellArgs);

    CLI::App* scenes = app.add_subcommand("scenes", "list the built-in scenes, one per line");
    CLI::App* methods = app.add_subcommand("methods", "list the motion-blur methods, one per line");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::string message = e.what();
        std::replace(message.begin(), message.end(), '\n', ' ');
        std::cerr << "streak: error: " << message << "\n";
        return kExitBadInput;
    }
    if (render->parsed()) return runRender(renderArgs);
    if (compare->parsed()) return runCompare(compareA, compareB, heatmap, foregroundLevel);
    if (exportCommand->parsed()) return runExport(exportScene, exportPath);
    if (shellCommand->parsed()) return runShell(shellArgs);
    if (scenes->parsed()) return runScenes();
    if (methods->parsed()) return runMethods();
    return kExitBadInput;
}

}  // namespace
}  // namespace streak

int main(int argc, char** argv) {
    try {
        return streak::run(argc, argv);
    } catch (const streak::Error& e) {
        std::cerr << "streak: error: " << e.what() << "\n";
        return streak::kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "streak: internal error: " << e.what() << "\n";
        return 1;
    }
}
