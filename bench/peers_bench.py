#!/usr/bin/python3
"""Every method against the peers a user would pick instead: docs/BENCHMARKS.md "Peers".

For each scene: the reference is accumulation with 3000 shutter times; each method renders over
its settings (accumulation, stochastic and embree over S; post-filter over tile and taps;
motion-path, analytic and higher-order at their defaults and a budget or two), and each
render's time ("render" phase of --stats, least of --repeats) and PSNR give one point of its
time-quality curve. Prints a table per scene (all points), and the summary: per method, the
least time that reaches 40 dB and 50 dB, and its ratio to the fastest peer (accumulation,
stochastic, embree, post-filter) at that quality. With --plot DIR, one Pareto plot per scene
(DIR/pareto_<scene>_<size>.png, log time on x). A sampling method's ladder of S stops at the
first setting within 70 dB of the reference. A scene that does not move over the shutter (one
accumulation pass equals four) takes one pass as its reference.

Section converge: embree at S = 1024 against accumulation at S = 1024 on every shared model.

Section failures: post-filter's known failure modes beside accumulation 3000 and analytic, as an
image sheet (DIR/post_filter_failures.png): thin bars over a wall moving differently (fence),
translucent panes (translucent), a fast spin (spin), and a moving camera (pan).

usage: bench/peers_bench.py [--streak build/streak] [--sections builtin,gltf,failures,converge] [--size 320x240] [--plot docs] [--repeats 1]
"""
import argparse
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import Streak, machine, pyplot  # noqa: E402

BUILTIN = ["cubes", "rotating-cube", "spin", "clothball", "sphere", "crossing", "twist", "fence", "pan", "translucent"]
SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "scenes")
GLTF = [  # name, file, flags: the frames and shutters of bench/ground_truth_bench.py (every shared model)
    ("CesiumMan", "CesiumMan/glTF-Binary/CesiumMan.glb", ["--frame", "12", "--shutter", "2"]),
    ("Fox", "Fox/glTF-Binary/Fox.glb", ["--frame", "10", "--shutter", "1", "--animation", "Run"]),
    ("RiggedFigure", "RiggedFigure/glTF-Binary/RiggedFigure.glb", ["--frame", "10", "--shutter", "2"]),
    ("BoxAnimated", "BoxAnimated/glTF-Binary/BoxAnimated.glb", ["--frame", "12", "--shutter", "3"]),
    ("AnimatedTriangle", "AnimatedTriangle/glTF/AnimatedTriangle.gltf", ["--frame", "3", "--shutter", "2"]),
    ("AnimatedCube", "AnimatedCube/glTF/AnimatedCube.gltf", ["--frame", "12", "--shutter", "2"]),
    ("InterpolationTest", "InterpolationTest/glTF-Binary/InterpolationTest.glb",
     ["--frame", "12", "--shutter", "3", "--animation", "CubicSpline Rotation"]),
    ("SimpleSkin", "SimpleSkin/glTF/SimpleSkin.gltf", ["--frame", "12", "--shutter", "6"]),
    ("RiggedSimple", "RiggedSimple/glTF-Binary/RiggedSimple.glb", ["--frame", "20", "--shutter", "3"]),
    ("SimpleMorph", "SimpleMorph/glTF/SimpleMorph.gltf", ["--frame", "24", "--shutter", "12"]),
    ("AnimatedMorphCube", "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", ["--frame", "30", "--shutter", "6"]),
    ("MorphStressTest", "MorphStressTest/glTF-Binary/MorphStressTest.glb", ["--frame", "24", "--shutter", "6", "--animation", "TheWave"]),
    ("ToyCar", "ToyCar/glTF/ToyCar.gltf", []),  # static: its first glTF camera
    ("MetalRoughSpheresNoTextures", "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", []),  # static
]
PEERS = ["accumulation", "stochastic", "embree", "post-filter"]
SETTINGS = {
    "accumulation": [["--samples", str(s)] for s in (1, 2, 4, 8, 16, 32, 64, 128, 256)],
    "stochastic": [["--samples", str(s)] for s in (1, 2, 4, 8, 16, 32, 64)],
    "embree": [["--samples", str(s)] for s in (1, 2, 4, 8, 16, 32, 64, 128)],
    "post-filter": [["--option", f"tile={k}", "--option", f"samples={n}"] for k, n in ((10, 15), (20, 15), (20, 31), (40, 31))],
    "motion-path": [[]],
    "analytic": [[], ["--max-intervals", "8"]],
    "higher-order": [[]],
}


