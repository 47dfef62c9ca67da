#include "methods/embree/embree_renderer.h"

#include "exposure/sample_passes.h"
#include "raster/sample_pattern.h"
#include "scene/flat_geometry.h"
#include "util/error.h"
#include "util/progress.h"
#include "util/random.h"

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec4.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace streak {

namespace {

// Embree's handles, owned.
struct DeviceRelease {
    void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
};
struct SceneRelease {
    void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};
using DeviceHandle = std::unique_ptr<RTCDeviceTy, DeviceRelease>;
using SceneHandle = std::unique_ptr<RTCSceneTy, SceneRelease>;

// The first error Embree reports on a device, turned into one Error when checked.
struct DeviceErrors {
    std::string first;
    static void record(void* user, RTCError, const char* message) {
        auto* errors = static_cast<DeviceErrors*>(user);
        if (errors->first.empty()) errors->first = message ? message : "unknown error";
    }
    void check(const char* what) const {
        if (!first.empty()) throw RenderFailure(std::string("Embree: ") + what + ": " + first);
    }
};

// The triangles a ray has already met (passed through): an intersection filter skips them, so
// the next trace from the same distance finds the next surface, coplanar ones included.
struct SkipContext {
    RTCIntersectContext context;  ///< first: Embree hands the filter a pointer to it
    const std::pair<unsigned, unsigned>* skipped = nullptr;
    std::size_t numSkipped = 0;
};

void skipMetTriangles(const RTCFilterFunctionNArguments* args) {
    const auto* skip = reinterpret_cast<const SkipContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const std::pair<unsigned, unsigned> id{RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i)};
        if (std::find(skip->skipped, skip->skipped + skip->numSkipped, id) != skip->skipped + skip->numSkipped) args->valid[i] = 0;
    }
}

struct Options {
    int samples = 8;
    int curveSegments = 4;
    int maxLayers = 64;
};

// One mesh as Embree sees it: positions (and normals) at evenly spaced time steps, linear
// between them. Piecewise-linear keys are the steps; Bezier keys are cut into steps.
struct SteppedMesh {
    int numSteps = 1;
    std::vector<glm::vec3> positions;  ///< step-major
    std::vector<glm::vec3> normals;    ///< step-major, or empty
    std::uint32_t firstTriangle = 0;   ///< in FlatGeometry's order

    // The step pair and weight at time t.
    std::pair<int, float> stepAt(float t) const {
        if (numSteps == 1) return {0, 0.0f};
        const float x = std::clamp(t, 0.0f, 1.0f) * float(numSteps - 1);
        const int s = std::min(int(x), numSteps - 2);
        return {s, x - float(s)};
    }
};

