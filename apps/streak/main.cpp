// streak: the command line, a client of the public API (include/streak/) only. The only place
// where an Error becomes one stderr line and exit 2 (bad input), or 1 (RenderFailure: the input
// was good, the machine could not make the render).

#include <streak/streak.h>

#include <CLI/CLI.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

namespace streak {
namespace {

namespace sk = streak::api;

constexpr int kExitBadInput = 2;
constexpr int kExitRenderFailed = 1;  ///< the input was good, the render could not be made (RenderFailure)

// Runs write, a write of an output whose path was accepted before the render: a failure now (a
// full disk, a quota) is the render's, not the input's.
template <class Write>
void writeAccepted(Write&& write) {
    try {
        write();
    } catch (const RenderFailure&) {
        throw;
    } catch (const Error& e) {
        throw RenderFailure(e.what());
    }
}

// A one-line progress bar on stderr, drawn only when stderr is a terminal.
// Progress on stderr: a bar redrawn in place when stderr is a terminal; with --progress-lines,
// lines a farm manager's parser reads (Deadline's and Flamenco's forms): "Progress: N%" as each
// whole percent is reached, and "Frame F done in S s" after each frame; else nothing.
class Progress {
public:
    explicit Progress(bool lines) : m_mode(lines ? Mode::Lines : isatty(STDERR_FILENO) != 0 ? Mode::Bar : Mode::None) {}
    ~Progress() {
        if (m_mode == Mode::Bar && m_drawn) std::fprintf(stderr, "\r%60s\r", "");
    }
    void update(double fraction) {
        const int percent = int(std::clamp(fraction, 0.0, 1.0) * 100.0 + (m_mode == Mode::Bar ? 0.5 : 0.0));
        if (m_mode == Mode::Lines) {
            if (percent <= m_percent) return;
            m_percent = percent;
            std::fprintf(stderr, "Progress: %d%%\n", percent);
            std::fflush(stderr);
            return;
        }
        if (m_mode != Mode::Bar) return;
        const auto now = std::chrono::steady_clock::now();
        if (fraction < 1.0 && m_drawn && now - m_last < std::chrono::milliseconds(100)) return;
        m_last = now;
        m_drawn = true;
        const int width = 40, filled = int(fraction * width + 0.5);
        std::fprintf(stderr, "\r[%s%s] %3d%%", std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(), percent);
        std::fflush(stderr);
    }
    void frameDone(double frame, double seconds) {
        if (m_mode != Mode::Lines) return;
        std::fprintf(stderr, "Frame %ld done in %.1f s\n", std::lround(frame), seconds);
        std::fflush(stderr);
    }

private:
    enum class Mode { None, Bar, Lines };
    Mode m_mode;
    bool m_drawn = false;
    int m_percent = -1;
    std::chrono::steady_clock::time_point m_last;
};

// Throws Error unless `path` could be created: a known extension in an existing, writable folder.
void checkWritable(const std::string& path, bool mustBeImage) {
    if (mustBeImage) sk::checkImagePath(path);
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
std::array<float, 3> parseVec3(const std::string& text, const std::string& flag) {
    std::array<float, 3> v;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%f,%f,%f%c", &v[0], &v[1], &v[2], &extra) != 3 ||
        !std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); }))
        throw Error(flag + " must be three numbers x,y,z (write --flag=-1,2,3 for negative ones), got '" + text + "'");
    return v;
}

std::array<float, 3> parseColor(const std::string& text) {
    std::array<float, 3> c;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%f,%f,%f%c", &c[0], &c[1], &c[2], &extra) != 3 ||
        !std::all_of(c.begin(), c.end(), [](float x) { return std::isfinite(x) && x >= 0.0f; }))
        throw Error("--background must be three non-negative numbers r,g,b, got '" + text + "'");
    return c;
}

