#include "methods/accumulation_gl/accumulation_gl_renderer.h"

#include "gpu/gpu_frame.h"
#include "gpu/gpu_timer.h"
#include "exposure/instant_schedule.h"
#include "gpu/instant_passes.h"

#include <limits>

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
        const exposure::InstantSchedule schedule(scene.shutter, m_options.samples, settings.height);
        gpu::GpuTimer timer;
        {
            PhaseTimer wall(context.stats, "passes wall");  // with the GPU's wait; the CLI times "render" whole
            timer.begin("passes");
            for (int s = 0; s < schedule.numInstants(); ++s) {
                if (schedule.isUniform()) {
                    passes.draw(schedule.time(s));
                } else if (schedule.rows(s).first <= schedule.rows(s).second) {
                    const float n = float(schedule.numInstants());
                    passes.draw(schedule.time(s), std::numeric_limits<std::size_t>::max(), glm::vec2(float(s) / n, float(s + 1) / n));
                }
                if (context.progress) context.progress->update(double(s + 1) / schedule.numInstants());
            }
            timer.end();
            glFinish();
        }
        checkGlErrorAfterRender();
        timer.report(context.stats);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        Image image = gpu::readSampleGrid(passes.sum(), frame.grid, schedule.isUniform() ? 1.0f / float(m_options.samples) : 1.0f);

        RenderStats& stats = context.stats;
        stats.setCounter("time_samples", m_options.samples);
        stats.setCounter("instants", schedule.numInstants());
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
