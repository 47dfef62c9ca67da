#include "methods/motion_path_gl/motion_path_gl_renderer.h"

#include "exposure/pixel_shading.h"
#include "exposure/sample_passes.h"
#include "exposure/segmented_geometry.h"
#include "exposure/span_shading.h"
#include "gpu/fragment_lists.h"
#include "gpu/gl_context.h"
#include "gpu/gpu_timer.h"
#include "gpu/sample_grid.h"
#include "gpu/scene_buffers.h"
#include "gpu/shader_library.h"
#include "scene/flat_geometry.h"
#include "util/error.h"

#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <string>

namespace streak {

namespace {

struct Options {
    int maxFragments = 150;
    int maxIntervals = 90;
    int maskBits = 128;
    bool exactWeights = true;  ///< opaque pieces measured in time (motion-path's default), not in mask slices
    exposure::SpanShadingSettings spanShading;  ///< texture-samples, taps-per-texel, texture-filter (the shaders' uniforms)
    exposure::PixelShadingOptions shading;      ///< shading=pixel|sample, shading-cells, shading-filter (exposure/pixel_shading.h)
    bool sortIntervals = true;
    int curveSegments = exposure::SegmentedGeometry::kAutoCurveSegments;
    int gpuMemoryMb = 1024;
};

constexpr std::size_t kNodeBytes = 24;     // PathNode, std430
constexpr std::size_t kInitialNodesPerSample = 4;

// The resolve pass's counters (ResolveCounterBuffer).
struct ResolveCounters {
    std::uint32_t intervalOverflowSamples, splits, cycles, shadedSpans, intervals, maxIntervals, shownOverflowSamples;
    std::uint32_t piecesWritten, pieceOverflowSamples;
};

// The pixel pass's counters (PixelShadingCounterBuffer).
struct PixelShadingCounters {
    std::uint32_t pixels, pieces, clusters, visibleTriangles, overflowPixels, maxClusters, stillSampleLookups;
};
// The clusters of a pixel one dispatch of the pixel pass shades (see its shader: llvmpipe's limit
// on an invocation's loop iterations).
constexpr int kClustersPerDispatch = 8;

// At shading=pixel the resolve leaves each sample's visible opaque pieces in a pool for the pixel
// pass: a run (first, count) a sample and kPieceBytes a piece (PieceNode, std430). The pool takes
// up to kPiecesPerSample a sample, within a quarter of the GPU memory budget; a sample it cannot
// hold shades its own pieces (piece_overflow_samples).
constexpr std::size_t kPieceBytes = 16, kSampleRunBytes = 8, kPiecesPerSample = 4;
// The most pieces the pixel pass sorts and clusters in one pixel (its local arrays); past them a
// piece is shaded at its sample (piece_overflow_pixels).
int maxPixelPieces(int aa) { return std::clamp(8 * aa * aa, 64, 512); }
// The --aa the pixel pass's arrays are sized for: one build serves --aa 1-4 and one 5-8 (each
// build took llvmpipe seconds, and a change of --aa rebuilt it).
int pixelPassAa(int aa) { return aa <= 4 ? 4 : aa <= 8 ? 8 : aa; }

// What shows in a sample, for the passes (the resolve's ShownRecord, std430): kMaxShown a sample.
struct ShownRecord {
    std::uint32_t triangle;  ///< ~0u: none
    float share, depth, nearest, farthest;
    float r, g, b;
};
static_assert(sizeof(ShownRecord) == 32);
constexpr int kMaxShown = 8;

// The passes from the resolve's records: each pixel's samples' surfaces into PixelPasses.
void writeShownPasses(const Scene& scene, const FlatGeometry& geometry, const RenderSettings& settings, const gpu::SampleGrid& grid,
                      const std::vector<ShownRecord>& records, Image& image, RenderStats& stats) {
    exposure::PassFrame frame(scene, settings.passes, settings.width, settings.height);
    exposure::PixelPasses pixel;
    const float sampleWeight = 1.0f / float(grid.aa * grid.aa);
    for (int py = 0; py < grid.height; ++py)
        for (int px = 0; px < grid.width; ++px) {
            pixel.begin(frame);
            for (int j = 0; j < grid.aa; ++j)
                for (int i = 0; i < grid.aa; ++i) {
                    const std::size_t sample = std::size_t(py * grid.aa + j) * std::size_t(grid.samplesWide()) + std::size_t(px * grid.aa + i);
                    for (int k = 0; k < kMaxShown; ++k) {
                        const ShownRecord& r = records[sample * kMaxShown + std::size_t(k)];
                        if (r.triangle >= geometry.triangles().size()) break;
                        const FlatTriangle& t = geometry.triangles()[r.triangle];
                        pixel.add({r.triangle, t.mesh, t.material, r.share, r.depth, r.nearest, r.farthest});
                        pixel.addColor(r.triangle, glm::vec3(r.r, r.g, r.b));
                    }
                }
            pixel.finish(frame, px, py, sampleWeight);
        }
    frame.writeTo(image, stats);
}

void setInt(GLuint program, const char* name, int value) { glProgramUniform1i(program, glGetUniformLocation(program, name), value); }

class MotionPathGlRenderer final : public Renderer {
public:
    explicit MotionPathGlRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        gpu::GlContext& gl = gpu::sharedContext();
        const FlatGeometry geometry(scene);
        const gpu::SampleGrid grid{settings.width, settings.height, settings.aa};
        const exposure::SegmentedGeometry::SegmentPlan plan =
            exposure::SegmentedGeometry::plan(scene, m_options.curveSegments, raster::Viewport{settings.width, settings.height});
        const int numSegments = plan.numSegments;
        std::optional<gpu::SceneBuffers> buffers;
        {
            PhaseTimer timer(context.stats, "upload");
            buffers.emplace(geometry, settings.width, settings.height, settings.aa, settings.isGridPattern, settings.shading);
        }
        std::map<std::string, std::string> defines = buffers->defines();
        defines["MAX_INTERVALS"] = std::to_string(m_options.maxIntervals);
        defines["MAX_SHOWN"] = std::to_string(kMaxShown);
        const gpu::GlProgram& paths = gpu::buildProgram(
            {{GL_VERTEX_SHADER, {"scene.glsl", "motion_path_gl.vert.glsl"}},
             {GL_GEOMETRY_SHADER, {"scene.glsl", "motion_path_gl.geom.glsl"}},
             {GL_FRAGMENT_SHADER, {"scene.glsl", "fragment_list.glsl", "moving_triangle.glsl", "motion_path_gl.frag.glsl"}}},
            defines);
        const gpu::GlProgram& resolve = gpu::buildProgram(
            {{GL_COMPUTE_SHADER, {"scene.glsl", "shading.glsl", "fragment_list.glsl", "moving_triangle.glsl", "depth_time.glsl",
                                  "span_shading.glsl", "motion_path_gl_resolve.comp.glsl"}}},
            defines);
        for (GLuint program : {paths.id(), resolve.id()}) setInt(program, "u_numSegments", numSegments);
        setInt(resolve.id(), "u_maskBits", m_options.maskBits);
        setInt(resolve.id(), "u_sortIntervals", m_options.sortIntervals ? 1 : 0);
        setInt(resolve.id(), "u_exactWeights", m_options.exactWeights ? 1 : 0);
        setInt(resolve.id(), "u_textureSamples", m_options.spanShading.maxTextureTaps);
        glProgramUniform1f(resolve.id(), glGetUniformLocation(resolve.id(), "u_tapsPerTexel"), m_options.spanShading.tapsPerTexel);
        setInt(resolve.id(), "u_sweptTexture", m_options.spanShading.textureFilter == exposure::SpanTextureFilter::Swept ? 1 : 0);
        // The passes' records (a token buffer without them), within the GPU memory budget.
        const bool writesSurfaces = settings.passes.any();
        const std::size_t shownBytes = writesSurfaces ? grid.numSamples() * kMaxShown * sizeof(ShownRecord) : 16;
        if (shownBytes > std::size_t(m_options.gpuMemoryMb) * (std::size_t(1) << 20))
            throw Error("method 'motion-path-gl': the passes need " + std::to_string(shownBytes >> 20) + " MB of GPU memory (" +
                        std::to_string(kMaxShown * sizeof(ShownRecord)) + " bytes a sample), past --gpu-memory " + std::to_string(m_options.gpuMemoryMb));
        const gpu::GlBuffer shownBuffer(shownBytes);
        const std::uint32_t none = ~0u;
        glClearNamedBufferData(shownBuffer.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
        setInt(resolve.id(), "u_writeSurfaces", writesSurfaces ? 1 : 0);

        // The piece pool of shading=pixel, and the pass that shades a pixel's samples together.
        const std::size_t budgetBytes = std::size_t(m_options.gpuMemoryMb) * (std::size_t(1) << 20);
        const exposure::PixelShadingOptions shading = m_options.shading.forMode(settings.shading);
        const bool perPixel = shading.rate == exposure::ShadingRate::Pixel &&
                              grid.numSamples() * kSampleRunBytes + shownBytes < budgetBytes / 4;
        const std::size_t pieceCapacity =
            perPixel ? std::min(grid.numSamples() * kPiecesPerSample, (budgetBytes / 4 - shownBytes - grid.numSamples() * kSampleRunBytes) / kPieceBytes) : 0;
        const gpu::GlBuffer pieceBuffer(std::max<std::size_t>(pieceCapacity * kPieceBytes, 16));
        const gpu::GlBuffer sampleRuns(perPixel ? grid.numSamples() * kSampleRunBytes : 16);
        const std::uint32_t zeroRun = 0;
        glClearNamedBufferData(sampleRuns.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zeroRun);
        setInt(resolve.id(), "u_shadingPerPixel", perPixel ? 1 : 0);
        glProgramUniform1ui(resolve.id(), glGetUniformLocation(resolve.id(), "u_pieceCapacity"), GLuint(pieceCapacity));
        const int cells = shading.cellsFor(grid.aa);
        const gpu::GlProgram* pixelShading = nullptr;
        if (perPixel) {
            std::map<std::string, std::string> pixelDefines = defines;
            pixelDefines.erase("MAX_INTERVALS");  // the resolve's
            const int arrayAa = pixelPassAa(grid.aa);
            pixelDefines["MAX_PIXEL_PIECES"] = std::to_string(maxPixelPieces(arrayAa));
            pixelDefines["MAX_PIXEL_SAMPLES"] = std::to_string(arrayAa * arrayAa);
            pixelShading = &gpu::buildProgram({{GL_COMPUTE_SHADER, {"scene.glsl", "shading.glsl", "moving_triangle.glsl", "span_shading.glsl",
                                                                     "motion_path_gl_pixel_shading.comp.glsl"}}},
                                              pixelDefines);
            const GLuint id = pixelShading->id();
            setInt(id, "u_numSegments", numSegments);
            setInt(id, "u_textureSamples", m_options.spanShading.maxTextureTaps);
            glProgramUniform1f(id, glGetUniformLocation(id, "u_tapsPerTexel"), m_options.spanShading.tapsPerTexel);
            setInt(id, "u_sweptTexture", m_options.spanShading.textureFilter == exposure::SpanTextureFilter::Swept ? 1 : 0);
            setInt(id, "u_shadingCells", cells);
            setInt(id, "u_maxPixelPieces", maxPixelPieces(grid.aa));
            setInt(id, "u_boxFilter", shading.boxFilter ? 1 : 0);
            setInt(id, "u_writeSurfaces", writesSurfaces ? 1 : 0);
        }

        const gpu::GlVertexArray vertexArray;  // empty: vertices are pulled from storage buffers
        const gpu::GlFramebuffer framebuffer;  // no attachments: pass 1 writes only its lists
        glNamedFramebufferParameteri(framebuffer.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, grid.samplesWide());
        glNamedFramebufferParameteri(framebuffer.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, grid.samplesHigh());
        const gpu::GlTexture output(GL_RGBA32F, grid.samplesWide(), grid.samplesHigh());
        const GLsizei numVertices = GLsizei(buffers->numTriangles() * 3);

        // Pass 1, again with a larger buffer while it overflows (see the header).
        // The lists get what the passes' records leave of the GPU memory budget.
        const std::size_t usedBytes = shownBytes + (perPixel ? grid.numSamples() * kSampleRunBytes + pieceCapacity * kPieceBytes : 0);
        const std::size_t capNodes = std::max<std::size_t>(1, (budgetBytes - std::min(budgetBytes, usedBytes)) / kNodeBytes);
        std::size_t capacity = std::min(capNodes, std::max<std::size_t>(1024, grid.numSamples() * kInitialNodesPerSample));
        std::uint32_t sampleBudget = std::uint32_t(m_options.maxFragments);
        std::optional<gpu::FragmentLists> lists;
        gpu::FragmentLists::Counts counts;
        gpu::GpuTimer timer;
        int renders = 0;
        {
            PhaseTimer wall(context.stats, "passes wall");  // with the GPU's wait; the CLI times "render" whole
            glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
            glViewport(0, 0, grid.samplesWide(), grid.samplesHigh());
            glBindVertexArray(vertexArray.id());
            glDisable(GL_DEPTH_TEST);
            glDisable(GL_CULL_FACE);
            for (;;) {
                lists.emplace(grid, kNodeBytes, capacity);
                lists->clear();
                glUseProgram(paths.id());
                buffers->bind(paths.id());
                lists->bind(paths.id(), 7, sampleBudget);
                timer.begin("rasterize paths");
                for (int k = 0; k < numSegments; ++k) {
                    setInt(paths.id(), "u_segment", k);
                    glDrawArrays(GL_TRIANGLES, 0, numVertices);
                }
                timer.end();
                ++renders;
                counts = lists->counts();
                if (!counts.isOverflowing(capacity)) break;
                if (counts.asked <= capNodes) {
                    capacity = std::min<std::size_t>(capNodes, counts.asked + counts.asked / 4);
                } else {
                    // Past the cap: a per-sample budget that the buffer always holds.
                    capacity = capNodes;
                    sampleBudget = std::uint32_t(std::max<std::size_t>(1, std::min<std::size_t>(sampleBudget, capNodes / grid.numSamples())));
                }
            }

            const ResolveCounters zero{};
            const gpu::GlBuffer resolveCounters(sizeof zero, &zero);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
            glUseProgram(resolve.id());
            buffers->bind(resolve.id());
            lists->bind(resolve.id(), 7, sampleBudget);
            resolveCounters.bindStorage(9);
            shownBuffer.bindStorage(10);
            pieceBuffer.bindStorage(11);
            sampleRuns.bindStorage(12);
            glBindImageTexture(2, output.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
            timer.begin("resolve");
            glDispatchCompute(GLuint((grid.samplesWide() + 7) / 8), GLuint((grid.samplesHigh() + 7) / 8), 1);
            timer.end();
            m_pixelCounters = {};
            m_pixelDispatches = 1;
            const gpu::GlBuffer pixelCounters(sizeof m_pixelCounters, &m_pixelCounters);
            if (pixelShading) {
                glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
                glUseProgram(pixelShading->id());
                buffers->bind(pixelShading->id());
                pieceBuffer.bindStorage(11);
                sampleRuns.bindStorage(12);
                shownBuffer.bindStorage(10);
                pixelCounters.bindStorage(13);
                glBindImageTexture(2, output.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
                setInt(pixelShading->id(), "u_clusterCount", kClustersPerDispatch);
                timer.begin("pixel shading");
                for (int first = 0;; first += kClustersPerDispatch) {
                    setInt(pixelShading->id(), "u_firstCluster", first);
                    glDispatchCompute(GLuint((grid.width + 7) / 8), GLuint((grid.height + 7) / 8), 1);
                    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
                    if (first == 0) pixelCounters.download(&m_pixelCounters, sizeof m_pixelCounters);
                    if (first + kClustersPerDispatch >= int(m_pixelCounters.maxClusters)) break;
                    ++m_pixelDispatches;
                }
                timer.end();
            }
            glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
            glFinish();
            resolveCounters.download(&m_counters, sizeof m_counters);
            if (pixelShading) pixelCounters.download(&m_pixelCounters, sizeof m_pixelCounters);
        }
        gpu::checkGlError("rendering motion-path-gl");
        timer.report(context.stats);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        Image image = gpu::readSampleGrid(output, grid);
        if (writesSurfaces) {
            std::vector<ShownRecord> records(grid.numSamples() * kMaxShown);
            shownBuffer.download(records.data(), records.size() * sizeof(ShownRecord));
            gpu::checkGlError("reading motion-path-gl's passes back");
            writeShownPasses(scene, geometry, settings, grid, records, image, context.stats);
            context.stats.setCounter("shown_overflow_samples", double(m_counters.shownOverflowSamples));
        }
        if (context.progress) context.progress->update(1.0);

        const double numSamples = double(grid.numSamples());
        RenderStats& stats = context.stats;
        stats.setInfo("gl_renderer", gl.renderer());
        stats.setInfo("gl_version", gl.version());
        stats.setCounter("segments_per_triangle", numSegments);
        stats.setCounter("path_renders", renders);
        stats.setCounter("list_capacity_nodes", double(capacity));
        stats.setCounter("list_bytes", double(lists->bytes()));
        stats.setCounter("fragments", double(counts.asked));
        stats.setCounter("fragments_per_sample_mean", double(counts.asked) / numSamples);
        stats.setCounter("fragment_overflow_spans", double(counts.budgetRefused));
        stats.setCounter("sample_budget", sampleBudget);
        stats.setCounter("backface_intervals_culled", double(counts.methodCounter));
        stats.setCounter("intervals", double(m_counters.intervals));
        stats.setCounter("intervals_per_sample_mean", double(m_counters.intervals) / numSamples);
        stats.setCounter("intervals_per_sample_max", double(m_counters.maxIntervals));
        stats.setCounter("interval_overflow_samples", double(m_counters.intervalOverflowSamples));
        stats.setCounter("interval_splits", double(m_counters.splits));
        stats.setCounter("sort_cycles", double(m_counters.cycles));
        if (perPixel) {
            // The spans shaded: the pixel pass's clusters and what samples shaded alone on overflow.
            exposure::PixelShadingCounters shaded;
            shaded.pixels = m_pixelCounters.pixels;
            shaded.pieces = m_pixelCounters.pieces;
            shaded.shadedSpans = std::int64_t(m_pixelCounters.clusters) + m_counters.shadedSpans;
            shaded.visibleTriangles = m_pixelCounters.visibleTriangles;
            shaded.stillSampleLookups = m_pixelCounters.stillSampleLookups;
            exposure::recordPixelShadingStats(stats, shaded, double(grid.width) * grid.height, shading);
            stats.setCounter("piece_capacity", double(pieceCapacity));
            stats.setCounter("piece_overflow_samples", double(m_counters.pieceOverflowSamples));
            stats.setCounter("piece_overflow_pixels", double(m_pixelCounters.overflowPixels));
            stats.setCounter("pixel_shading_dispatches", m_pixelDispatches);
        } else {
            stats.setCounter("shading_per_pixel", 0);
            stats.setCounter("shaded_spans", double(m_counters.shadedSpans));
        }
        stats.setCounter("max_fragments", m_options.maxFragments);
        stats.setCounter("max_intervals", m_options.maxIntervals);
        stats.setCounter("mask_bits", m_options.maskBits);
        stats.setCounter("exact_weights", m_options.exactWeights ? 1 : 0);
        exposure::recordSpanShadingSettings(stats, m_options.spanShading);
        exposure::recordSegmentPlan(stats, plan);
        stats.setCounter("sort_enabled", m_options.sortIntervals ? 1 : 0);
        return image;
    }

    // Depth, Cryptomatte and deep from the resolve's record of what shows in each sample.
    bool writesPasses() const override { return true; }

private:
    Options m_options;
    ResolveCounters m_counters{};
    PixelShadingCounters m_pixelCounters{};
    int m_pixelDispatches = 0;
};

}  // namespace

std::unique_ptr<Renderer> createMotionPathGlRenderer(OptionMap& options) {
    Options o;
    o.maxFragments = options.getInt("max-fragments", 150, 2, 1 << 16);
    o.maxIntervals = options.getInt("max-intervals", 90, 1, 512);
    o.maskBits = options.getInt("mask-bits", 128, 32, 256);
    if (o.maskBits != 32 && o.maskBits != 64 && o.maskBits != 128 && o.maskBits != 256)
        throw Error("method 'motion-path-gl': mask-bits must be 32, 64, 128 or 256, got " + std::to_string(o.maskBits));
    o.exactWeights = options.getInt("exact-weights", 1, 0, 1) != 0;
    o.spanShading = exposure::spanShadingSettings(options, "motion-path-gl");
    o.shading = exposure::pixelShadingOptions(options, "motion-path-gl");
    o.sortIntervals = options.getInt("sort", 1, 0, 1) != 0;
    o.curveSegments = options.getInt("curve-segments", o.curveSegments, 0, exposure::SegmentedGeometry::kMaxCurveSegments);
    o.gpuMemoryMb = options.getInt("gpu-memory", 1024, 1, 1 << 20);
    return std::make_unique<MotionPathGlRenderer>(o);
}

}  // namespace streak