// --region x0,y0,x1,y1: four whole numbers.
sk::Region parseRegion(const std::string& text) {
    int v[4];
    const char* p = text.data();
    const char* end = text.data() + text.size();
    for (int i = 0; i < 4; ++i) {
        const auto [next, ec] = std::from_chars(p, end, v[i]);
        if (ec != std::errc() || (i < 3 ? next == end || *next != ',' : next != end))
            throw Error("--region must be four whole numbers x0,y0,x1,y1 (pixels [x0, x1) x [y0, y1)), got '" + text + "'");
        p = next + 1;
    }
    return {v[0], v[1], v[2], v[3]};
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
    float adaptive = 0.0f;
    float adaptiveFull = 0.0f;
    std::optional<std::string> region;  ///< --region x0,y0,x1,y1
    bool sampleGrid = false;
    bool transparent = false;
    std::string passes;  ///< comma-separated
    int cryptomatteRanks = 6;
    std::optional<std::string> deep;  ///< --deep FILE.exr
    int deepSamples = 16;
    std::string shading = "phong";
    std::optional<std::string> background;
    std::uint64_t seed = 0;
    int threads = 0;
    int memoryBudget = sk::kDefaultMemoryBudgetMB;  ///< MB
    int repeat = 1;
    std::optional<std::string> sequence;  ///< --frames A:B[:STEP]
    bool skipExisting = false;            ///< --skip-existing: frames whose output exists are not rendered
    bool placeholders = false;            ///< --placeholders: claim each frame's output before rendering it
    bool progressLines = false;           ///< --progress-lines: progress as lines on stderr
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
    std::optional<int> motionCurveOrder;
    std::optional<double> keyTolerance;
    std::optional<int> camera;
    std::optional<std::string> cameraPos;
    std::optional<std::string> cameraTarget;
    std::optional<std::string> cameraUp;
    std::optional<std::string> cameraPosEnd;
    std::optional<std::string> cameraTargetEnd;
    std::optional<float> fov;
    std::optional<std::string> pointCache;
    std::optional<std::string> pointCacheMesh;
    std::optional<std::string> pointCacheSpace;
    std::optional<std::string> velocityUnit;
    bool sequenceInterpolate = false;
};