def label(args):
    return " ".join(a for a in args if not a.startswith("--")) or "default"


LADDERS = {"accumulation", "stochastic", "embree"}  # settings in rising S: a converged one ends the ladder
CONVERGED_DB = 70.0


def points(streak, spec, flags, size, ref):
    out = os.path.join(streak.tmp, "p.exr")
    rows = []
    for method, settings in SETTINGS.items():
        for args in settings:
            ms, _ = streak.render(spec, method, out, size=size, args=[*flags, *args])
            rows.append((method, label(args), ms, streak.psnr(ref, out)))
            if method in LADDERS and rows[-1][3] >= CONVERGED_DB:
                break  # more samples only cost time: it already is the reference
    return rows


def reference(streak, spec, flags, size):
    """Accumulation with 3000 shutter times; where the scene does not move (one pass and four
    passes give the same image: four equal images average to it exactly) one pass is that
    image, and the 3000 passes are skipped."""
    ref, four = os.path.join(streak.tmp, "ref.exr"), os.path.join(streak.tmp, "ref4.exr")
    streak.render(spec, "accumulation", ref, size=size, args=[*flags, "--samples", "1"], repeats=1)
    streak.render(spec, "accumulation", four, size=size, args=[*flags, "--samples", "4"], repeats=1)
    if streak.psnr(ref, four) >= 100.0:
        print("(still over the shutter: the reference is one accumulation pass, which 3000 would repeat)\n")
        return ref
    streak.render(spec, "accumulation", ref, size=size, args=[*flags, "--samples", "3000"], repeats=1)
    return ref


def fastest(rows, method, target):
    times = [ms for m, _, ms, db in rows if m == method and db >= target]
    return min(times) if times else None


def report(name, rows, plot_dir, size):
    print(f"#### {name} ({size})\n")
    print("| method | setting | ms | PSNR |")
    print("|---|---|---:|---:|")
    for method, setting, ms, db in rows:
        print(f"| {method} | {setting} | {ms:.0f} | {db:.1f} dB |")
    print()
    summary = []
    for target in (40.0, 50.0):
        peer_times = [t for t in (fastest(rows, p, target) for p in PEERS) if t is not None]
        best_peer = min(peer_times) if peer_times else None
        for method in SETTINGS:
            t = fastest(rows, method, target)
            ratio = f"{t / best_peer:.2f}" if t is not None and best_peer else "—"
            summary.append((target, method, t, ratio))
    print(f"| {name}: time to reach | " + " | ".join(SETTINGS) + " |")
    print("|---|" + "---:|" * len(SETTINGS))
    for target in (40.0, 50.0):
        cells = []
        for method in SETTINGS:
            (_, _, t, ratio), = [s for s in summary if s[0] == target and s[1] == method]
            cells.append("—" if t is None else f"{t:.0f} ms ({ratio})")
        print(f"| {target:.0f} dB (ratio to the fastest peer) | " + " | ".join(cells) + " |")
    print(flush=True)
    if plot_dir:
        plt = pyplot()
        fig, ax = plt.subplots(figsize=(6, 4))
        for method in SETTINGS:
            pts = sorted((ms, db) for m, _, ms, db in rows if m == method)
            if pts:
                ax.plot([p[0] for p in pts], [min(p[1], 80.0) for p in pts], "o-" if len(pts) > 1 else "s", label=method)
        ax.set_xscale("log")
        ax.set_xlabel(f"ms per frame ({size}, 2 cores)")
        ax.set_ylabel("PSNR dB vs accumulation 3000")
        ax.set_title(name)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(plot_dir, f"pareto_{re.sub(r'[^A-Za-z0-9]+', '_', name)}_{size}.png"), dpi=100)
        plt.close(fig)


