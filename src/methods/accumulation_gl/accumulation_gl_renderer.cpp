#include "methods/accumulation_gl/accumulation_gl_renderer.h"

#include "gpu/gpu_frame.h"
#include "gpu/gpu_timer.h"
#include "gpu/instant_passes.h"

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
        gpu::InstantPasses passes(frame, m_options.translucent);
        passes.clearSum();
        gpu::GpuTimer timer;
        {
            PhaseTimer wall(context.stats, "passes wall");  // with the GPU's wait; the CLI times "render" whole
            timer.begin("passes");
            for (int s = 0; s < m_options.samples; ++s) {
                passes.draw((float(s) + 0.5f) / float(m_options.samples));
                if (context.progress) context.progress->update(double(s + 1) / m_options.samples);
            }
            timer.end();
            glFinish();
        }
        checkGlErrorAfterRender();
        timer.report(context.stats);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        Image image = gpu::readSampleGrid(passes.sum(), frame.grid, 1.0f / float(m_options.samples));

        RenderStats& stats = context.stats;
        stats.setCounter("time_samples", m_options.samples);
        stats.setCounter("samples_on_grid", 1);  // hardware rasterization: texel centres
        passes.translucency().report(stats);
        stats.setCounter("gpu_memory_bytes", double(passes.gpuBytes()));
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