// The load options from the flags; Error for a glTF flag given with a built-in scene or a camera
// flag without the ones it needs.
sk::LoadOptions loadOptions(const RenderArgs& args) {
    const bool isGltf = sk::isSceneFile(args.scene);
    const std::pair<const char*, bool> flags[] = {
        {"--frame", args.frame.has_value()}, {"--shutter", args.shutter.has_value()}, {"--fps", args.fps.has_value()},
        {"--animation", args.animation.has_value()}, {"--motion-keys", args.motionKeys.has_value()},
        {"--motion-curve", args.motionCurve.has_value()}, {"--motion-fit-samples", args.motionFitSamples.has_value()},
        {"--motion-curve-order", args.motionCurveOrder.has_value()}, {"--key-tolerance", args.keyTolerance.has_value()}, {"--camera", args.camera.has_value()},
        {"--camera-pos", args.cameraPos.has_value()}, {"--camera-target", args.cameraTarget.has_value()},
        {"--camera-up", args.cameraUp.has_value()}, {"--camera-pos-end", args.cameraPosEnd.has_value()},
        {"--camera-target-end", args.cameraTargetEnd.has_value()}, {"--fov", args.fov.has_value()},
        {"--point-cache", args.pointCache.has_value()}, {"--point-cache-mesh", args.pointCacheMesh.has_value()},
        {"--point-cache-space", args.pointCacheSpace.has_value()}, {"--velocity-unit", args.velocityUnit.has_value()},
        {"--sequence-interpolate", args.sequenceInterpolate}};
    for (const auto& [flag, given] : flags)
        if (given && !isGltf) throw Error(std::string(flag) + " applies to scene files (glTF, OBJ, PLY) only");
    sk::LoadOptions options;
    options.frame = args.frame.value_or(options.frame);
    options.shutterFrames = args.shutter.value_or(options.shutterFrames);
    options.fps = args.fps.value_or(options.fps);
    options.animation = args.animation.value_or("");
    options.motionKeys = args.motionKeys.value_or(options.motionKeys);
    if (args.motionKeys && *args.motionKeys == 0) throw Error("--motion-keys must be in [2, 256], got 0");
    options.motionFitSamples = args.motionFitSamples.value_or(options.motionFitSamples);
    if (args.motionFitSamples && *args.motionFitSamples < 0) throw Error("--motion-fit-samples must be 0 or more, got " + std::to_string(*args.motionFitSamples));
    if (args.motionCurve) {
        if (*args.motionCurve != "bezier" && *args.motionCurve != "linear") throw Error("--motion-curve must be linear or bezier, got '" + *args.motionCurve + "'");
        options.motionCurve = *args.motionCurve;
    }
    if (args.motionCurveOrder && (options.motionCurve != "bezier" || args.motionKeys))
        throw Error("--motion-curve-order takes --motion-curve bezier without --motion-keys (the degree of the chosen pieces)");
    options.motionCurveOrder = args.motionCurveOrder.value_or(options.motionCurveOrder);
    options.keyTolerancePixels = args.keyTolerance.value_or(options.keyTolerancePixels);
    if ((args.pointCacheMesh || args.pointCacheSpace) && !args.pointCache) throw Error("--point-cache-mesh and --point-cache-space need --point-cache");
    options.pointCache = args.pointCache.value_or("");
    options.pointCacheMesh = args.pointCacheMesh.value_or("");
    if (args.pointCacheSpace && *args.pointCacheSpace != "object" && *args.pointCacheSpace != "world")
        throw Error("--point-cache-space must be object or world, got '" + *args.pointCacheSpace + "'");
    options.pointCacheSpace = args.pointCacheSpace.value_or(options.pointCacheSpace);
    options.velocityUnit = args.velocityUnit.value_or(options.velocityUnit);
    options.sequenceInterpolate = args.sequenceInterpolate;
    options.width = args.width;
    options.height = args.height;
    options.camera = args.camera;
    const bool hasLookAtFlag = args.cameraUp || args.cameraPosEnd || args.cameraTargetEnd || args.fov;
    if (args.cameraPos.has_value() != args.cameraTarget.has_value() || (hasLookAtFlag && !args.cameraPos))
        throw Error("an explicit camera needs both --camera-pos and --camera-target");
    if (args.cameraPos) {
        if (args.camera) throw Error("--camera and --camera-pos cannot both be given");
        sk::LookAt look;
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

// A trail method (blur-shell, shell) loads the trail instead of the shutter: Error for the flags
// that place a shutter.
void checkTrailFlags(const RenderArgs& args, const std::string& who) {
    for (const auto& [flag, given] : {std::pair{"--shutter", args.shutter.has_value()}, std::pair{"--motion-keys", args.motionKeys.has_value()},
                                      std::pair{"--motion-curve", args.motionCurve.has_value()}})
        if (given) throw Error(std::string(flag) + " does not apply to " + who + ": its trail is length seconds with one key per update");
}

// The --option KEY=VALUE flags, into `options`.
void addOptionFlags(const std::vector<std::string>& flags, std::map<std::string, std::string>& options) {
    for (const std::string& option : flags) {
        const std::size_t equals = option.find('=');
        if (equals == std::string::npos || equals == 0) throw Error("--option must be KEY=VALUE, got '" + option + "'");
        options[option.substr(0, equals)] = option.substr(equals + 1);
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

FrameList frameList(const RenderArgs& args) {
    FrameList list;
    if (!args.sequence) {
        list.frames.push_back(args.frame.value_or(0.0));
        return list;
    }
    if (!sk::isSceneFile(args.scene)) throw Error("--frames A:B applies to scene files (glTF, OBJ, PLY) only: a built-in scene has no clock");
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
    bool hasNumber = false;
    std::string out;
    try {
        out = sk::framePatternPath(pattern, std::lround(frame), hasNumber);
    } catch (const Error& e) {
        throw Error(flag + " " + e.what());
    }
    if (!hasNumber && isSequence) throw Error(flag + " '" + pattern + "' needs a %d (e.g. out_%04d.png) to name each frame of --frames");
    return out;
}

// Claims a frame for this process (Blender's placeholders): creates its output, empty, only if no
// file is there, in one atomic step (O_EXCL), so that of the machines sharing a folder exactly one
// renders each frame. False where the output exists: rendered, or claimed by another.
bool claimOutput(const std::string& path) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd < 0) {
        if (errno == EEXIST) return false;
        throw Error("cannot claim " + path + ": " + std::strerror(errno));
    }
    ::close(fd);
    return true;
}

int runRender(const RenderArgs& args) {
    using Clock = std::chrono::steady_clock;
    if (args.width <= 0 || args.height <= 0 || args.width > sk::kMaxImageSize || args.height > sk::kMaxImageSize)
        throw Error("--width and --height must be in [1, " + std::to_string(sk::kMaxImageSize) + "], got " +
                    std::to_string(args.width) + "x" + std::to_string(args.height));
    if (args.aa < 1 || args.aa > 16) throw Error("--aa must be in [1, 16], got " + std::to_string(args.aa));
    if (args.repeat < 1) throw Error("--repeat must be 1 or more, got " + std::to_string(args.repeat));
    if (args.threads < 0) throw Error("--threads must be 0 (all cores) or more, got " + std::to_string(args.threads));
    if (args.memoryBudget < 1) throw Error("--memory-budget must be 1 MB or more, got " + std::to_string(args.memoryBudget));
    if (args.samples && *args.samples <= 0) throw Error("--samples must be positive, got " + std::to_string(*args.samples));
    if (args.shading != "phong" && args.shading != "unlit") throw Error("--shading must be phong or unlit, got '" + args.shading + "'");
    sk::RenderSettings settings;
    settings.method = args.method;
    settings.width = args.width;
    settings.height = args.height;
    settings.aa = args.aa;
    settings.adaptive = args.adaptive;
    settings.adaptiveFull = args.adaptiveFull;
    settings.sampleGrid = args.sampleGrid;
    settings.transparent = args.transparent;
    for (std::size_t begin = 0; begin < args.passes.size();) {
        const std::size_t comma = std::min(args.passes.find(',', begin), args.passes.size());
        settings.passes.push_back(args.passes.substr(begin, comma - begin));
        begin = comma + 1;
    }
    settings.cryptomatteRanks = args.cryptomatteRanks;
    if (!settings.passes.empty() && lowercaseExtension(args.output) != ".exr")
        throw Error("--passes are written to EXR: -o " + args.output + " is not an .exr");
    if (args.deep && lowercaseExtension(*args.deep) != ".exr") throw Error("--deep writes a deep EXR: " + *args.deep + " is not an .exr");
    if (args.deepSamples < 1 || args.deepSamples > 1024) throw Error("--deep-samples must be in [1, 1024], got " + std::to_string(args.deepSamples));
    settings.deep = args.deep.has_value();
    settings.deepSamples = args.deepSamples;
    settings.unlit = args.shading == "unlit";
    settings.seed = args.seed;
    settings.threads = args.threads;
    settings.memoryBudgetMB = args.memoryBudget;
    if (args.region) settings.region = parseRegion(*args.region);  // the Renderer checks it lies in the image
    // Method-specific flags become the method's options; a method rejects those it does not take.
    const std::pair<const char*, const std::optional<int>*> methodFlags[] = {
        {"samples", &args.samples}, {"max-fragments", &args.maxFragments}, {"max-intervals", &args.maxIntervals},
        {"mask-bits", &args.maskBits}, {"texture-samples", &args.textureSamples}, {"sort", &args.sort},
        {"curve-segments", &args.curveSegments}, {"taps-per-texel", &args.tapsPerTexel}, {"gpu-memory", &args.gpuMemory}};
    for (const auto& [key, value] : methodFlags)
        if (value->has_value()) settings.options[key] = std::to_string(**value);
    addOptionFlags(args.options, settings.options);
    sk::Renderer renderer(settings);

    sk::LoadOptions load = loadOptions(args);
    if (args.shutterCurve) load.shutter.curve = *args.shutterCurve;
    if (args.rollingShutter) load.shutter.rollingDuration = float(*args.rollingShutter);
    if (args.shutterPosition) load.shutterPosition = *args.shutterPosition;
    if (args.background) load.background = parseColor(*args.background);
    if (args.shutterPosition && !sk::isSceneFile(args.scene)) throw Error("--shutter-position applies to scene files (glTF, OBJ, PLY) only");
    load.trail = renderer.trail();
    if (load.trail) {
        if (args.shutterPosition || args.shutterCurve || args.rollingShutter)
            throw Error("the shutter flags do not apply to method " + args.method + ": it draws a trail, not a shutter average");
        if (sk::isSceneFile(args.scene)) checkTrailFlags(args, "method " + args.method);
    }
    const FrameList list = frameList(args);
    std::vector<std::string> outputs, statsPaths, deepPaths;
    const bool isStatsPerFrame = args.stats.find('%') != std::string::npos;
    for (const double frame : list.frames) {
        outputs.push_back(framePath(args.output, frame, list.isSequence, "-o"));
        checkWritable(outputs.back(), true);
        if (args.deep) {
            deepPaths.push_back(framePath(*args.deep, frame, list.isSequence, "--deep"));
            checkWritable(deepPaths.back(), true);
            if (std::filesystem::weakly_canonical(deepPaths.back()) == std::filesystem::weakly_canonical(outputs.back()))
                throw Error("--deep " + deepPaths.back() + " is the -o image: the deep image is a file of its own");
        }
        if (isStatsPerFrame) {
            statsPaths.push_back(framePath(args.stats, frame, list.isSequence, "--stats"));
            checkWritable(statsPaths.back(), false);
        }
    }
    if (!args.stats.empty() && !isStatsPerFrame) checkWritable(args.stats, false);

    Progress progress(args.progressLines);
    std::vector<std::string> frameJson;
    for (std::size_t f = 0; f < list.frames.size(); ++f) {
        // A frame whose output exists is another's or done (--skip-existing); with placeholders
        // this process claims the frame first, and a claim it cannot make is a frame taken.
        const bool isTaken = args.placeholders ? !claimOutput(outputs[f]) : args.skipExisting && std::filesystem::exists(outputs[f]);
        const bool isClaimed = args.placeholders && !isTaken;
        if (isTaken) {
            std::cout << "skipped frame " << list.frames[f] << ": " << outputs[f] << " exists" << std::endl;
            progress.update(double(f + 1) / double(list.frames.size()));
            continue;
        }
        try {
            const auto start = Clock::now();
            load.frame = list.frames[f];
            const sk::Scene scene = sk::Scene::load(args.scene, load);

            // Renders before the last warm up what a renderer keeps between renders (GL programs
            // and the driver's compiled code, caches); the image and stats are the last's.
            sk::RenderResult result;
            for (int r = 0; r < args.repeat; ++r) {
                const double share = 1.0 / (double(list.frames.size()) * args.repeat), offset = (double(f) * args.repeat + r) * share;
                result = renderer.render(scene, [&](double fraction) { progress.update(offset + share * fraction); });
            }
            sk::Stats& stats = result.stats;
            stats.counters["repeat"] = args.repeat;
            if (list.isSequence) stats.counters["frame"] = list.frames[f];
            // All or nothing, per frame: the image, its deep image and its stats.
            auto removeFrame = [&] {
                std::filesystem::remove(outputs[f]);
                if (args.deep) std::filesystem::remove(deepPaths[f]);
            };
            writeAccepted([&] { sk::writeImage(result.image, outputs[f]); });
            if (result.deep) {
                try {
                    writeAccepted([&] { sk::writeDeepImage(*result.deep, deepPaths[f]); });
                } catch (const Error&) {
                    std::filesystem::remove(outputs[f]);
                    throw;
                }
            }
            stats.timesMs.emplace_back("total", std::chrono::duration<double, std::milli>(Clock::now() - start).count());
            if (isStatsPerFrame) {
                try {
                    writeAccepted([&] { writeTextFile(statsPaths[f], stats.json()); });
                } catch (const Error&) {
                    removeFrame();
                    throw;
                }
            } else if (!args.stats.empty()) {
                frameJson.push_back(stats.json());
            }
            progress.update(double(f + 1) / double(list.frames.size()));
            progress.frameDone(list.frames[f], std::chrono::duration<double>(Clock::now() - start).count());
        } catch (...) {
            if (isClaimed) std::filesystem::remove(outputs[f]);  // the claim goes with a failed render
            throw;
        }
    }
    if (!args.stats.empty() && !isStatsPerFrame && (list.isSequence || !frameJson.empty())) {
        std::string text = list.isSequence ? std::string() : frameJson.front();
        if (list.isSequence) {
            text = "{\"frames\": [\n";
            for (std::size_t f = 0; f < frameJson.size(); ++f) text += (f ? ",\n" : "") + frameJson[f];
            text += "\n]}\n";
        }
        try {
            writeAccepted([&] { writeTextFile(args.stats, text); });
        } catch (const Error&) {
            if (!list.isSequence) {  // all or nothing
                std::filesystem::remove(outputs.front());
                if (args.deep) std::filesystem::remove(deepPaths.front());
            }
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
    const sk::Image imageA = sk::readImage(a);
    const sk::Image imageB = sk::readImage(b);
    if (imageA.width != imageB.width || imageA.height != imageB.height)
        throw Error("cannot compare " + a + " (" + std::to_string(imageA.width) + "x" + std::to_string(imageA.height) + ") with " + b +
                    " (" + std::to_string(imageB.width) + "x" + std::to_string(imageB.height) + "): sizes differ");
    const sk::Comparison c = sk::compare(imageA, imageB, float(foregroundLevel / 255.0));
    std::ostringstream out;
    out.precision(4);
    out << std::fixed << "PSNR: " << decibels(c.psnr) << " dB\nSSIM: " << c.ssim << "\n";
    out << "foreground PSNR: " << decibels(c.foregroundPsnr) << " dB (" << c.foregroundPixels << " pixels)\n";
    for (const sk::PassComparison& p : sk::comparePasses(imageA, imageB))
        out << p.pass << ": RMS " << std::setprecision(6) << p.rms << ", max " << p.maxError << " (" << p.pixels << " pixels)\n" << std::setprecision(4);
    if (!heatmap.empty()) {
        const sk::Heatmap map = sk::errorHeatmap(imageA, imageB);
        sk::writeImage(map.image, heatmap);
        out << "heatmap: " << heatmap << " (white = " << map.maxError << " largest error)\n";
    }
    std::cout << out.str();
    return 0;
}

// `streak stitch`: regions of one frame, rendered apart with --region to EXR, joined into it.
int runStitch(const std::string& output, const std::vector<std::string>& inputs) {
    checkWritable(output, true);
    std::vector<sk::Image> regions;
    for (const std::string& path : inputs) {
        if (lowercaseExtension(path) != ".exr") throw Error("cannot stitch " + path + ": stitch joins EXR regions (a PNG does not say where its region lies)");
        regions.push_back(sk::readImage(path));  // a whole frame is the region covering it
    }
    const sk::Image frame = sk::stitch(regions);
    sk::writeImage(frame, output);
    std::cout << "stitched " << inputs.size() << " regions into " << frame.width << "x" << frame.height << " -> " << output << "\n";
    return 0;
}

int runExport(const std::string& spec, const std::string& path) {
    if (lowercaseExtension(path) != ".glb") throw Error("cannot write " + path + ": export writes glTF binary (.glb) only");
    checkWritable(path, false);
    sk::Scene::load(spec).writeGltf(path);
    return 0;
}

// `streak shell`: the blur shell at T = --frame / --fps and the mesh there, as glTF, so the
// trail can be seen from any angle while the animation is paused (Jones 2004, section 3.3).
int runShell(const RenderArgs& args) {
    std::map<std::string, std::string> options;
    addOptionFlags(args.options, options);
    sk::LoadOptions load = loadOptions(args);
    load.trail = sk::blurShellTrail(options);
    const std::string extension = lowercaseExtension(args.output);
    if (extension != ".glb" && extension != ".gltf") throw Error("cannot write " + args.output + ": shell writes glTF (.glb or .gltf)");
    checkWritable(args.output, false);
    if (sk::isSceneFile(args.scene)) checkTrailFlags(args, "shell");
    const sk::BlurShell shell = sk::blurShell(sk::Scene::load(args.scene, load), options);
    shell.scene.writeGltf(args.output);
    std::cout << "shell: " << shell.strips << " strips, " << shell.triangles << " triangles (" << shell.silhouetteEdges
              << " silhouette edges at the last update) -> " << args.output << "\n";
    return 0;
}

int runScenes() {
    for (const sk::SceneInfo& info : sk::builtinScenes()) std::cout << "builtin:" << info.name << "  " << info.description << "\n";
    return 0;
}

int runMethods() {
    for (const sk::Method& info : sk::methods()) std::cout << info.name << "  " << info.description << "\n";
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
                       "glTF: linear (piecewise linear keys) or bezier (curves through the poses: with --motion-keys 3 or 4 one curve; "
                       "without, as many pieces as keep within --key-tolerance of the animation)");
    app->add_option("--motion-curve-order", args.motionCurveOrder,
                       "glTF, --motion-curve bezier without --motion-keys: the degree of the chosen pieces, 2 or 3 (2)");
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
    app->add_option("--point-cache", args.pointCache,
                    "glTF: a PC2 or MDD point cache (Blender's Mesh Cache) moving one mesh: its triangle primitives' vertices, in order, "
                    "take the cache's points instead of its skin and morph targets (PC2 frames at --fps from its start frame; MDD times in seconds)");
    app->add_option("--point-cache-mesh", args.pointCacheMesh, "glTF: the node or mesh name the point cache moves (default: the scene's only mesh)");
    app->add_flag("--sequence-interpolate", args.sequenceInterpolate,
                  "OBJ/PLY sequences: interpolate the files even where their triangles differ (files of other vertex counts: an error, not held)");
    app->add_option("--velocity-unit", args.velocityUnit,
                    "velocities (glTF _VELOCITY, PLY vx vy vz, an OBJ's NAME.vel sidecar) in metres per second or per frame: second or frame (second)");
    app->add_option("--point-cache-space", args.pointCacheSpace,
                    "glTF: object (the cache's points are in the node's space, which its transform places) or world (object)");
}

int run(int argc, char** argv) {
    CLI::App app{"streak: analytic motion blur of moving and deforming triangle meshes"};
    app.require_subcommand(1);

    RenderArgs renderArgs;
    CLI::App* render = app.add_subcommand("render", "render a scene with motion blur over the shutter [0,1]");
    render->add_option("scene", renderArgs.scene, "scene: builtin:NAME[?key=value&...] (see 'streak scenes'), a glTF 2.0 file (.gltf, .glb), or an OBJ/PLY mesh or numbered sequence (mesh_%04d.ply)")
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
                       "motion-path: linear segments per key segment for curved screen motion (turning camera, Bezier keys); 0: as many "
                       "(1, 2, 4 ... 64) as keep vertices within 1/8 pixel of their screen paths (0)");
    render->add_option("--gpu-memory", renderArgs.gpuMemory,
                       "GL methods: MB the per-sample lists may grow to before the per-sample budget applies (1024)");
    render->add_option("--option", renderArgs.options, "a method option KEY=VALUE (repeatable; see the method's options)");
    render->add_option("--aa", renderArgs.aa, "spatial anti-aliasing: N x N sub-pixel samples (n-rooks: each its own row and column), box filter")->capture_default_str();
    render->add_option("--adaptive", renderArgs.adaptive,
                       "adaptive anti-aliasing, a threshold T in (0, 1] (0: off; motion-path, analytic, higher-order): one sample per pixel first, "
                       "then --aa N x N samples (or half as many a side: --adaptive-full) where a pixel and a neighbour differ by more than T in sRGB colour or coverage "
                       "(still edges, silhouettes; a motion-blurred ramp mostly keeps one sample). 0.02 refines what aliasing shows")
        ->capture_default_str();
    render->add_option("--adaptive-full", renderArgs.adaptiveFull,
                       "with --adaptive T at --aa 3 or more: a refined pixel whose largest difference is at most this takes half the "
                       "samples a side (at least 2), the rest N x N (0: 3 T; T: every refined pixel N x N)")
        ->capture_default_str();
    render->add_option("--region", renderArgs.region,
                       "render only the pixels [x0, x1) x [y0, y1) of the image, x0,y0,x1,y1 (Blender's border render): to .exr the "
                       "region keeps its place in the frame (data window), and 'streak stitch' joins regions into the whole frame, bit for bit");
    render->add_flag("--sample-grid", renderArgs.sampleGrid, "place the --aa samples on the regular N x N grid instead of n-rooks");
    render->add_option("--passes", renderArgs.passes,
                       "passes written beside the colour into the EXR, comma-separated: depth (Z, Z.min), object_id and material_id "
                       "(Cryptomatte 1.1: CryptoObject00..., CryptoMaterial00...; motion-path, analytic, higher-order, motion-path-gl exact; embree, accumulation, stochastic sampled), "
                       "albedo (albedo.R/G/B: every method, one more render, unlit), normal (normal.X/Y/Z: every method, one more render), "
                       "vector (vector.X/Y/Z/W, Blender's Vector: screen motion in pixels to the frame before and from the frame after; "
                       "CPU methods, scenes with frames, two more renders)");
    render->add_option("--cryptomatte-ranks", renderArgs.cryptomatteRanks, "Cryptomatte (ID, coverage) pairs kept per pixel")->capture_default_str();
    CLI::Option* deepOption = render->add_option("--deep", renderArgs.deep,
                       "also write a deep scanline EXR (R G B A Z ZBack, what Nuke's DeepRead takes) to this .exr: per pixel a sample per "
                       "visible surface layer, from the nearest depth it shows at to the farthest, compositing front to back to the image's RGBA "
                       "(the background's sample at Z 1e10 unless --transparent); motion-path, analytic, higher-order, motion-path-gl exact; embree, accumulation, stochastic sampled. "
                       "With --frames, a pattern as -o");
    render->add_option("--deep-samples", renderArgs.deepSamples,
                       "deep samples (surface layers) kept per pixel; the closest in depth are joined past it (deep_layers_merged in --stats)")
        ->capture_default_str()
        ->needs(deepOption);
    render->add_flag("--transparent", renderArgs.transparent,
                     "transparent background (Blender's Film > Transparent): RGBA, alpha the exact coverage; EXR premultiplied, PNG straight");
    render->add_option("--shading", renderArgs.shading, "phong (one directional light + ambient) or unlit (albedo)")->capture_default_str();
    render->add_option("--background", renderArgs.background, "background colour r,g,b in linear [0,1] (default: the scene's)");
    render->add_option("--seed", renderArgs.seed, "seed of random sampling")->capture_default_str();
    render->add_option("--threads", renderArgs.threads, "worker threads (0: all cores)")->capture_default_str();
    render->add_option("--memory-budget", renderArgs.memoryBudget,
                       "MB the render should stay within: the exact methods split tiles whose lists would pass what it leaves above the scene "
                       "(--stats: memory_budget_*)")->capture_default_str();
    render->add_option("--repeat", renderArgs.repeat, "render each frame this many times; times and counters are the last's (warm: GL programs built)")
        ->capture_default_str();
    render->add_option("--frames", renderArgs.sequence,
                       "glTF: render the frames A:B[:STEP] (frame F gets the shutter at F), each to -o with its %d (e.g. out_%04d.png)");
    render->add_flag("--progress-lines", renderArgs.progressLines,
                     "progress as lines on stderr, for a farm manager's log parser: \"Progress: N%\" at each whole percent and "
                     "\"Frame F done in S s\" after each frame (default: a bar when stderr is a terminal, else nothing)");
    render->add_flag("--skip-existing", renderArgs.skipExisting,
                     "render only the frames whose output file is missing (Blender's Overwrite off)");
    render->add_flag("--placeholders", renderArgs.placeholders,
                     "claim each frame by creating its output, empty, before rendering it, only if no file is there (atomically): a "
                     "frame whose output exists is skipped, and a failed render removes its claim (Blender's Placeholders). "
                     "Machines sharing a folder can then all run the same --frames, and each frame is rendered once");
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
        "compare", "print PSNR (dB), SSIM and foreground PSNR (over the pixels where either image is above the threshold) of two images of the same size; "
                   "then, for the passes both have, RMS and largest difference: alpha, each channel (Z, albedo.R, ...) and each Cryptomatte name's matte");
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
    exportCommand->add_option("scene", exportScene, "scene: builtin:NAME[?key=value&...], a glTF file or an OBJ/PLY mesh or sequence (its default shutter)")->required();
    exportCommand->add_option("output", exportPath, "output file (.glb)")->required();

    RenderArgs shellArgs;
    shellArgs.output = "shell.glb";
    CLI::App* shellCommand = app.add_subcommand(
        "shell", "write the blur shell (Jones 2004) at T = --frame / --fps and the mesh there as glTF 2.0, to view the trail from any angle");
    shellCommand->add_option("scene", shellArgs.scene, "scene: builtin:NAME[?key=value&...] (its shutter is the trail), a glTF file or an OBJ/PLY mesh or sequence")->required();
    shellCommand->add_option("-o,--output", shellArgs.output, "output file (.glb or .gltf)")->capture_default_str();
    shellCommand->add_option("--option", shellArgs.options, "a blur-shell option KEY=VALUE: length, subdivisions, alpha, fade (repeatable)");
    shellCommand->add_option("--width", shellArgs.width, "image width, for the aspect of a framing camera")->capture_default_str();
    shellCommand->add_option("--height", shellArgs.height, "image height, for the aspect of a framing camera")->capture_default_str();
    addGltfFlags(shellCommand, shellArgs);

    std::string stitchOutput;
    std::vector<std::string> stitchInputs;
    CLI::App* stitchCommand = app.add_subcommand(
        "stitch", "join regions of one frame, rendered with --region to .exr, into the whole frame: each pixel from the one region "
                  "holding it (an error if they overlap or leave a pixel out)");
    stitchCommand->add_option("output", stitchOutput, "the whole frame (.png or .exr)")->required();
    stitchCommand->add_option("regions", stitchInputs, "the regions (.exr)")->required();

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
    if (stitchCommand->parsed()) return runStitch(stitchOutput, stitchInputs);
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
    } catch (const streak::RenderFailure& e) {
        std::cerr << "streak: error: " << e.what() << "\n";
        return streak::kExitRenderFailed;
    } catch (const streak::Error& e) {
        std::cerr << "streak: error: " << e.what() << "\n";
        return streak::kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "streak: internal error: " << e.what() << "\n";
        return 1;
    }
}
