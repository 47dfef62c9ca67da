#include "methods/accumulation_gl/accumulation_gl_renderer.h"

#include "gpu/gpu_frame.h"
#include "gpu/gpu_timer.h"
#include "gpu/shader_library.h"
#include "gpu/translucent_resolve.h"

#include <map>
#include <string>

namespace streak {

namespace {

struct Options {
    int samples = 256;
    gpu::TranslucentOptions translucent;
};

class AccumulationGlRenderer final : public Renderer {
public:
    explicit AccumulationGlRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        // Hardware rasterization puts the samples at the texel centres of the sample grid: the
        // regular grid, whatever settings.isGridPattern says (counted below).
        const gpu::GpuFrame frame(scene, settings.width, settings.height, settings.aa, /*isGridPattern=*/true, settings.shading, context.stats);
        const gpu::SampleGrid& grid = frame.grid;
        const gpu::SceneBuffers& buffers = frame.buffers;
        std::map<std::string, std::string> defines = buffers.defines();
        defines["TRANSLUCENT_PASS"] = "0";
        const gpu::GlProgram& opaque = gpu::buildProgram(
            {{GL_VERTEX_SHADER, {"scene.glsl", "accumulation_gl.vert.glsl"}},
             {GL_FRAGMENT_SHADER, {"scene.glsl", "shading.glsl", "accumulation_gl.frag.glsl"}}}, defines);
        defines["TRANSLUCENT_PASS"] = "1";
        defines["LIST_SKIP_HELPERS"] = "1";  // its fragment shader takes derivatives
        const gpu::GlProgram& translucent = gpu::buildProgram(
            {{GL_VERTEX_SHADER, {"scene.glsl", "accumulation_gl.vert.glsl"}},
             {GL_FRAGMENT_SHADER,
              {"scene.glsl", "shading.glsl", "fragment_list.glsl", "translucent_node.glsl", "accumulation_gl.frag.glsl"}}},
            defines);

        gpu::TranslucentResolve translucency(grid, buffers, frame.geometry, m_options.translucent);
        const gpu::SampleFramebuffer target(grid);
        const gpu::GlTexture sum(GL_RGBA32F, grid.samplesWide(), grid.samplesHigh());
        const gpu::GlVertexArray vertexArray;  // empty: vertices are pulled from storage buffers
        const float zero[4] = {0, 0, 0, 0};
        glClearTexImage(sum.id(), 0, GL_RGBA, GL_FLOAT, zero);

        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
        glViewport(0, 0, grid.samplesWide(), grid.samplesHigh());
        glBindVertexArray(vertexArray.id());
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);  // single-sided triangles are culled per material in the shader
        glFrontFace(GL_CW);       // y is flipped to raster rows, which mirrors the winding
        const GLsizei numVertices = GLsizei(buffers.numTriangles() * 3);
        gpu::GpuTimer timer;
        {
            PhaseTimer wall(context.stats, "passes wall");  // with the GPU's wait; the CLI times "render" whole
            timer.begin("passes");
            for (int s = 0; s < m_options.samples; ++s) {
                const float t = (float(s) + 0.5f) / float(m_options.samples);
                glDepthMask(GL_TRUE);
                glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
                glClearBufferfv(GL_COLOR, 0, zero);
                glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
                glUseProgram(opaque.id());
                buffers.bind(opaque.id());
                glProgramUniform1f(opaque.id(), glGetUniformLocation(opaque.id(), "u_time"), t);
                glDrawArrays(GL_TRIANGLES, 0, numVertices);
                if (translucency.hasTranslucent()) {
                    translucency.clear();
                    // The translucent pass writes only its lists: no depth, no colour (its
                    // fragment shader has no output, and GL would store undefined values).
                    glDepthMask(GL_FALSE);
                    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
                    glUseProgram(translucent.id());
                    buffers.bind(translucent.id());
                    translucency.bindForAppending(translucent.id());
                    glProgramUniform1f(translucent.id(), glGetUniformLocation(translucent.id(), "u_time"), t);
                    glDrawArrays(GL_TRIANGLES, 0, numVertices);
                }
                translucency.resolve(target.color, sum);
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
        stats.setCounter("time_samples", m_options.samples);
        stats.setCounter("samples_on_grid", 1);  // hardware rasterization: texel centres
        translucency.report(stats);
        stats.setCounter("gpu_memory_bytes", double(buffers.uploadBytes() + translucency.bytes() + grid.numSamples() * 16 * 3));
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
    o.translucent = gpu::TranslucentOptions::read(options);
    return std::make_unique<AccumulationGlRenderer>(o);
}

}  // namespace streak