def failures(streak, size, plot_dir):
    print(f"#### post-filter's failure modes ({size}): PSNR against accumulation 3000\n")
    print("| scene | post-filter | analytic | one instant |")
    print("|---|---:|---:|---:|")
    scenes = ["fence", "translucent", "spin", "pan"]
    images = []
    for name in scenes:
        ref = os.path.join(streak.tmp, f"fail-{name}-ref.png")
        streak.render("builtin:" + name, "accumulation", ref, size=size, args=["--samples", "3000"], repeats=1)
        row = [ref]
        cells = []
        for method, args in (("post-filter", []), ("analytic", []), ("accumulation", ["--samples", "1"])):
            out = os.path.join(streak.tmp, f"fail-{name}-{method}.png")
            streak.render("builtin:" + name, method, out, size=size, args=args, repeats=1)
            cells.append(f"{streak.psnr(ref, out):.1f} dB")
            row.append(out)
        images.append((name, row, cells))
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)
    print()
    if plot_dir:
        plt = pyplot()
        import matplotlib.image as mpimg
        titles = ["accumulation 3000", "post-filter", "analytic", "one instant (t = 0.5)"]
        fig, axes = plt.subplots(len(images), 4, figsize=(11, 2.2 * len(images)))
        for r, (name, row, cells) in enumerate(images):
            for c, path in enumerate(row):
                ax = axes[r][c]
                ax.imshow(mpimg.imread(path))
                ax.set_title(f"{name}: {titles[c]}" + (f" ({cells[c - 1]})" if c > 0 else ""), fontsize=7)
                ax.axis("off")
        fig.tight_layout()
        fig.savefig(os.path.join(plot_dir, "post_filter_failures.png"), dpi=100)
        print(f"(sheet: {os.path.join(plot_dir, 'post_filter_failures.png')})\n")


def converge(streak, size):
    """embree converged: S = 1024 ray times per sample against accumulation's 1024 shutter times,
    on every shared model (the issue's 33 dB target; tests check the built-in scenes)."""
    print(f"### embree S = 1024 against accumulation S = 1024 on the shared models ({size}, phong)\n")
    print("| model | triangles | PSNR (dB) | embree ms | accumulation ms |")
    print("|---|---:|---:|---:|---:|")
    a, b = os.path.join(streak.tmp, "conv-a.exr"), os.path.join(streak.tmp, "conv-b.exr")
    for name, path, flags in GLTF:
        spec = os.path.join(SCENES, path)
        if not os.path.exists(spec):
            continue
        ms_e, stats = streak.render(spec, "embree", a, size=size, args=[*flags, "--samples", "1024"], repeats=1)
        ms_a, _ = streak.render(spec, "accumulation", b, size=size, args=[*flags, "--samples", "1024"], repeats=1)
        print(f"| {name} | {int(stats['counters']['triangles'])} | {streak.psnr(a, b):.1f} | {ms_e:.0f} | {ms_a:.0f} |", flush=True)
    print()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--streak", default="build/streak")
    parser.add_argument("--sections", default="builtin,gltf,failures")
    parser.add_argument("--size", default="320x240")
    parser.add_argument("--plot", default="")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--scenes", default="", help="comma-separated subset of the scene names")
    args = parser.parse_args()
    print(f"Machine: {machine()}. Least of {args.repeats} runs per render; Phong, --aa 1.\n")
    chosen = set(args.scenes.split(",")) if args.scenes else None
    with tempfile.TemporaryDirectory() as tmp:
        streak = Streak(args.streak, tmp, args.repeats)
        cases = []
        if "builtin" in args.sections:
            cases += [(n, "builtin:" + n, []) for n in BUILTIN]
        if "gltf" in args.sections:
            cases += [(n, os.path.join(SCENES, p), f) for n, p, f in GLTF if os.path.exists(os.path.join(SCENES, p))]
        for name, spec, flags in cases:
            if chosen and name not in chosen:
                continue
            ref = reference(streak, spec, flags, args.size)
            report(name, points(streak, spec, flags, args.size, ref), args.plot, args.size)
        if "failures" in args.sections:
            failures(streak, args.size, args.plot)
        if "converge" in args.sections:
            converge(streak, args.size)


if __name__ == "__main__":
    main()