class EmbreeRenderer final : public Renderer {
public:
    explicit EmbreeRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        DeviceErrors errors;
        const DeviceHandle device(rtcNewDevice(nullptr));
        if (!device) throw Error("Embree: cannot create a device (" + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
        rtcSetDeviceErrorFunction(device.get(), DeviceErrors::record, &errors);
        const FlatGeometry geometry(scene);
        std::vector<SteppedMesh> meshes;
        SceneHandle rtScene;
        {
            PhaseTimer timer(context.stats, "build");
            meshes = steppedMeshes(scene);
            rtScene = buildScene(device.get(), scene, meshes);
            errors.check("building the scene");
        }

        const raster::SamplePattern pattern = raster::samplePatternFor(settings.aa, settings.isGridPattern);
        const int spp = pattern.count(), width = settings.width, height = settings.height;
        const float aspect = float(width) / float(height), tanHalf = std::tan(scene.camera.verticalFov * 0.5f);
        const double spacing = double(pattern.footprintStep()) / double(raster::kSubpixelScale);
        Image image(width, height);
        image.setUncovered();
        std::optional<exposure::PassFrame> passFrame;
        if (settings.passes.any()) passFrame.emplace(scene, settings.passes, width, height);
        std::atomic<std::int64_t> rays{0}, overflowSamples{0};
        PhaseTimer timer(context.stats, "trace+shade");
        // A region render traces its pixels only: each pixel's rays are seeded by the pixel, not by
        // what was traced before it.
        const raster::PixelBounds pixels = settings.region.value_or(raster::PixelBounds{0, 0, width - 1, height - 1});
        PartsProgress progress(context.progress, std::size_t(pixels.y1 - pixels.y0 + 1));
        tbb::parallel_for(tbb::blocked_range<int>(pixels.y0, pixels.y1 + 1, 1), [&](const tbb::blocked_range<int>& rows) {
            std::vector<std::pair<unsigned, unsigned>> skipped;
            std::int64_t localRays = 0, localOverflow = 0;
            exposure::PixelPasses pixelPasses;
            exposure::PixelPasses* passes = passFrame ? &pixelPasses : nullptr;
            for (int py = rows.begin(); py != rows.end(); ++py) {
                const ShutterWindow window = scene.shutter.rowWindow(py, height);  // times stratified in its exposure
                for (int px = pixels.x0; px <= pixels.x1; ++px) {
                    glm::vec4 sum(0.0f);
                    if (passes) passes->begin(*passFrame);
                    const std::uint64_t pixel = std::uint64_t(py) * std::uint64_t(width) + std::uint64_t(px);
                    for (int a = 0; a < spp; ++a) {
                        const glm::dvec2 ndc = pattern.ndcOf(px, py, a, width, height);
                        for (int j = 0; j < m_options.samples; ++j) {
                            const float t = window.timeAt(stratifiedSampleTime(settings.seed, pixel, a, j, m_options.samples));
                            const CameraPose pose = scene.camera.poseAt(t);
                            const glm::mat3 worldFromCamera = glm::mat3_cast(pose.worldFromCamera);
                            // View z is -1, so a ray's distance is the view depth (clip w).
                            auto directionAt = [&](double x, double y) {
                                return worldFromCamera * glm::vec3(float(x) * aspect * tanHalf, float(y) * tanHalf, -1.0f);
                            };
                            const Ray ray{pose.position, directionAt(ndc.x, ndc.y), directionAt(ndc.x + 2.0 * spacing / width, ndc.y),
                                          directionAt(ndc.x, ndc.y - 2.0 * spacing / height), t};
                            bool isOverflow = false;
                            sum += trace(rtScene.get(), geometry, meshes, ray, settings.shading, skipped, localRays, isOverflow, passes);
                            localOverflow += isOverflow ? 1 : 0;
                        }
                    }
                    const glm::vec4 mean = sum / float(spp * m_options.samples);
                    image.at(px, py) = glm::vec3(mean);
                    image.alpha()[std::size_t(pixel)] = mean.w;
                    if (passes) passes->finish(*passFrame, px, py, 1.0f / float(spp * m_options.samples));
                }
                progress.partDone();
            }
            rays += localRays;
            overflowSamples += localOverflow;
        });
        errors.check("tracing");
        RenderStats& stats = context.stats;
        stats.setCounter("time_samples_per_position", m_options.samples);
        stats.setCounter("rays", double(rays.load()));
        stats.setCounter("translucent_layer_overflow_samples", double(overflowSamples.load()));
        if (passFrame) passFrame->writeTo(image, context.stats);
        return image;
    }

    bool writesPasses() const override { return true; }

private:
    struct Ray {
        glm::vec3 origin, direction, directionRight, directionDown;  ///< the sample's, and one spacing right and down
        float time;
    };

    std::vector<SteppedMesh> steppedMeshes(const Scene& scene) const {
        std::vector<SteppedMesh> meshes;
        std::uint32_t first = 0;
        for (const Mesh& mesh : scene.meshes) {
            SteppedMesh& m = meshes.emplace_back();
            m.firstTriangle = first;
            first += std::uint32_t(mesh.triangles.size());
            const bool isCurve = mesh.isCurved();
            m.numSteps = mesh.isStatic() ? 1 : isCurve ? (mesh.numKeys - 1) * m_options.curveSegments + 1 : mesh.numKeys;
            const std::size_t n = mesh.numVertices();
            for (int s = 0; s < m.numSteps; ++s) {
                if (!isCurve && !mesh.isStatic()) {
                    m.positions.insert(m.positions.end(), mesh.positions.begin() + std::ptrdiff_t(s * n),
                                       mesh.positions.begin() + std::ptrdiff_t((s + 1) * n));
                    if (mesh.hasNormals())
                        m.normals.insert(m.normals.end(), mesh.normals.begin() + std::ptrdiff_t(s * n),
                                         mesh.normals.begin() + std::ptrdiff_t((s + 1) * n));
                    continue;
                }
                const MotionWeights w = mesh.weightsAt(m.numSteps == 1 ? 0.0f : float(s) / float(m.numSteps - 1));
                for (std::uint32_t v = 0; v < n; ++v) {
                    m.positions.push_back(mesh.positionAt(v, w));
                    if (mesh.hasNormals()) m.normals.push_back(mesh.normalAt(v, w));
                }
            }
        }
        return meshes;
    }

