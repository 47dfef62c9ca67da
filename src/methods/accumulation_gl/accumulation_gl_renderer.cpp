#include "methods/accumulation_gl/accumulation_gl_renderer.h"

#include "gpu/fragment_lists.h"
#include "gpu/gl_context.h"
#include "gpu/gpu_timer.h"
#include "gpu/sample_grid.h"
#include "gpu/scene_buffers.h"
#include "gpu/shader_library.h"
#include "scene/flat_geometry.h"
#include "util/error.h"

#include <algorithm>
#include <map>
#include <optional>
#include <string>

namespace streak {

namespace {

struct Options {
    int samples = 256;
    int layers = 64;
    int gpuMemoryMb = 1024;
};

constexpr std::size_t kNodeBytes = 32;  // TranslucentNode, std430

class AccumulationGlRenderer final : public Renderer {
public:
    explicit AccumulationGlRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        gpu::GlContext& gl = gpu::sharedContext();
        const FlatGeometry geometry(scene);
        const gpu::SampleGrid grid{settings.width, settings.height, settings.aa};
        std::optional<gpu::SceneBuffers> buffers;
        {
            PhaseTimer timer(context.stats, "upload");
            buffers.emplace(geometry, settings.width, settings.height, settings.aa, settings.shading);
        }
        std::map<std::string, std::string> defines = buffers->defines();
        defines["MAX_LAYERS"] = std::to_string(m_options.layers);
        defines["TRANSLUCENT_PASS"] = "0";
        const gpu::GlProgram opaque = gpu::buildProgram(
            {{GL_VERTEX_SHADER, {"scene.glsl", "accumulation_gl.vert.glsl"}},
             {GL_FRAGMENT_SHADER, {"scene.glsl", "shading.glsl", "accumulation_gl.frag.glsl"}}}, defines);
        defines["TRANSLUCENT_PASS"] = "1";
        defines["LIST_SKIP_HELPERS"] = "1";  // its fragment shader takes derivatives
        const gpu::GlProgram translucent = gpu::buildProgram(
            {{GL_VERTEX_SHADER, {"scene.glsl", "accumulation_gl.vert.glsl"}},
             {GL_FRAGMENT_SHADER, {"scene.glsl", "shading.glsl", "fragment_list.glsl", "accumulation_gl.frag.glsl"}}}, defines);
        const gpu::GlProgram compose =
            gpu::buildProgram({{GL_COMPUTE_SHADER, {"scene.glsl", "fragment_list.glsl", "accumulation_gl_compose.comp.glsl"}}}, defines);

