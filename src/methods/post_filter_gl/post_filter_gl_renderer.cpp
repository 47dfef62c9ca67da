#include "methods/post_filter_gl/post_filter_gl_renderer.h"

#include "exposure/reconstruction_filter.h"
#include "gpu/gpu_frame.h"
#include "gpu/gpu_timer.h"
#include "gpu/instant_passes.h"
#include "gpu/shader_library.h"

#include <glm/vec4.hpp>

#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace streak {

namespace {

constexpr GLuint kJitterBinding = 8;  // post_filter_gather.comp.glsl

class PostFilterGlRenderer final : public Renderer {
public:
    PostFilterGlRenderer(const exposure::ReconstructionOptions& options, const gpu::TranslucentOptions& translucent)
        : m_options(options), m_translucent(translucent) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        // Hardware rasterization puts the samples at the texel centres of the sample grid.
        const gpu::GpuFrame frame(scene, settings.width, settings.height, settings.aa, /*isGridPattern=*/true, settings.shading, context.stats);
        const gpu::SceneBuffers& buffers = frame.buffers;
        const int width = settings.width, height = settings.height, k = m_options.tile;
        const int tilesWide = (width + k - 1) / k, tilesHigh = (height + k - 1) / k;
        std::map<std::string, std::string> defines = buffers.defines();
        const gpu::GlProgram& velocity = gpu::buildProgram({{GL_VERTEX_SHADER, {"scene.glsl", "post_filter_gl.vert.glsl"}},
                                                            {GL_FRAGMENT_SHADER, {"scene.glsl", "shading.glsl", "post_filter_gl.frag.glsl"}}},
                                                           defines);
        const gpu::GlProgram& pixels = gpu::buildProgram({{GL_COMPUTE_SHADER, {"scene.glsl", "post_filter_pixels.comp.glsl"}}}, defines);
        defines["NEIGHBOR_PASS"] = "0";
        const gpu::GlProgram& tileMax = gpu::buildProgram({{GL_COMPUTE_SHADER, {"scene.glsl", "post_filter_tiles.comp.glsl"}}}, defines);
        defines["NEIGHBOR_PASS"] = "1";
        const gpu::GlProgram& neighborMax = gpu::buildProgram({{GL_COMPUTE_SHADER, {"scene.glsl", "post_filter_tiles.comp.glsl"}}}, defines);
        const gpu::GlProgram& gather = gpu::buildProgram({{GL_COMPUTE_SHADER, {"scene.glsl", "post_filter_gather.comp.glsl"}}}, defines);

        gpu::InstantPasses passes(frame, m_translucent);
        const gpu::SampleFramebuffer motion(frame.grid);
        const gpu::GlTexture pixelColor(GL_RGBA32F, width, height), pixelMotion(GL_RGBA32F, width, height);
        const gpu::GlTexture tiles(GL_RGBA32F, tilesWide, tilesHigh), neighbors(GL_RGBA32F, tilesWide, tilesHigh);
        const gpu::GlTexture filtered(GL_RGBA32F, width, height);
        std::vector<float> jitters(std::size_t(width) * std::size_t(height));
        for (std::size_t i = 0; i < jitters.size(); ++i) jitters[i] = exposure::gatherJitter(settings.seed, i);
        const gpu::GlBuffer jitterBuffer = gpu::GlBuffer::from(jitters);
        const gpu::GlVertexArray vertexArray;
        const float zero[4] = {0, 0, 0, 0};
        auto groups = [](int n) { return GLuint((n + 7) / 8); };

        gpu::GpuTimer timer;
        {
            PhaseTimer wall(context.stats, "passes wall");
            timer.begin("centre frame");
            passes.clearSum();
            passes.draw(0.5f);
            timer.begin("velocity");
            glBindFramebuffer(GL_FRAMEBUFFER, motion.framebuffer.id());
            glViewport(0, 0, frame.grid.samplesWide(), frame.grid.samplesHigh());
            glBindVertexArray(vertexArray.id());
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LESS);
            glDepthMask(GL_TRUE);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDisable(GL_BLEND);
            glDisable(GL_CULL_FACE);
            glFrontFace(GL_CW);
            glClearBufferfv(GL_COLOR, 0, zero);
            glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
            glUseProgram(velocity.id());
            buffers.bind(velocity.id());
            glDrawArrays(GL_TRIANGLES, 0, GLsizei(buffers.numTriangles() * 3));
            glMemoryBarrier(GL_ALL_BARRIER_BITS);

            timer.begin("filter");
            glUseProgram(pixels.id());
            buffers.bind(pixels.id());
            glProgramUniform1f(pixels.id(), glGetUniformLocation(pixels.id(), "u_maxRadius"), m_options.maxRadius);
            // The shutter only by its velocity scale, as post-filter.
            glProgramUniform1f(pixels.id(), glGetUniformLocation(pixels.id(), "u_velocityScale"), scene.shutter.rollingDuration);
            glBindImageTexture(0, passes.sum().id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
            glBindImageTexture(1, motion.color.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
            glBindImageTexture(2, pixelColor.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
            glBindImageTexture(3, pixelMotion.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
            glDispatchCompute(groups(width), groups(height), 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            for (const auto& [program, input, output] : {std::tuple{&tileMax, &pixelMotion, &tiles}, std::tuple{&neighborMax, &tiles, &neighbors}}) {
                glUseProgram(program->id());
                buffers.bind(program->id());
                glProgramUniform4i(program->id(), glGetUniformLocation(program->id(), "u_tiles"), tilesWide, tilesHigh, k, 0);
                glBindImageTexture(0, input->id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
                glBindImageTexture(1, output->id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
                glDispatchCompute(groups(tilesWide), groups(tilesHigh), 1);
                glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            }
            glUseProgram(gather.id());
            buffers.bind(gather.id());
            glProgramUniform4i(gather.id(), glGetUniformLocation(gather.id(), "u_gather"), k, m_options.samples, 0, 0);
            glProgramUniform1f(gather.id(), glGetUniformLocation(gather.id(), "u_softDepth"), m_options.softDepth);
            glBindImageTexture(0, pixelColor.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
            glBindImageTexture(1, pixelMotion.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
            glBindImageTexture(2, neighbors.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
            glBindImageTexture(3, filtered.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
            jitterBuffer.bindStorage(kJitterBinding);
            glDispatchCompute(groups(width), groups(height), 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
            timer.end();
            glFinish();
        }
        gpu::checkGlError("rendering post-filter-gl");
        timer.report(context.stats);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        Image image = gpu::readSampleGrid(filtered, gpu::SampleGrid{width, height, 1});
        context.stats.setCounter("samples_on_grid", 1);
        context.stats.setInfo("shutter_model", "velocity scale only");
        context.stats.setCounter("tiles", double(tilesWide * tilesHigh));
        passes.translucency().report(context.stats);
        context.stats.setCounter("gpu_memory_bytes", double(passes.gpuBytes() + frame.grid.numSamples() * 16 * 2 + std::size_t(width) * height * 16 * 3));
        return image;
    }

private:
    exposure::ReconstructionOptions m_options;
    gpu::TranslucentOptions m_translucent;
};

}  // namespace

std::unique_ptr<Renderer> createPostFilterGlRenderer(OptionMap& options) {
    const exposure::ReconstructionOptions filter = exposure::ReconstructionOptions::read(options);
    return std::make_unique<PostFilterGlRenderer>(filter, gpu::TranslucentOptions::read(options));
}

}  // namespace streak