    static SceneHandle buildScene(RTCDevice device, const Scene& scene, const std::vector<SteppedMesh>& meshes) {
        SceneHandle rtScene(rtcNewScene(device));
        if (!rtScene) return rtScene;
        rtcSetSceneFlags(rtScene.get(), RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
        for (std::size_t m = 0; m < meshes.size(); ++m) {
            const Mesh& mesh = scene.meshes[m];
            const SteppedMesh& stepped = meshes[m];
            const std::size_t n = mesh.numVertices();
            RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            if (!geom) return rtScene;
            rtcSetGeometryTimeStepCount(geom, unsigned(stepped.numSteps));
            for (int s = 0; s < stepped.numSteps; ++s) {
                auto* vertices = static_cast<float*>(
                    rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, unsigned(s), RTC_FORMAT_FLOAT3, 3 * sizeof(float), n));
                if (!vertices) break;
                for (std::size_t v = 0; v < n; ++v)
                    for (int c = 0; c < 3; ++c) vertices[3 * v + std::size_t(c)] = stepped.positions[std::size_t(s) * n + v][c];
            }
            auto* indices = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
            if (indices)
                for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
                    for (int c = 0; c < 3; ++c) indices[3 * t + std::size_t(c)] = mesh.triangles[t][c];
            rtcCommitGeometry(geom);
            rtcAttachGeometryByID(rtScene.get(), geom, unsigned(m));
            rtcReleaseGeometry(geom);
        }
        rtcCommitScene(rtScene.get());
        return rtScene;
    }

