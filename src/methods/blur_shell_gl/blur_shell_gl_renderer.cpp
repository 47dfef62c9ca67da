#include "methods/blur_shell_gl/blur_shell_gl_renderer.h"

#include "gpu/gpu_frame.h"
#include "gpu/gpu_timer.h"
#include "gpu/instant_passes.h"
#include "scene/blur_shell.h"

#include <limits>

namespace streak {

namespace {

class BlurShellGlRenderer final : public Renderer {
public:
    BlurShellGlRenderer(const BlurShellOptions& options, bool isSorted, const gpu::TranslucentOptions& translucent)
        : m_options(options), m_isSorted(isSorted), m_translucent(translucent) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        const ShellScene shellScene = buildShellScene(scene, m_options, context.stats);
        // Hardware rasterization puts the samples at the texel centres of the sample grid.
        const gpu::GpuFrame frame(shellScene.scene, settings.width, settings.height, settings.aa, /*isGridPattern=*/true,
                                  settings.shading, context.stats);
        gpu::InstantPasses passes(frame, m_translucent);
        passes.clearSum();
        gpu::GpuTimer timer;
        {
            PhaseTimer wall(context.stats, "passes wall");
            timer.begin("passes");
            passes.draw(1.0f, m_isSorted ? std::numeric_limits<std::size_t>::max() : shellScene.firstShellTriangle());
            timer.end();
            glFinish();
        }
        gpu::checkGlError("rendering blur-shell-gl");
        timer.report(context.stats);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        Image image = gpu::readSampleGrid(passes.sum(), frame.grid, 1.0f);
        context.stats.setCounter("samples_on_grid", 1);
        passes.translucency().report(context.stats);
        context.stats.setCounter("gpu_memory_bytes", double(passes.gpuBytes()));
        return image;
    }

    std::optional<AnimationTrail> animationTrail() const override {
        return AnimationTrail{m_options.lengthSeconds, m_options.subdivisions + 1};
    }

private:
    BlurShellOptions m_options;
    bool m_isSorted;
    gpu::TranslucentOptions m_translucent;
};

}  // namespace

std::unique_ptr<Renderer> createBlurShellGlRenderer(OptionMap& options) {
    const BlurShellOptions shell = BlurShellOptions::read(options);
    const bool isSorted = BlurShellOptions::readIsSorted(options);
    return std::make_unique<BlurShellGlRenderer>(shell, isSorted, gpu::TranslucentOptions::read(options));
}

}  // namespace streak
