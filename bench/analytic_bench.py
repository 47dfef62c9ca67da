#!/usr/bin/python3
"""The analytic (Gribel et al. 2010) figures of docs/BENCHMARKS.md.

Sections (all by default, or pick with --sections):
  quality      Every built-in scene at 256x192: analytic's and motion-path's PSNR against
               accumulation with 3000 shutter times, their times, and how much overlapping
               coverage the linear depth orders wrongly (check-depth-order).
  compression  cubes and a fast fence (fence?travel=3: thin bars crossing each pixel several
               times, the paper's failure case) with a budget of K = 2, 4, 8, 16, 64 intervals
               per sample and unlimited: PSNR and time; a plot. Then the oracle weights tried
               for the defaults, at K = 4.
  culling      Tile culling against the moving edges on and off (cubes, 1024x768): time and
               tiles culled.

Times are the "render" phase of --stats, the least of --repeats runs.

usage: bench/analytic_bench.py [--streak build/streak] [--sections quality,compression,culling]
                               [--plot docs/analytic_compression.png] [--repeats 3]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import SCENES, machine, pyplot, run_sections  # noqa: E402


def quality(streak):
    print("### Quality and time per frame against motion-path (256x192, phong, reference: accumulation 3000)\n")
    print("| scene | analytic PSNR | analytic ms | motion-path PSNR | motion-path ms | intervals per sample | misordered overlap |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    out = os.path.join(streak.tmp, "q.exr")
    for name in SCENES:
        ref = streak.reference(name)
        an_ms, _ = streak.render("builtin:" + name, "analytic", out)
        an = streak.psnr(ref, out)
        _, checked = streak.render("builtin:" + name, "analytic", out, args=["--option", "check-depth-order=1"], repeats=1)
        mp_ms, _ = streak.render("builtin:" + name, "motion-path", out)
        mp = streak.psnr(ref, out)
        c = checked["counters"]
        overlap = c["depth_overlap_time"]
        misordered = f"{100.0 * c['depth_misordered_fraction']:.3f}%" if overlap > 0 else "no overlap"
        print(f"| {name} | {an:.1f} dB | {an_ms:.1f} | {mp:.1f} dB | {mp_ms:.1f} | {c['intervals_per_sample_mean']:.2f} | {misordered} |",
              flush=True)
    print()


def compression(streak, plot):
    print("### Compression: a budget of K intervals per sample (256x192, phong)\n")
    print("| scene | K | PSNR | ms | samples compressed | merges |")
    print("|---|---:|---:|---:|---:|---:|")
    out = os.path.join(streak.tmp, "c.exr")
    budgets = [2, 4, 8, 16, 64, 0]
    curves = {}
    for name in ["cubes", "fence?travel=3"]:
        ref = streak.reference(name)
        for k in budgets:
            ms, stats = streak.render("builtin:" + name, "analytic", out, args=["--max-intervals", str(k)])
            p = streak.psnr(ref, out)
            c = stats["counters"]
            curves.setdefault(name, []).append((k, p, ms))
            print(f"| {name} | {k if k else 'unlimited'} | {p:.1f} dB | {ms:.1f} | {int(c['compressed_samples'])} | {int(c['merges'])} |",
                  flush=True)
    print()
    if plot:
        plt = pyplot()
        fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.6))
        labels = [str(k) if k else "all" for k in budgets]
        for name, rows in curves.items():
            a.plot(labels, [r[1] for r in rows], "o-", label=name)
            b.plot(labels, [r[2] for r in rows], "o-", label=name)
        a.set_xlabel("K (intervals per sample)")
        a.set_ylabel("PSNR dB vs reference")
        a.set_title("quality under compression")
        b.set_xlabel("K (intervals per sample)")
        b.set_ylabel("ms per frame (256x192)")
        b.set_title("time")
        for ax in (a, b):
            ax.grid(alpha=0.3)
            ax.legend()
        fig.suptitle(f"streak analytic, {machine()}", fontsize=8)
        fig.tight_layout()
        fig.savefig(plot, dpi=110)
        print(f"Plot: `{plot}`\n")
    print("Oracle weights h1..h5 (gap, depth, slope, duration, colour) at K = 4:\n")
    print("| weights | cubes PSNR | fence?travel=3 PSNR |")
    print("|---|---:|---:|")
    for weights in ["20,1,0.25,0.25,1", "4,1,0.25,0.25,1", "1,1,1,1,1", "1,0,0,0,0", "0,0,0,1,0", "0,0,0,0,1"]:
        row = []
        for name in ["cubes", "fence?travel=3"]:
            streak.render("builtin:" + name, "analytic", out, args=["--max-intervals", "4", "--option", "oracle-weights=" + weights],
                          repeats=1)
            row.append(streak.psnr(streak.reference(name), out))
        print(f"| {weights} | {row[0]:.1f} dB | {row[1]:.1f} dB |", flush=True)
    print()


def culling(streak):
    print("### Tile culling against the moving edges (cubes n=1000, 1024x768)\n")
    print("| tile-cull | ms | tile tests | tiles culled |")
    print("|---:|---:|---:|---:|")
    out = os.path.join(streak.tmp, "t.exr")
    for flag in ("1", "0"):
        ms, stats = streak.render("builtin:cubes", "analytic", out, size="1024x768", args=["--option", "tile-cull=" + flag])
        c = stats["counters"]
        print(f"| {flag} | {ms:.0f} | {int(c['tile_tests'])} | {int(c['tiles_culled'])} |", flush=True)
    print()


def main():
    run_sections({"quality": lambda s, a: quality(s), "compression": lambda s, a: compression(s, a.plot), "culling": lambda s, a: culling(s)},
                 "docs/analytic_compression.png")


if __name__ == "__main__":
    main()
