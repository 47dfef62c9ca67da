// The GLSL twin of span shading (span_shading.glsl) against exposure::shadeTriangleSpan: the
// same mean colour for the spans a built-in scene's samples really see, textured and lit, at one
// sample and at the sites a pixel's shared shading takes (held to the triangle, wider, a box).

#include "exposure/segmented_geometry.h"
#include "exposure/triangle_surface_point.h"
#include "gpu/gpu_frame.h"
#include "gpu/shader_library.h"
#include "raster/moving_triangle.h"
#include "raster/sample_pattern.h"
#include "scene/builtin_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

namespace streak {
namespace {

// std430 twin of span_shading_probe.comp.glsl's ShadingProbe.
struct ShadingProbe {
    glm::dvec2 ndc;
    float t0, t1;
    std::uint32_t triangle;
    std::uint32_t flags;  ///< 1: clampToTriangle, 2: boxFootprint
    glm::vec2 footprintPixels;
    glm::vec2 pad;
};
static_assert(sizeof(ShadingProbe) == 48);

// The site probe k shades at: every third a sample's, the others a shared shading's, held to the
// triangle with a footprint up to a pixel wide, a box or a lookup, its point moved off the
// sample by up to half a pixel (so some points lie outside the triangle and are held to it).
exposure::ShadingSite siteOf(std::size_t k, const glm::dvec2& ndc, int width, int height) {
    if (k % 3 == 0) return exposure::sampleSite(ndc, 1);
    const double fx = 0.25 + 0.25 * double(k % 4), fy = 0.25 + 0.25 * double((k / 4) % 4);
    const glm::dvec2 shift(double(int(k % 5) - 2) * 0.25 * 2.0 / width, double(int(k % 7) - 3) * (1.0 / 6.0) * 2.0 / height);
    return {ndc + shift, glm::dvec2(fx, fy), true, k % 3 == 1};
}

class SpanShadingGlsl : public testing::TestWithParam<std::tuple<std::string, exposure::SpanTextureFilter>> {};

TEST_P(SpanShadingGlsl, MatchesCpuSpanShading) {
    const Scene scene = makeBuiltinScene(std::get<0>(GetParam()), OptionMap{});
    const int width = 96, height = 72, curveSegments = 4;
    const ShadingMode shading = ShadingMode::Phong;
    exposure::SpanShadingSettings settings;
    settings.maxTextureTaps = 32;
    settings.tapsPerTexel = 2.0f;
    settings.textureFilter = std::get<1>(GetParam());

    // Every inside span of every segment at every pixel centre (up to a budget). The GL twins
    // cut the shutter into the plan's segments and merge none, so neither does the CPU here: a
    // merged segment's span may cross the joints the shader's segments have.
    const exposure::SegmentedGeometry segmented(scene, raster::Viewport{width, height}, curveSegments, 0.0);
    const raster::SamplePattern pattern = raster::SamplePattern::rooks(1);
    std::vector<ShadingProbe> probes;
    for (int y = 0; y < height; y += 2)
        for (int x = 0; x < width; x += 2) {
            const glm::dvec2 ndc = pattern.ndcOf(x, y, 0, width, height);
            for (const exposure::TriangleSegment& seg : segmented.segments()) {
                if (!seg.isInFront()) continue;
                const raster::MovingTriangle moving(seg.clip0, seg.clip1);
                std::array<double, 8> bounds;
                const int n = moving.insideSpans(ndc, scene.camera.zNear, false, bounds);
                for (int i = 0; i + 1 < n; i += 2) {
                    const float t0 = float(seg.t0 + bounds[i] * (double(seg.t1) - seg.t0));
                    const float t1 = float(seg.t0 + bounds[i + 1] * (double(seg.t1) - seg.t0));
                    if (!(t1 > t0)) continue;
                    const exposure::ShadingSite site = siteOf(probes.size(), ndc, width, height);
                    probes.push_back({site.ndc, t0, t1, seg.triangle, (site.clampToTriangle ? 1u : 0u) | (site.boxFootprint ? 2u : 0u),
                                      glm::vec2(site.footprintPixels), glm::vec2(0.0f)});
                }
            }
        }
    ASSERT_GT(probes.size(), 100u);
    if (probes.size() > 20000) probes.resize(20000);

    RenderStats stats;
    const gpu::GpuFrame frame(scene, width, height, 1, false, shading, stats);
    std::map<std::string, std::string> defines = frame.buffers.defines();
    const gpu::GlProgram& program = gpu::buildProgram(
        {{GL_COMPUTE_SHADER, {"scene.glsl", "shading.glsl", "moving_triangle.glsl", "span_shading.glsl", "span_shading_probe.comp.glsl"}}},
        defines);
    glUseProgram(program.id());
    frame.buffers.bind(program.id());
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_numSegments"), segmented.numSegments());
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_textureSamples"), settings.maxTextureTaps);
    glProgramUniform1f(program.id(), glGetUniformLocation(program.id(), "u_tapsPerTexel"), settings.tapsPerTexel);
    glProgramUniform1i(program.id(), glGetUniformLocation(program.id(), "u_sweptTexture"),
                       settings.textureFilter == exposure::SpanTextureFilter::Swept ? 1 : 0);
    const gpu::GlBuffer input = gpu::GlBuffer::from(probes);
    const gpu::GlBuffer output(probes.size() * sizeof(glm::vec4));
    input.bindStorage(10);
    output.bindStorage(11);
    glDispatchCompute(GLuint((probes.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> shaded(probes.size());
    glGetNamedBufferSubData(output.id(), 0, GLsizeiptr(shaded.size() * sizeof(glm::vec4)), shaded.data());
    gpu::checkGlError("span shading probe");

    const raster::Viewport viewport{width, height};
    exposure::MovingTriangleCache cache;
    int mismatches = 0;
    float worst = 0.0f;
    for (std::size_t i = 0; i < probes.size(); ++i) {
        const ShadingProbe& p = probes[i];
        const exposure::ShadingSite site{p.ndc, glm::dvec2(p.footprintPixels), (p.flags & 1u) != 0, (p.flags & 2u) != 0};
        const ShadedColor want = exposure::shadeTriangleSpan(segmented, viewport, shading, settings, p.triangle, p.t0, p.t1, site, cache);
        const glm::vec4 got = shaded[i];
        const float error = std::max({std::abs(got.x - want.color.x), std::abs(got.y - want.color.y), std::abs(got.z - want.color.z),
                                      std::abs(got.w - want.alpha)});
        worst = std::max(worst, error);
        if (error > 2e-3f && ++mismatches <= 5)
            ADD_FAILURE() << "probe " << i << " (site flags " << p.flags << ") triangle " << p.triangle << " [" << p.t0 << ", " << p.t1 << "] at (" << p.ndc.x << ", "
                          << p.ndc.y << "): gl " << got.x << " " << got.y << " " << got.z << " " << got.w << ", cpu " << want.color.x
                          << " " << want.color.y << " " << want.color.z << " " << want.alpha;
    }
    EXPECT_EQ(mismatches, 0) << "of " << probes.size() << "; worst " << worst;
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, SpanShadingGlsl,
                         testing::Combine(testing::Values("rotating-cube", "twist", "pan", "translucent", "cubes"),
                                          testing::Values(exposure::SpanTextureFilter::Swept, exposure::SpanTextureFilter::Taps)));

}  // namespace
}  // namespace streak
