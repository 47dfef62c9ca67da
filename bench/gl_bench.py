#!/usr/bin/python3
"""The GL figures of docs/BENCHMARKS.md (issue: motion paths on the GPU).

Sections (all by default, or pick with --sections):
  passes  Per-pass GPU times of motion-path-gl, accumulation-gl and stochastic-gl for
          builtin:cubes n=1000 and n=2000 and the largest cubes scene (n=5750: 69,000
          triangles, the size of Hong & Oh's 7.77 ms scene) at 1024x768 and 1920x1080.
  equal   Every built-in scene at 256x192: motion-path-gl's PSNR against accumulation with 3000
          shutter times, and the sample counts at which accumulation-gl and stochastic-gl reach
          the same PSNR, with the three warm frame times and the ratios.

Every timed render is the second of two renders in one process (--repeat 2), so shaders are
compiled and the driver's code generated before the timed frame. Pass times are the "gpu <pass>"
phases of --stats: GL timestamp queries on a GPU; on a software rasterizer (llvmpipe) the CPU
clock around glFinish, since llvmpipe stamps queries as it bins them. The GL_RENDERER of the run
is printed first. Least of --repeats runs (the machines are shared).

On the device machine (an H100), after building there with the EGL loader carried:
  bench/gl_bench.py --sections passes --repeats 3

usage: bench/gl_bench.py [--streak build/streak] [--sections passes,equal] [--repeats 1]
"""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import LADDER, SCENES, equal_quality_count, run_sections  # noqa: E402

GL_METHODS = ["motion-path-gl", "accumulation-gl", "stochastic-gl"]
# The baselines' sample counts in the pass table: the default of stochastic-gl, and 64 shutter
# times for accumulation-gl (the equal section finds the counts that match motion-path-gl).
TABLE_SAMPLES = {"motion-path-gl": [], "accumulation-gl": ["--samples", "64"], "stochastic-gl": ["--samples", "8"]}
WARM = ["--repeat", "2"]


def gl_renderer(streak):
    out = os.path.join(streak.tmp, "probe.exr")
    subprocess.run([streak.binary, "render", "builtin:crossing", "-m", "accumulation-gl", "--samples", "1", "--width", "16",
                    "--height", "16", "-o", out, "--stats", streak.stats], check=True)
    with open(streak.stats) as f:
        info = json.load(f)["info"]
    return f"{info['gl_renderer']}, {info['gl_version']}"


def passes(streak):
    print(f"GL_RENDERER: {gl_renderer(streak)}\n")
    print("### Per-pass GPU times (ms, warm frame, phong)\n")
    print("| scene | triangles | size | method | GPU ms per pass (summed over a frame) | GPU total ms | frame ms | intervals per sample |")
    print("|---|---:|---|---|---|---:|---:|---:|")
    out = os.path.join(streak.tmp, "passes.exr")
    for n in (1000, 2000, 5750):
        for size in ("1024x768", "1920x1080"):
            for method in GL_METHODS:
                ms, stats = streak.render(f"builtin:cubes?n={n}", method, out, size=size, args=[*TABLE_SAMPLES[method], *WARM])
                t, c = stats["time_ms"], stats["counters"]
                per_pass = ", ".join(f"{k[4:]} {v:.1f}" for k, v in t.items() if k.startswith("gpu ") and k != "gpu total")
                label = method + (f" ({TABLE_SAMPLES[method][1]} samples)" if TABLE_SAMPLES[method] else "")
                intervals = f"{c['intervals_per_sample_mean']:.2f}" if "intervals_per_sample_mean" in c else "–"
                print(f"| cubes n={n} | {int(c['triangles'])} | {size} | {label} | {per_pass} | {t['gpu total']:.1f} | {ms:.1f} | "
                      f"{intervals} |", flush=True)
    print()


def equal(streak):
    print("### Equal quality against the GPU baselines (256x192, phong, reference: accumulation 3000)\n")
    print("| scene | motion-path-gl PSNR | ms | accumulation-gl samples (PSNR) | ms | ratio | stochastic-gl samples (PSNR) | ms | ratio |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name in SCENES:
        scene = "builtin:" + name
        ref = streak.reference(name)
        out = os.path.join(streak.tmp, "mp-gl.exr")
        mp_ms, _ = streak.render(scene, "motion-path-gl", out, args=WARM)
        target = streak.psnr(ref, out)
        cells = [f"{target:.1f} dB", f"{mp_ms:.1f}"]
        for method, top in (("accumulation-gl", 2048), ("stochastic-gl", 512)):
            ladder = [r for r in LADDER if r <= top]
            n, n_psnr, path = equal_quality_count(streak, scene, method, ref, target, ladder=ladder)
            if n is None:
                cells += [f"> {top} ({n_psnr:.1f} dB)", "–", "–"]
                continue
            ms, _ = streak.render(scene, method, path, args=["--samples", str(n), *WARM])
            cells += [f"{n} ({n_psnr:.1f} dB)", f"{ms:.1f}", f"{ms / mp_ms:.1f}"]
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)
    print()


def main():
    run_sections({"passes": lambda s, a: passes(s), "equal": lambda s, a: equal(s)}, "")


if __name__ == "__main__":
    main()