        bool hasTranslucent = false;
        for (const FlatTriangle& tri : geometry.triangles()) hasTranslucent = hasTranslucent || scene.materials[tri.material].isTranslucent();
        // Translucent fragments of one pass: a sample holds at most `layers` that matter, and
        // the list buffer at most gpu-memory.
        const std::size_t capacity = hasTranslucent ? std::max<std::size_t>(
                                                          1, std::min(grid.numSamples() * std::size_t(m_options.layers),
                                                                      std::size_t(m_options.gpuMemoryMb) * (1u << 20) / kNodeBytes))
                                                    : 1;
        const gpu::FragmentLists lists(grid, kNodeBytes, capacity);
        const gpu::GlTexture colorTarget(GL_RGBA32F, grid.samplesWide(), grid.samplesHigh());
        const gpu::GlTexture depthTarget(GL_DEPTH_COMPONENT32F, grid.samplesWide(), grid.samplesHigh());
        const gpu::GlTexture sum(GL_RGBA32F, grid.samplesWide(), grid.samplesHigh());
        const gpu::GlFramebuffer framebuffer;
        glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, colorTarget.id(), 0);
        glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depthTarget.id(), 0);
        if (glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error("OpenGL: the accumulation-gl framebuffer is incomplete");
        const gpu::GlVertexArray vertexArray;  // empty: vertices are pulled from storage buffers
        const float zero[4] = {0, 0, 0, 0};
        glClearTexImage(sum.id(), 0, GL_RGBA, GL_FLOAT, zero);
        lists.clear();

        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
        glViewport(0, 0, grid.samplesWide(), grid.samplesHigh());
        glBindVertexArray(vertexArray.id());
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);  // single-sided triangles are culled per material in the shader
        glFrontFace(GL_CW);       // y is flipped to raster rows, which mirrors the winding
        const GLsizei numVertices = GLsizei(buffers->numTriangles() * 3);
        const GLuint groupsX = GLuint((grid.samplesWide() + 7) / 8), groupsY = GLuint((grid.samplesHigh() + 7) / 8);
        std::uint64_t overflowSamples = 0, listOverflow = 0;
        gpu::GpuTimer timer;
        {
            PhaseTimer wall(context.stats, "render");
            timer.begin("passes");
            for (int s = 0; s < m_options.samples; ++s) {
                const float t = (float(s) + 0.5f) / float(m_options.samples);
                glDepthMask(GL_TRUE);
                glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
                glClearBufferfv(GL_COLOR, 0, zero);
                glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
                glUseProgram(opaque.id());
                buffers->bind(opaque.id());
                glProgramUniform1f(opaque.id(), glGetUniformLocation(opaque.id(), "u_time"), t);
                glDrawArrays(GL_TRIANGLES, 0, numVertices);
                if (hasTranslucent) {
                    lists.clear();
                    // The translucent pass writes only its lists: no depth, no colour (its
                    // fragment shader has no output, and GL would store undefined values).
                    glDepthMask(GL_FALSE);
                    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
                    glUseProgram(translucent.id());
                    buffers->bind(translucent.id());
                    lists.bind(translucent.id(), 7, std::uint32_t(m_options.layers) * 4u);
                    glProgramUniform1f(translucent.id(), glGetUniformLocation(translucent.id(), "u_time"), t);
                    glDrawArrays(GL_TRIANGLES, 0, numVertices);
                }
                glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                                GL_ATOMIC_COUNTER_BARRIER_BIT);
                glUseProgram(compose.id());
                buffers->bind(compose.id());
                lists.bind(compose.id(), 7, std::uint32_t(m_options.layers) * 4u);
                glBindImageTexture(2, colorTarget.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
                glBindImageTexture(3, sum.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
                glDispatchCompute(groupsX, groupsY, 1);
                glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
                if (hasTranslucent) {
                    const gpu::FragmentLists::Counts counts = lists.counts();
                    overflowSamples += counts.methodCounter;
                    listOverflow += counts.asked > capacity ? counts.asked - capacity : 0;
                    listOverflow += counts.budgetRefused;
                }
                if (context.progress) context.progress->update(double(s + 1) / m_options.samples);
            }
            timer.end();
            glFinish();
        }
        checkGlErrorAfterRender();
        timer.report(context.stats);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        Image image = gpu::readSampleGrid(sum, grid, 1.0f / float(m_options.samples));

        RenderStats& stats = context.stats;
        stats.setInfo("gl_renderer", gl.renderer());
        stats.setInfo("gl_version", gl.version());
        stats.setCounter("time_samples", m_options.samples);
        stats.setCounter("translucent_layer_overflow_samples", double(overflowSamples));
        stats.setCounter("translucent_list_overflow_fragments", double(listOverflow));
        stats.setCounter("gpu_memory_bytes", double(buffers->uploadBytes() + lists.bytes() + grid.numSamples() * 16 * 3));
        return image;
    }

private:
    static void checkGlErrorAfterRender() { gpu::checkGlError("rendering accumulation-gl"); }

    Options m_options;
};

}  // namespace

std::unique_ptr<Renderer> createAccumulationGlRenderer(OptionMap& options) {
    Options o;
    o.samples = options.getInt("samples", 256, 1, 1 << 20);
    o.layers = options.getInt("layers", 64, 1, 256);
    o.gpuMemoryMb = options.getInt("gpu-memory", 1024, 16, 1 << 20);
    return std::make_unique<AccumulationGlRenderer>(o);
}

}  // namespace streak
