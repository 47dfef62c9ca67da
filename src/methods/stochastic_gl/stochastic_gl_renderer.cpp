#include "methods/stochastic_gl/stochastic_gl_renderer.h"

#include "gpu/gpu_frame.h"
#include "gpu/gpu_timer.h"
#include "gpu/shader_library.h"
#include "gpu/translucent_resolve.h"
#include "util/error.h"
#include "util/random.h"

#include <glm/gtc/type_ptr.hpp>
#include <tbb/parallel_for.h>

#include <map>
#include <string>
#include <vector>

namespace streak {

namespace {

struct Options {
    int samples = 8;
    gpu::TranslucentOptions translucent;
};

// The stochastic-gl program of one pass: bounds per corner, a quad per triangle, the test per sample.
const gpu::GlProgram& buildPassProgram(std::map<std::string, std::string> defines, bool isTranslucentPass) {
    defines["TRANSLUCENT_PASS"] = isTranslucentPass ? "1" : "0";
    return gpu::buildProgram({{GL_VERTEX_SHADER, {"scene.glsl", "raster.glsl", "stochastic_gl_clip.glsl", "stochastic_gl.vert.glsl"}},
                              {GL_GEOMETRY_SHADER, {"scene.glsl", "shading.glsl", "stochastic_gl.geom.glsl"}},
                              {GL_FRAGMENT_SHADER,
                               {"scene.glsl", "shading.glsl", "raster.glsl", "stochastic_gl_clip.glsl", "fragment_list.glsl",
                                "translucent_node.glsl", "stochastic_gl.frag.glsl"}}},
                             defines);
}

// Every sample's time in `stratum`, one float per sample texel (rows top first), stratified in its
// row's exposure of the shutter as stochastic's are.
void fillSampleTimes(const gpu::SampleGrid& grid, const Shutter& shutter, std::uint64_t seed, int stratum, int numStrata,
                     std::vector<float>& times) {
    const int n = grid.aa, wide = grid.samplesWide();
    times.resize(grid.numSamples());
    tbb::parallel_for(0, grid.samplesHigh(), [&](int y) {
        const int py = y / n, j = y % n;
        const ShutterWindow window = shutter.rowWindow(py, grid.height);
        for (int x = 0; x < wide; ++x) {
            const int px = x / n, i = x % n;
            const std::uint64_t pixel = std::uint64_t(py) * std::uint64_t(grid.width) + std::uint64_t(px);
            times[std::size_t(y) * wide + x] = window.timeAt(stratifiedSampleTime(seed, pixel, j * n + i, stratum, numStrata));
        }
    });
}

class StochasticGlRenderer final : public Renderer {
public:
    explicit StochasticGlRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        const gpu::GpuFrame frame(scene, settings.width, settings.height, settings.aa, settings.isGridPattern, settings.shading, context.stats);
        const gpu::SampleGrid& grid = frame.grid;
        const gpu::SceneBuffers& buffers = frame.buffers;
        const gpu::GlProgram& opaque = buildPassProgram(buffers.defines(), false);
        const gpu::GlProgram& translucent = buildPassProgram(buffers.defines(), true);
        gpu::TranslucentResolve translucency(grid, buffers, frame.geometry, m_options.translucent);

