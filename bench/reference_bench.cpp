// Google Benchmark programs: whole renders of the built-in scenes by the motion-path method and
// the references, with the references' cost per shutter time (accumulation) or time stratum
// (stochastic). No assertions: figures go to docs/BENCHMARKS.md.

#include "methods/registry.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_loader.h"

#include <benchmark/benchmark.h>

#include <chrono>

namespace {

void renderOnce(benchmark::State& state, const std::string& method, const std::string& spec, int samples, int width, int height) {
    streak::Scene scene = streak::loadScene(spec);
    streak::validateScene(scene);
    streak::OptionMap options;
    if (samples > 0) options.set("samples", std::to_string(samples));
    auto renderer = streak::createRenderer(method, options);
    streak::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    double seconds = 0.0;
    for (auto _ : state) {
        streak::RenderStats stats;
        streak::RenderContext context{stats};
        const auto start = std::chrono::steady_clock::now();
        benchmark::DoNotOptimize(renderer->render(scene, settings, context));
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    state.counters["triangles"] = double(scene.numTriangles());
    if (samples > 0) state.counters["ms_per_time_sample"] = seconds * 1e3 / (double(state.iterations()) * samples);
}

void BM_AccumulationCubes(benchmark::State& state) {
    renderOnce(state, "accumulation", "builtin:cubes?n=" + std::to_string(state.range(0)), 16, 1024, 768);
}
BENCHMARK(BM_AccumulationCubes)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_StochasticCubes(benchmark::State& state) {
    renderOnce(state, "stochastic", "builtin:cubes?n=" + std::to_string(state.range(0)), 2, 1024, 768);
}
BENCHMARK(BM_StochasticCubes)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_MotionPathCubes(benchmark::State& state) {
    renderOnce(state, "motion-path", "builtin:cubes?n=" + std::to_string(state.range(0)), 0, 1024, 768);
}
BENCHMARK(BM_MotionPathCubes)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AccumulationRotatingCube(benchmark::State& state) {
    renderOnce(state, "accumulation", "builtin:rotating-cube", 64, 1024, 768);
}
BENCHMARK(BM_AccumulationRotatingCube)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
