// The GLSL twin of raster::MovingTriangle (moving_triangle.glsl) against the CPU class: the
// same exact inside spans for random moving triangles, on whatever GL 4.5 driver runs the tests.

#include "gpu/gl_context.h"
#include "gpu/gl_object.h"
#include "gpu/shader_library.h"
#include "raster/moving_triangle.h"
#include "util/random.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace streak {
namespace {

// std430 twins of inside_spans_probe.comp.glsl's structs.
struct SpanProbe {
    glm::vec4 open[3], close[3];
    glm::dvec2 ndc;
    double zNear;
    std::int32_t checkNearPlane;
    std::int32_t pad;
};
static_assert(sizeof(SpanProbe) == 128);
struct SpanProbeResult {
    double bounds[8];
    std::int32_t count;
    std::int32_t pad;
};
static_assert(sizeof(SpanProbeResult) == 72);

std::vector<SpanProbeResult> runProbes(const std::vector<SpanProbe>& probes) {
    gpu::sharedContext();
    const gpu::GlProgram& program = gpu::buildProgram({{GL_COMPUTE_SHADER, {"moving_triangle.glsl", "inside_spans_probe.comp.glsl"}}});
    const gpu::GlBuffer input = gpu::GlBuffer::from(probes);
    const gpu::GlBuffer output(probes.size() * sizeof(SpanProbeResult));
    input.bindStorage(0);
    output.bindStorage(1);
    glUseProgram(program.id());
    glDispatchCompute(GLuint((probes.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<SpanProbeResult> results(probes.size());
    glGetNamedBufferSubData(output.id(), 0, GLsizeiptr(results.size() * sizeof(SpanProbeResult)), results.data());
    gpu::checkGlError("inside spans probe");
    return results;
}

// Triangles that move, turn and change depth (w from 0.5 to 3), so every edge equation has a
// u^2 term; points anywhere in NDC. The GLSL spans equal the CPU's to rounding.
TEST(MovingTriangleGlsl, InsideSpansMatchTheCpu) {
    Rng rng(29);
    auto randomClip = [&] { return glm::vec4(rng.uniform(-2, 2), rng.uniform(-2, 2), 0.0f, rng.uniform(0.5f, 3.0f)); };
    std::vector<SpanProbe> probes(4000);
    for (std::size_t i = 0; i < probes.size(); ++i) {
        SpanProbe& p = probes[i];
        for (int c = 0; c < 3; ++c) p.open[c] = randomClip(), p.close[c] = randomClip();
        p.ndc = {rng.uniform(-1, 1), rng.uniform(-1, 1)};
        p.zNear = 1.0;
        p.checkNearPlane = int(i % 2);
    }
    const std::vector<SpanProbeResult> results = runProbes(probes);
    int withSpans = 0, mismatches = 0;
    for (std::size_t i = 0; i < probes.size(); ++i) {
        const SpanProbe& p = probes[i];
        const raster::MovingTriangle moving({p.open[0], p.open[1], p.open[2]}, {p.close[0], p.close[1], p.close[2]});
        std::array<double, 8> bounds;
        const int n = moving.insideSpans(p.ndc, p.zNear, p.checkNearPlane != 0, bounds);
        withSpans += n > 0;
        bool same = results[i].count == n;
        for (int k = 0; same && k < n; ++k) same = std::abs(results[i].bounds[k] - bounds[k]) <= 1e-9;
        if (!same && ++mismatches <= 5) {
            ADD_FAILURE() << "probe " << i << ": gl " << results[i].count << " bounds, cpu " << n << "; first gl "
                          << (results[i].count > 0 ? results[i].bounds[0] : -1) << ", cpu " << (n > 0 ? bounds[0] : -1);
        }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(withSpans, 400);  // the test means something: many samples are covered
}

}  // namespace
}  // namespace streak