        const gpu::SampleFramebuffer opaqueTarget(grid);  // rgb and 1/w of the nearest opaque hit, its depth
        const gpu::GlTexture sum(GL_RGBA32F, grid.samplesWide(), grid.samplesHigh());
        const gpu::GlTexture sampleTimes(GL_R32F, grid.samplesWide(), grid.samplesHigh());
        // The translucent pass writes only its lists and reads the opaque hits as an image, so it
        // draws into no attachment (the colour target bound both ways would be a feedback loop).
        const gpu::GlFramebuffer listFramebuffer;
        glNamedFramebufferParameteri(listFramebuffer.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, grid.samplesWide());
        glNamedFramebufferParameteri(listFramebuffer.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, grid.samplesHigh());
        if (glCheckNamedFramebufferStatus(listFramebuffer.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw RenderFailure("OpenGL: the stochastic-gl list framebuffer is incomplete");
        const gpu::GlVertexArray vertexArray;  // empty: vertices are pulled from storage buffers
        const float zero[4] = {0, 0, 0, 0};
        glClearTexImage(sum.id(), 0, GL_RGBA, GL_FLOAT, zero);

        glViewport(0, 0, grid.samplesWide(), grid.samplesHigh());
        glBindVertexArray(vertexArray.id());
        glDisable(GL_CULL_FACE);  // bounding quads face either way; culling is per material in the test
        glDepthFunc(GL_LESS);     // strictly nearer: ties keep the first (lowest-index) triangle, as on the CPU
        const GLsizei numVertices = GLsizei(buffers.numTriangles() * 3);
        const glm::mat4 staticClipFromWorld = scene.camera.clipFromWorld(0.0f, float(settings.width) / float(settings.height));
        auto drawStratum = [&](const gpu::GlProgram& program, float t0, float t1) {
            glUseProgram(program.id());
            buffers.bind(program.id());
            glProgramUniformMatrix4fv(program.id(), glGetUniformLocation(program.id(), "u_staticClipFromWorld"), 1, GL_FALSE,
                                      glm::value_ptr(staticClipFromWorld));
            glBindImageTexture(4, sampleTimes.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
            glProgramUniform2f(program.id(), glGetUniformLocation(program.id(), "u_stratum"), t0, t1);
            glDrawArrays(GL_TRIANGLES, 0, numVertices);
        };

        std::vector<float> times;
        gpu::GpuTimer timer;
        {
            PhaseTimer wall(context.stats, "passes wall");  // with the GPU's wait; the CLI times "render" whole
            for (int j = 0; j < m_options.samples; ++j) {
                {
                    PhaseTimer timesTimer(context.stats, "sample times");
                    fillSampleTimes(grid, scene.shutter, settings.seed, j, m_options.samples, times);
                    glTextureSubImage2D(sampleTimes.id(), 0, 0, 0, grid.samplesWide(), grid.samplesHigh(), GL_RED, GL_FLOAT,
                                        times.data());
                }
                // The stratum's times in every row, top row's window to bottom row's (as stochastic).
                const float t0 = scene.shutter.rowWindow(0, settings.height).timeAt(float(j) / float(m_options.samples));
                const float t1 = scene.shutter.rowWindow(settings.height - 1, settings.height).timeAt(float(j + 1) / float(m_options.samples));
                timer.begin("opaque");
                glBindFramebuffer(GL_FRAMEBUFFER, opaqueTarget.framebuffer.id());
                glEnable(GL_DEPTH_TEST);
                glDepthMask(GL_TRUE);
                glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);  // another GL method may have left it off
                glClearBufferfv(GL_COLOR, 0, zero);
                glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
                drawStratum(opaque, t0, t1);
                if (translucency.hasTranslucent()) {
                    timer.begin("translucent");
                    translucency.clear();
                    glBindFramebuffer(GL_FRAMEBUFFER, listFramebuffer.id());
                    glDisable(GL_DEPTH_TEST);  // the shader compares with the opaque hit itself
                    translucency.bindForAppending(translucent.id());
                    glBindImageTexture(2, opaqueTarget.color.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
                    drawStratum(translucent, t0, t1);
                }
                timer.begin("resolve");
                translucency.resolve(opaqueTarget.color, sum);
                timer.end();
                if (context.progress) context.progress->update(double(j + 1) / m_options.samples);
            }
            glFinish();
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        gpu::checkGlError("rendering stochastic-gl");
        timer.report(context.stats);
        Image image = gpu::readSampleGrid(sum, grid, 1.0f / float(m_options.samples));

        RenderStats& stats = context.stats;
        stats.setCounter("time_samples_per_position", m_options.samples);
        stats.setCounter("samples_per_pixel", double(m_options.samples) * settings.aa * settings.aa);
        translucency.report(stats);
        const std::size_t targetBytes = grid.numSamples() * (16 + 16 + 4 + 4);  // colour, sum, depth, times
        stats.setCounter("gpu_memory_bytes", double(buffers.uploadBytes() + translucency.bytes() + targetBytes));
        return image;
    }

private:
    Options m_options;
};

}  // namespace

std::unique_ptr<Renderer> createStochasticGlRenderer(OptionMap& options) {
    Options o;
    o.samples = options.getInt("samples", 8, 1, 1 << 20);
    o.translucent = gpu::TranslucentOptions::read(options);
    return std::make_unique<StochasticGlRenderer>(o);
}

}  // namespace streak
