#!/usr/bin/python3
"""Speed figures of docs/BENCHMARKS.md (issue 16): where the exact methods' time goes, and what
each lever changed.

Section profile: per-phase times and counters of motion-path and analytic on builtin:cubes at
1024x768, on the dense ToyCar (109k triangles) under a camera move (320x240, --aa 2), and on
ToyCar and the 1M-triangle MetalRoughSpheresNoTextures static (320x240, --aa 4 and 8), least
of the repeats; with --baseline OLD_STREAK (a build of the commit before a change, run with its
own libstreak.so beside it) both binaries are timed in the same run, alternating, and the images
compared (PSNR between them: inf when the change is exact).

Section static: the exact methods on the static cases against one accumulation pass at the same
--aa (a static scene's exact answer: issue 28's target is at most 1.3 times it), per sample and
per pixel shading, with --baseline the build before a change beside them.

Section simd: analytic's interval phase at each SIMD level of its edge batches (STREAK_SIMD=
scalar, sse2, and avx2 where the CPU has it), alternating, least of the repeats, on the static
ToyCar and the dense camera move; the images are compared (inf: every level is exact).

Section dense: issue 28's dense camera move (MetalRoughSpheresNoTextures, 1,040,213 triangles,
the camera travelling a quarter of the frame without turning) at 240x135 --aa 2: wall, peak
memory and phases of analytic and motion-path, with --baseline the build before beside them.

Section quality: the dense camera move at equal quality (issue 28: "faster than embree at the
same foreground PSNR against accumulation-1024 of that move"), at --dense-size (240x135) --aa 2:
accumulation with 1024 shutter times is the reference; analytic and motion-path, then embree at
--embree-ladder rays per sample and accumulation at --accumulation-ladder times, each one run:
render time, peak memory, and foreground PSNR against the reference and against analytic's image
(the exact one: a sampled method's error is then its own, not the reference's too).

Section budget: the dense camera move at 240x135 and 480x270 with motion-path and analytic, at
the default --memory-budget and at each of --budgets (MB, default 1000): wall, peak memory, what
was resident when the tiles began, the share per thread, the tiles halved and the pixels cut,
and the image against the default budget's (inf: halving tiles is exact).

Section models: every shared model at the ground-truth bench's 320x240 view (its frame, shutter
and animation; unlit, black background), analytic and motion-path at --aa 3 and analytic with
--adaptive 0.02: render time, least of the repeats, with --baseline the build before beside it
(alternating) and the images compared (inf: the change is exact).

Section shading: issue 33's shading target on CesiumMan, Fox and RiggedFigure at the ground-truth
bench's 320x240 views, --aa 8 unlit, analytic: per-sample shading, the default (4 x 4 cells of
2 x 2 samples for a moving textured triangle) and one cell a pixel: render and shade ms, the
shadings and their ratio to the distinct triangles each pixel sees, and with --cycles DIR (a
ground_truth_bench.py --out folder) the foreground PSNR against DIR/MODEL/cycles-1024.exr.

Section threads: render time at --threads 1 and 2 (the ratio is the thread scaling).

Section memory: peak resident memory of each method (the process's maxrss) on the profile's
cases, on every built-in scene at 1024x768, and on the 1M-triangle MetalRoughSpheresNoTextures.

Section resolution: render time of each method on builtin:cubes from 256x192 to 1920x1080, and
per megapixel (cost linear in pixels: a flat column); --plot DIR draws DIR/speed_resolution.png.

Profiles of the hot functions come from perf (Debian's linux-perf), not from this script:
  perf record -g build/streak render builtin:cubes -m motion-path -o x.exr
  perf report --no-children --percent-limit 1 --stdio

usage: bench/speed_bench.py [--streak build/streak] [--baseline DIR/streak] [--sections profile,static,simd,dense,quality,budget,models,shading,threads,memory,resolution] [--repeats 3] [--cycles DIR] [--budgets 1000] [--dense-size 240x135] [--embree-ladder 8,...,1024] [--accumulation-ladder 64,256] [--plot docs]
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import compare, machine, pyplot  # noqa: E402

SHARED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "scenes")
TOYCAR = os.path.join(SHARED, "ToyCar", "glTF", "ToyCar.gltf")
SPHERES = os.path.join(SHARED, "MetalRoughSpheresNoTextures", "glTF-Binary", "MetalRoughSpheresNoTextures.glb")
CASES = [
    ("cubes 1024x768", ["builtin:cubes", "--width", "1024", "--height", "768"]),
    ("ToyCar camera move 320x240 aa 2", [TOYCAR, "--camera-pos=-0.03,0.025,0.05", "--camera-target", "0,0,0",
                                          "--camera-pos-end=-0.02,0.025,0.055", "--fov", "40", "--width", "320", "--height", "240",
                                          "--aa", "2"]),
    # The two dense static models at the --aa the ground-truth bench needs for 40 dB there.
    ("ToyCar static 320x240 aa 4", [TOYCAR, "--width", "320", "--height", "240", "--aa", "4"]),
    ("MetalRoughSpheresNoTextures static 320x240 aa 8", [SPHERES, "--width", "320", "--height", "240", "--aa", "8"]),
]
BUILTIN = ["cubes", "rotating-cube", "spin", "clothball", "sphere", "crossing", "twist", "fence", "pan", "translucent"]
MEMORY_CASES = CASES + [(f"{n} 1024x768", [f"builtin:{n}", "--width", "1024", "--height", "768"]) for n in BUILTIN[1:]] + [
    ("MetalRoughSpheresNoTextures (1,040,213 triangles) 1024x768", [SPHERES, "--width", "1024", "--height", "768"])]
SIZES = [(256, 192), (512, 384), (1024, 768), (1920, 1080)]
METHODS = [("motion-path", []), ("analytic", []), ("accumulation 64", ["-m", "accumulation", "--samples", "64"])]


DENSE_CAMERAS = ["--camera-pos=0.00277,0.00274,0.0103", "--camera-target=0.00277,0.00274,0",
                 "--camera-pos-end=0.0055,0.0040,0.0100", "--camera-target-end=0.0055,0.0040,0"]
DENSE = ("MetalRoughSpheresNoTextures camera move 240x135 aa 2", [SPHERES, *DENSE_CAMERAS, "--width", "240", "--height", "135", "--aa", "2"])


def run(binary, case_args, method_args, out, stats, extra=(), simd=None):
    """Renders once (at SIMD level `simd` when given); returns (stats, peak resident MiB)."""
    env = dict(os.environ)
    if simd:
        env["STREAK_SIMD"] = simd
    # A saved baseline with its own library (libstreak.so, or only its versioned file): without
    # the path, the binary's run path finds this build's library instead.
    folder = os.path.dirname(binary)
    if folder not in ("", "build") and glob.glob(os.path.join(folder, "libstreak.so*")):
        env["LD_LIBRARY_PATH"] = folder
    args = [binary, "render", *case_args, *method_args, *extra, "-o", out, "--stats", stats]
    process = subprocess.Popen(args, env=env)
    _, status, usage = os.wait4(process.pid, 0)
    if status != 0:
        raise SystemExit(f"failed: {' '.join(args)}")
    with open(stats) as f:
        return json.load(f), usage.ru_maxrss / 1024.0


def method_args(name, extra):
    return extra if extra else ["-m", name]


def psnr(binary, a, b):
    out = subprocess.run([binary, "compare", a, b], check=True, capture_output=True, text=True).stdout
    return out.split("\n")[0].split(":")[1].strip()


def profile(args, tmp):
    print("### Phases (ms, least of the repeats)\n")
    binaries = [("this build", args.streak)] + ([("baseline", args.baseline)] if args.baseline else [])
    for case, case_args in CASES:
        if not os.path.exists(case_args[0]) and not case_args[0].startswith("builtin:"):
            print(f"{case}: skipped, no {case_args[0]}\n")
            continue
        for method, extra in METHODS[:2]:
            best = {}
            for _ in range(args.repeats):
                for label, binary in binaries:
                    stats, _ = run(binary, case_args, method_args(method, extra), os.path.join(tmp, f"{label}.exr"),
                                   os.path.join(tmp, "s.json"))
                    if label not in best or stats["time_ms"]["render"] < best[label]["time_ms"]["render"]:
                        best[label] = stats
            phases = [p for p in best["this build"]["time_ms"] if p not in ("load", "tiles", "total")]
            print(f"{case}, {method}:\n")
            print("| build | " + " | ".join(phases) + " | hidden intervals culled | intervals / sample |")
            print("|---|" + "---:|" * (len(phases) + 2))
            for label, _ in binaries:
                s = best[label]
                cells = [f"{s['time_ms'].get(p, 0):.0f}" for p in phases]
                c = s["counters"]
                print(f"| {label} | " + " | ".join(cells) +
                      f" | {c.get('hidden_intervals_culled', 0):.0f} | {c.get('intervals_per_sample_mean', 0):.2f} |")
            if args.baseline:
                ratio = best["baseline"]["time_ms"]["render"] / best["this build"]["time_ms"]["render"]
                print(f"\nrender: baseline / this build = {ratio:.2f}; images apart: "
                      f"{psnr(args.streak, os.path.join(tmp, 'this build.exr'), os.path.join(tmp, 'baseline.exr'))}\n")
            else:
                print()


def static(args, tmp):
    print("### Static scenes against one accumulation pass (render ms, least of the repeats; in brackets / accumulation)\n")
    binaries = [("this build", args.streak)] + ([("baseline", args.baseline)] if args.baseline else [])
    exact = [(f"{m}{', ' + label if label != 'this build' else ''}{', shading=pixel' if pixel else ''}", binary, m, pixel)
             for m in ("motion-path", "analytic") for label, binary in binaries for pixel in (False, True)]
    print("| scene | accumulation --samples 1 | " + " | ".join(name for name, *_ in exact) + " |")
    print("|---|" + "---:|" * (len(exact) + 1))
    for case, case_args in CASES[2:]:
        if not os.path.exists(case_args[0]):
            continue
        def least(binary, method_args_):
            return min(run(binary, case_args, method_args_, os.path.join(tmp, "st.exr"), os.path.join(tmp, "s.json"))[0]["time_ms"]["render"]
                       for _ in range(args.repeats))
        base = least(args.streak, ["-m", "accumulation", "--samples", "1"])
        cells = []
        for _, binary, method, pixel in exact:
            ms = least(binary, ["-m", method] + (["--option", "shading=pixel"] if pixel else []))
            cells.append(f"{ms:.0f} ({ms / base:.2f})")
        print(f"| {case} | {base:.0f} | " + " | ".join(cells) + " |", flush=True)
    print()


def simd(args, tmp):
    print("### Edge batches at each SIMD level: analytic's intervals phase (ms, least of the repeats)\n")
    probe, _ = run(args.streak, ["builtin:cubes", "--width", "32", "--height", "24"], ["-m", "analytic"],
                   os.path.join(tmp, "p.exr"), os.path.join(tmp, "s.json"))
    levels = ["scalar", "sse2"] + (["avx2"] if probe["info"].get("simd") == "avx2" else [])
    print("| scene | " + " | ".join(levels) + " | render, " + " | render, ".join(levels) + " | images apart |")
    print("|---|" + "---:|" * (2 * len(levels) + 1))
    for case, case_args in [CASES[2], DENSE, CASES[1]]:
        if not os.path.exists(case_args[0]):
            continue
        best = {}
        for _ in range(args.repeats):
            for level in levels:
                stats, _ = run(args.streak, case_args, ["-m", "analytic"], os.path.join(tmp, f"{level}.exr"), os.path.join(tmp, "s.json"),
                               simd=level)
                assert stats["info"]["simd"] == level, stats["info"]
                if level not in best or stats["time_ms"]["intervals"] < best[level]["time_ms"]["intervals"]:
                    best[level] = stats
        apart = max((psnr(args.streak, os.path.join(tmp, "scalar.exr"), os.path.join(tmp, f"{level}.exr")) for level in levels[1:]),
                    key=lambda v: float(v.split()[0]) if v.split()[0] != "inf" else 1e9)
        cells = [f"{best[l]['time_ms']['intervals']:.0f}" for l in levels] + [f"{best[l]['time_ms']['render']:.0f}" for l in levels]
        print(f"| {case} | " + " | ".join(cells) + f" | {apart} |", flush=True)
    print()


def dense(args, tmp):
    case, case_args = DENSE
    print(f"### {case}: wall s, peak MiB, phases ms (one run each, alternating)\n")
    binaries = [("this build", args.streak)] + ([("baseline", args.baseline)] if args.baseline else [])
    print("| method | build | wall | peak | segments per triangle | setup | intervals | resolve | shade | edge quadratics solved |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for method in ("analytic", "motion-path"):
        for label, binary in binaries:
            start = time.monotonic()
            stats, peak = run(binary, case_args, ["-m", method], os.path.join(tmp, f"{label}.exr"), os.path.join(tmp, "s.json"))
            wall = time.monotonic() - start
            t, c = stats["time_ms"], stats["counters"]
            solved = sum(c.get(k, 0) for k in ("roots_constant", "roots_linear", "roots_none", "roots_double", "roots_two"))
            intervals = t.get("intervals", t.get("build intervals", 0) + t.get("rasterize", 0))
            print(f"| {method} | {label} | {wall:.1f} | {peak:.0f} | {c.get('segments_per_triangle', 0):.0f} | {t.get('setup', t.get('generate', 0)):.0f} | "
                  f"{intervals:.0f} | {t.get('resolve', 0):.0f} | {t.get('shade', 0):.0f} | {f'{solved / 1e6:.0f} M' if solved else '-'} |", flush=True)
        if args.baseline:
            print(f"| {method} | images apart | {psnr(args.streak, os.path.join(tmp, 'this build.exr'), os.path.join(tmp, 'baseline.exr'))} | | | | | | | |")
    print()


def quality(args, tmp):
    width, height = (int(v) for v in args.dense_size.split("x"))
    case_args = [SPHERES, *DENSE_CAMERAS, "--width", str(width), "--height", str(height), "--aa", "2"]
    print(f"### The dense camera move at equal quality, {width}x{height} --aa 2 (one run each)\n")
    reference = os.path.join(tmp, "reference.exr")
    start = time.monotonic()
    _, peak = run(args.streak, case_args, ["-m", "accumulation", "--samples", "1024"], reference, os.path.join(tmp, "s.json"))
    print(f"Reference: accumulation, 1024 shutter times, {time.monotonic() - start:.0f} s, {peak:.0f} MiB.\n")
    rows = [("analytic", "", ["-m", "analytic"]), ("motion-path", "", ["-m", "motion-path"])]
    rows += [("embree", s, ["-m", "embree", "--samples", s]) for s in args.embree_ladder.split(",") if s]
    rows += [("accumulation", s, ["-m", "accumulation", "--samples", s]) for s in args.accumulation_ladder.split(",") if s]
    print("| method | rays or times per sample | render s | peak MiB | fg PSNR against the reference | fg PSNR against analytic |")
    print("|---|---:|---:|---:|---:|---:|")
    exact = os.path.join(tmp, "analytic.exr")
    for label, samples, method in rows:
        out = os.path.join(tmp, f"{label}{samples}.exr")
        stats, peak = run(args.streak, case_args, method, out, os.path.join(tmp, "s.json"))
        against_exact = "—" if label == "analytic" else f"{compare(args.streak, exact, out)[1]:.1f}"
        print(f"| {label} | {samples or 'exact'} | {stats['time_ms']['render'] / 1000:.2f} | {peak:.0f} | "
              f"{compare(args.streak, reference, out)[1]:.1f} | {against_exact} |", flush=True)
    print()


def budget(args, tmp):
    print("### The memory budget on the dense camera move (one run each)\n")
    print("| case | method | --memory-budget MB | wall s | peak MiB | resident at the tiles MiB | share per thread MiB | tiles halved | pixels cut | image against the default's |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    sizes = [(f"{w}x{h}", [SPHERES, *DENSE_CAMERAS, "--width", str(w), "--height", str(h), "--aa", "2"]) for w, h in ((240, 135), (480, 270))]
    for label, size_args in sizes:
        for method in ("motion-path", "analytic"):
            budgets = [None] + [int(b) for b in args.budgets.split(",")]
            for mb in budgets:
                out = os.path.join(tmp, f"budget-{mb}.exr")
                extra = ["--memory-budget", str(mb)] if mb else []
                start = time.monotonic()
                stats, peak = run(args.streak, size_args, ["-m", method], out, os.path.join(tmp, "s.json"), extra)
                wall = time.monotonic() - start
                c = stats["counters"]
                apart = psnr(args.streak, os.path.join(tmp, "budget-None.exr"), out) if mb else ""
                print(f"| {label} | {method} | {c['memory_budget_mb']:.0f} | {wall:.1f} | {peak:.0f} | {c['memory_resident_mb']:.0f} | "
                      f"{c['tile_share_mb']:.0f} | {c['memory_budget_splits']:.0f} | {c['memory_budget_pixels_cut']:.0f} | {apart} |", flush=True)
    print()


def models(args, tmp):
    from ground_truth_bench import MODELS, SCENES  # the views the Cycles scores are taken at
    print("### The shared models (render ms, least of the repeats; 320x240 unlit)\n")
    binaries = [("this build", args.streak)] + ([("baseline", args.baseline)] if args.baseline else [])
    variants = [("analytic --aa 3", ["-m", "analytic", "--aa", "3"]), ("motion-path --aa 3", ["-m", "motion-path", "--aa", "3"]),
                ("analytic --aa 3 --adaptive 0.02", ["-m", "analytic", "--aa", "3", "--adaptive", "0.02"])]
    print("| model | method | " + " | ".join(label for label, _ in binaries) +
          (" | baseline / this build | images apart |" if args.baseline else " |"))
    print("|---|---|" + "---:|" * len(binaries) + ("---:|---:|" if args.baseline else ""))
    for name, path, flags in MODELS:
        case_args = [os.path.join(SCENES, path), "--width", "320", "--height", "240", "--shading", "unlit", "--background", "0,0,0"]
        case_args += [f"--{k}={v}" for k, v in flags.items()]
        if not os.path.exists(case_args[0]):
            continue
        for variant, variant_args in variants:
            best = {}
            for _ in range(args.repeats):
                for label, binary in binaries:
                    stats, _ = run(binary, case_args, variant_args, os.path.join(tmp, f"{label}.exr"), os.path.join(tmp, "s.json"))
                    best[label] = min(best.get(label, float("inf")), stats["time_ms"]["render"])
            cells = " | ".join(f"{best[label]:.0f}" for label, _ in binaries)
            tail = (f" | {best['baseline'] / best['this build']:.2f} | "
                    f"{psnr(args.streak, os.path.join(tmp, 'this build.exr'), os.path.join(tmp, 'baseline.exr'))} |") if args.baseline else " |"
            print(f"| {name} | {variant} | {cells}{tail}", flush=True)
    print()


def shading(args, tmp):
    # Issue 33's shading target: at 320x240 --aa 8 unlit on CesiumMan, Fox and RiggedFigure (the
    # ground-truth bench's views), at most 1.5 shadings per visible triangle and pixel, and the
    # shading time 10x below per-sample shading.
    from ground_truth_bench import MODELS, SCENES
    print("### Shadings per visible triangle (320x240 --aa 8 unlit, analytic; ms least of the repeats)\n")
    variants = [("per sample (shading=sample)", ["--option", "shading=sample"]), ("default", []),
                ("one cell (shading-cells=1)", ["--option", "shading-cells=1"])]
    print("| model | shading | render ms | shade ms | shaded spans | spans / visible triangles |" +
          (" fg PSNR against Cycles |" if args.cycles else ""))
    print("|---|---|---:|---:|---:|---:|" + ("---:|" if args.cycles else ""))
    for name, path, flags in MODELS:
        if name not in ("CesiumMan", "Fox", "RiggedFigure"):
            continue
        case_args = [os.path.join(SCENES, path), "--width", "320", "--height", "240", "--shading", "unlit", "--background", "0,0,0",
                     "--aa", "8", "-m", "analytic"] + [f"--{k}={v}" for k, v in flags.items()]
        if not os.path.exists(case_args[0]):
            continue
        for label, variant_args in variants:
            out = os.path.join(tmp, "shading.exr")
            runs = [run(args.streak, case_args, variant_args, out, os.path.join(tmp, "s.json"))[0] for _ in range(args.repeats)]
            c = runs[-1]["counters"]
            ratio = c["shaded_spans_per_pixel"] / c["visible_triangles_per_pixel"]
            row = (f"| {name} | {label} | {min(r['time_ms']['render'] for r in runs):.0f} | {min(r['time_ms']['shade'] for r in runs):.0f} | "
                   f"{c['shaded_spans']:,.0f} | {ratio:.2f} |")
            if args.cycles:
                row += f" {compare(args.streak, out, os.path.join(args.cycles, name, 'cycles-1024.exr'))[1]:.2f} dB |"
            print(row, flush=True)
    print()


def threads(args, tmp):
    print("### Thread scaling (render ms, least of the repeats)\n")
    print("| scene | method | 1 thread | 2 threads | scaling |")
    print("|---|---|---:|---:|---:|")
    for case, case_args in CASES[:1]:
        for method, extra in METHODS:
            times = []
            for n in (1, 2):
                times.append(min(run(args.streak, case_args, method_args(method, extra), os.path.join(tmp, "t.exr"),
                                     os.path.join(tmp, "s.json"), ["--threads", str(n)])[0]["time_ms"]["render"]
                                 for _ in range(args.repeats)))
            print(f"| {case} | {method} | {times[0]:.0f} | {times[1]:.0f} | {times[0] / times[1]:.2f} |", flush=True)
    print()


def memory(args, tmp):
    print("### Peak memory (MiB resident, the whole process)\n")
    print("| scene | " + " | ".join(m for m, _ in METHODS) + " |")
    print("|---|" + "---:|" * len(METHODS))
    for case, case_args in MEMORY_CASES:
        if not os.path.exists(case_args[0]) and not case_args[0].startswith("builtin:"):
            continue
        cells = [f"{run(args.streak, case_args, method_args(m, e), os.path.join(tmp, 'm.exr'), os.path.join(tmp, 's.json'))[1]:.0f}"
                 for m, e in METHODS]
        print(f"| {case} | " + " | ".join(cells) + " |", flush=True)
    print()


def resolution(args, tmp):
    print("### Resolution (builtin:cubes, render ms, least of the repeats; in brackets ms per megapixel)\n")
    print("| size | " + " | ".join(m for m, _ in METHODS) + " |")
    print("|---|" + "---:|" * len(METHODS))
    times = {m: [] for m, _ in METHODS}
    for w, h in SIZES:
        cells = []
        for method, extra in METHODS:
            ms = min(run(args.streak, ["builtin:cubes", "--width", str(w), "--height", str(h)], method_args(method, extra),
                         os.path.join(tmp, "r.exr"), os.path.join(tmp, "s.json"))[0]["time_ms"]["render"] for _ in range(args.repeats))
            times[method].append(ms)
            cells.append(f"{ms:.0f} ({ms / (w * h / 1e6):.0f})")
        print(f"| {w}x{h} | " + " | ".join(cells) + " |", flush=True)
    print()
    if args.plot:
        plt = pyplot()
        pixels = [w * h / 1e6 for w, h in SIZES]
        fig, ax = plt.subplots(figsize=(5.5, 4))
        for method, ms in times.items():
            ax.plot(pixels, ms, "o-", label=method)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("megapixels (256x192 ... 1920x1080)")
        ax.set_ylabel("render ms (2 cores)")
        ax.set_title("builtin:cubes: time against pixels")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(args.plot, "speed_resolution.png"), dpi=100)
        plt.close(fig)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--streak", default="build/streak")
    parser.add_argument("--baseline", default="")
    parser.add_argument("--sections", default="profile,static,threads,memory,resolution")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--budgets", default="1000", help="section budget: the --memory-budget values (MB) beside the default")
    parser.add_argument("--dense-size", default="240x135", help="section quality: the dense move's image size")
    parser.add_argument("--embree-ladder", default="8,32,64,128,256,512,1024", help="section quality: embree's rays per sample")
    parser.add_argument("--accumulation-ladder", default="64,256", help="section quality: accumulation's shutter times")
    parser.add_argument("--cycles", default="", help="section shading: a ground-truth bench --out DIR, whose DIR/MODEL/cycles-1024.exr each row is scored against")
    parser.add_argument("--plot", default="")
    args = parser.parse_args()
    print(f"Machine: {machine()}.\n")
    sections = {"profile": profile, "static": static, "simd": simd, "dense": dense, "quality": quality, "budget": budget, "models": models,
                "shading": shading, "threads": threads, "memory": memory, "resolution": resolution}
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.sections.split(","):
            sections[name](args, tmp)


if __name__ == "__main__":
    main()
