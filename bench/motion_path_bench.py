#!/usr/bin/python3
"""The motion-path figures of docs/BENCHMARKS.md (issue: motion paths on the CPU).

Sections (all by default, or pick with --sections):
  quality  Every built-in scene at 256x192: motion-path's PSNR against accumulation with 3000
           shutter times, and the accumulation sample count that reaches the same PSNR (found by
           bisection), with both times and their ratio.
  sweep    Hong & Oh's Fig. 15/16: cubes n = 1000, 1200, ..., 2000 at 1024x768, depth-time sort
           on and off: time per frame and mean intervals per sample; a plot.
  params   Error against --mask-bits (with exact-weights=0: the paper's slices) and --texture-samples (cubes and rotating-cube).
  default  The default scene (cubes n=1000, 1024x768): time per phase.

Times are the "render" phase of --stats, the least of --repeats runs (the machines are shared);
methods are compared within one run of this script. Images are compared as EXR, so 8-bit
quantization does not cap the PSNR.

usage: bench/motion_path_bench.py [--streak build/streak] [--sections quality,sweep,params,default]
                                  [--plot docs/motion_path_sweep.png] [--repeats 3]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import LADDER, SCENES, equal_quality_count, machine, pyplot, run_sections  # noqa: E402


def quality(streak):
    print("### Quality and equal-quality speed (256x192, phong, reference: accumulation 3000)\n")
    print("| scene | motion-path PSNR | motion-path ms | accumulation times at equal PSNR | accumulation ms | ratio |")
    print("|---|---:|---:|---:|---:|---:|")
    for name in SCENES:
        scene = "builtin:" + name
        ref = streak.reference(name)
        out = os.path.join(streak.tmp, "mp.exr")
        mp_ms, _ = streak.render(scene, "motion-path", out)
        target = streak.psnr(ref, out)
        n, n_psnr, acc = equal_quality_count(streak, scene, "accumulation", ref, target)
        n = n or LADDER[-1]
        acc_ms, _ = streak.render(scene, "accumulation", acc, args=["--samples", str(n)])
        mp_ms = min(mp_ms, streak.render(scene, "motion-path", out)[0])
        print(f"| {name} | {target:.1f} dB | {mp_ms:.1f} | {n} ({n_psnr:.1f} dB) | {acc_ms:.1f} | {acc_ms / mp_ms:.1f} |",
              flush=True)
    print()


def sweep(streak, plot):
    print("### Hong & Oh Fig. 15/16: cubes at 1024x768, depth-time sort on and off\n")
    print("| cubes n | triangles | sort on: ms | sort off: ms | intervals per sample (mean) | max | splits | sort ms (on) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    rows = []
    out = os.path.join(streak.tmp, "sweep.exr")
    for n in range(1000, 2001, 200):
        scene = f"builtin:cubes?n={n}"
        on_ms, on = streak.render(scene, "motion-path", out, size="1024x768", args=["--sort", "1"])
        off_ms, _ = streak.render(scene, "motion-path", out, size="1024x768", args=["--sort", "0"])
        c = on["counters"]
        rows.append((n, on_ms, off_ms, c["intervals_per_sample_mean"]))
        print(f"| {n} | {int(c['triangles'])} | {on_ms:.0f} | {off_ms:.0f} | {c['intervals_per_sample_mean']:.2f} | "
              f"{int(c['intervals_per_sample_max'])} | {int(c['interval_splits'])} | {on['time_ms']['sort']:.0f} |", flush=True)
    print()
    if plot:
        plt = pyplot()
        fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8))
        ns = [r[0] for r in rows]
        a.plot(ns, [r[1] for r in rows], "o-", label="sort on")
        a.plot(ns, [r[2] for r in rows], "s--", label="sort off")
        a.set_xlabel("cubes")
        a.set_ylabel("ms per frame (1024x768)")
        a.set_title("time per frame (cf. Fig. 15)")
        a.legend()
        a.grid(alpha=0.3)
        b.plot(ns, [r[3] for r in rows], "o-", color="C2")
        b.set_xlabel("cubes")
        b.set_ylabel("intervals per sample (mean)")
        b.set_title("depth complexity (cf. Fig. 16)")
        b.grid(alpha=0.3)
        fig.suptitle(f"streak motion-path, {machine()}", fontsize=8)
        fig.tight_layout()
        fig.savefig(plot, dpi=110)
        print(f"Plot: `{plot}`\n")


def params(streak):
    print("### Error against the mask size and the texture taps (256x192, phong)\n")
    print("| scene | mask-bits | texture-samples | PSNR | ms |")
    print("|---|---:|---:|---:|---:|")
    out = os.path.join(streak.tmp, "params.exr")
    for name in ["cubes", "rotating-cube"]:
        scene = "builtin:" + name
        ref = streak.reference(name)
        configs = [(b, 32) for b in (32, 64, 128, 256)] + [(128, k) for k in (1, 4, 16, 64)]
        for bits, k in configs:
            ms, _ = streak.render(scene, "motion-path", out, args=["--mask-bits", str(bits), "--texture-samples", str(k), "--option", "exact-weights=0"])
            print(f"| {name} | {bits} | {k} | {streak.psnr(ref, out):.1f} dB | {ms:.1f} |", flush=True)
    print()


def default(streak):
    print("### Default scene: cubes n=1000, 1024x768\n")
    out = os.path.join(streak.tmp, "default.exr")
    ms, stats = streak.render("builtin:cubes", "motion-path", out, size="1024x768")
    phases = ["generate", "bin", "rasterize", "build intervals", "sort", "resolve", "shade"]
    print("| render ms (least of runs) | " + " | ".join(phases) + " |")
    print("|---:|" + "---:|" * len(phases))
    print(f"| {ms:.0f} | " + " | ".join(f"{stats['time_ms'].get(p, 0):.0f}" for p in phases) + " |")
    c = stats["counters"]
    print(f"\nIntervals per sample {c['intervals_per_sample_mean']:.2f} (max {int(c['intervals_per_sample_max'])}), "
          f"{int(c['shaded_spans'])} spans shaded of {int(c['intervals'])} intervals.\n")


def main():
    run_sections({"quality": lambda s, a: quality(s), "sweep": lambda s, a: sweep(s, a.plot), "params": lambda s, a: params(s), "default": lambda s, a: default(s)},
                 "docs/motion_path_sweep.png")


if __name__ == "__main__":
    main()