    // The radiance along one primary ray: translucent layers front to back over the first opaque
    // surface (or the background); and in w its coverage, the share the background does not get.
    // Each surface that shows goes to `passes` (when given) with its share of the ray and depth.
    glm::vec4 trace(RTCScene rtScene, const FlatGeometry& geometry, const std::vector<SteppedMesh>& meshes, const Ray& ray,
                    ShadingMode shading, std::vector<std::pair<unsigned, unsigned>>& skipped, std::int64_t& rays,
                    bool& isOverflow, exposure::PixelPasses* passes) const {
        const Scene& scene = geometry.scene();
        skipped.clear();
        glm::vec3 color(0.0f);
        float transmittance = 1.0f, from = scene.camera.zNear;
        int layers = 0;
        const int maxPasses = 4 * m_options.maxLayers + 64;
        for (int pass = 0; pass < maxPasses; ++pass) {
            SkipContext skip;
            rtcInitIntersectContext(&skip.context);
            if (!skipped.empty()) {
                skip.context.filter = skipMetTriangles;
                skip.skipped = skipped.data();
                skip.numSkipped = skipped.size();
            }
            RTCRayHit hit{};
            hit.ray.org_x = ray.origin.x, hit.ray.org_y = ray.origin.y, hit.ray.org_z = ray.origin.z;
            hit.ray.dir_x = ray.direction.x, hit.ray.dir_y = ray.direction.y, hit.ray.dir_z = ray.direction.z;
            hit.ray.tnear = from;
            hit.ray.tfar = std::numeric_limits<float>::infinity();
            hit.ray.time = ray.time;
            hit.ray.mask = ~0u;
            hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(rtScene, &skip.context, &hit);
            ++rays;
            if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return glm::vec4(color + transmittance * scene.background, 1.0f - transmittance);

            const SteppedMesh& mesh = meshes[hit.hit.geomID];
            const FlatTriangle& tri = geometry.triangles()[mesh.firstTriangle + hit.hit.primID];
            const glm::uvec3 local = scene.meshes[hit.hit.geomID].triangles[hit.hit.primID];
            const std::pair<int, float> stepAndWeight = mesh.stepAt(ray.time);
            const int step = stepAndWeight.first;
            const float u = stepAndWeight.second;
            const std::size_t n = scene.meshes[hit.hit.geomID].numVertices();
            auto at = [&](const std::vector<glm::vec3>& values, std::uint32_t v) {
                const glm::vec3 a = values[std::size_t(step) * n + v];
                return mesh.numSteps == 1 ? a : a + u * (values[std::size_t(step + 1) * n + v] - a);
            };
            const std::array<glm::vec3, 3> corners{at(mesh.positions, local.x), at(mesh.positions, local.y), at(mesh.positions, local.z)};
            std::array<glm::vec3, 3> normals{};
            if (!mesh.normals.empty()) normals = {at(mesh.normals, local.x), at(mesh.normals, local.y), at(mesh.normals, local.z)};
            const glm::vec3 faceNormal = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
            const bool isFrontFacing = glm::dot(faceNormal, ray.direction) < 0.0f;
            skipped.emplace_back(hit.hit.geomID, hit.hit.primID);
            from = hit.ray.tfar;
            if (!isFrontFacing && !tri.isDoubleSided) continue;  // culled: pass through

            const glm::vec3 bary(1.0f - hit.hit.u - hit.hit.v, hit.hit.u, hit.hit.v);
            const glm::vec3 right = baryOnPlane(corners, faceNormal, ray.origin, ray.directionRight).value_or(bary);
            const glm::vec3 down = baryOnPlane(corners, faceNormal, ray.origin, ray.directionDown).value_or(bary);
            const SurfacePoint point = geometry.surfacePoint(tri, corners, normals, bary, right, down, isFrontFacing);
            const ShadedColor shaded = shadeSurface(scene, shading, point, ray.origin);
            const bool isOpaque = !scene.materials[tri.material].isTranslucent();
            if (passes && (isOpaque || layers < m_options.maxLayers)) {
                const std::uint32_t triangle = mesh.firstTriangle + hit.hit.primID;
                const float share = transmittance * (isOpaque ? 1.0f : shaded.alpha);
                passes->add({triangle, tri.mesh, tri.material, share, hit.ray.tfar, hit.ray.tfar, hit.ray.tfar});
                passes->addColor(triangle, share * shaded.color);
            }
            if (isOpaque) return glm::vec4(color + transmittance * shaded.color, 1.0f);
            if (layers == m_options.maxLayers) {
                isOverflow = true;  // past the budget: further translucent layers are left out
                continue;
            }
            ++layers;
            color += transmittance * shaded.alpha * shaded.color;
            transmittance *= 1.0f - shaded.alpha;
            if (transmittance <= 0.0f) return glm::vec4(color, 1.0f);
        }
        isOverflow = true;
        return glm::vec4(color + transmittance * scene.background, 1.0f - transmittance);
    }

    // Barycentrics where a ray meets a triangle's plane (outside the triangle too); none past the
    // plane's horizon.
    static std::optional<glm::vec3> baryOnPlane(const std::array<glm::vec3, 3>& c, const glm::vec3& normal, const glm::vec3& origin,
                                                const glm::vec3& direction) {
        const float denominator = glm::dot(direction, normal);
        if (!(std::abs(denominator) > 0.0f)) return std::nullopt;
        const float s = glm::dot(c[0] - origin, normal) / denominator;
        if (!(s > 0.0f)) return std::nullopt;
        const glm::vec3 p = origin + s * direction;
        const float area = glm::dot(normal, normal);
        const float b1 = glm::dot(glm::cross(p - c[0], c[2] - c[0]), normal) / area;
        const float b2 = glm::dot(glm::cross(c[1] - c[0], p - c[0]), normal) / area;
        return glm::vec3(1.0f - b1 - b2, b1, b2);
    }

    Options m_options;
};

}  // namespace

std::unique_ptr<Renderer> createEmbreeRenderer(OptionMap& options) {
    Options o;
    o.samples = options.getInt("samples", o.samples, 1, 1 << 16);
    o.curveSegments = options.getInt("curve-segments", o.curveSegments, 1, 64);
    o.maxLayers = options.getInt("max-layers", o.maxLayers, 1, 1024);
    return std::make_unique<EmbreeRenderer>(o);
}

}  // namespace streak
