#!/usr/bin/python3
"""The higher-order motion (Gribel et al. 2013) figures of docs/BENCHMARKS.md.

Sections (all by default, or pick with --sections):
  quality    spin, clothball and rotating-cube?speed=4 (and at 90 degrees: spin?angle=90,
             clothball?angle=90, rotating-cube?speed=2) at 256x192, unlit, --aa 2, against
             accumulation (--samples 3000) of the true motion (keys=64): PSNR and visibility
             accuracy of analytic on linear keys (2, 3, 5, 9 keys) and of higher-order on the
             quadratic (keys=3 curve=bezier) and cubic (keys=4) through the same poses.
  gltf       The skinned models at long shutters (CesiumMan over 6 frames, Fox running over 4),
             320x240, against accumulation 3000 of 64 keys: analytic on 2, 3, 5 and 9 linear keys,
             higher-order on --motion-curve bezier with 3 and 4 keys (the curve through the
             animation at 3 or 4 times, and the least-squares fit to 4n + 1 poses).
  adaptive   Chosen keys against chosen Bezier pieces (issue 32, item 3): the curved built-ins
             (spin, clothball, rotating-cube at speeds 1 and 4, cubes) exported as glTF with 64 keys, CesiumMan over 6 frames and Fox
             running over 4 (each through one fixed camera), 320x240, unlit, --aa 2, against accumulation 3000 of 64 keys: the
             linear default (analytic), the Bezier default (higher-order, --motion-curve bezier,
             pieces of degree 2 and 3) and 64 linear keys (analytic): PSNR, keys or pieces, and
             the render time.
  traversal  The paper's tables on the curved scenes (keys=3 curve=bezier): sample test
             efficiency and time of bounding-box traversal, generalized INTERVAL with 4, 16
             and 64 sub-intervals and TILE with 4x4, 2x2 and 1x1 blocks; TILE's speed-up over
             the bounding box and what its two tests (Triangle-Tile, Edge-Tile) culled.
  solvers    Closed form against Bezier clipping: time and agreement (PSNR between them).
  speed      Time per frame at 1024x768 of higher-order against analytic with the same poses
             (3 keys), on spin and clothball.

Times are the "render" phase of --stats, the least of --repeats runs. With --plot DIR the
quality and traversal sections also draw DIR/higher_order_quality.png and
DIR/higher_order_traversal.png.

usage: bench/higher_order_bench.py [--streak build/streak] [--sections quality,gltf,adaptive,traversal,solvers,speed] [--repeats 3] [--plot docs]
"""
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import pyplot, run_sections  # noqa: E402

CURVED = ["spin", "clothball", "rotating-cube?speed=4"]
MODERATE = ["spin?angle=90", "clothball?angle=90", "rotating-cube?speed=2"]  # quality only: the paper's 90 degrees
FLAGS = ["--aa", "2", "--shading", "unlit"]


def scene(name, keys, curve="linear"):
    return f"builtin:{name}{'&' if '?' in name else '?'}keys={keys}&curve={curve}"


def reference(streak, name):
    path = os.path.join(streak.tmp, name.replace("?", "_").replace("=", "_") + "-truth.exr")
    if not os.path.exists(path):
        streak.render(scene(name, 64), "accumulation", path, args=["--samples", "3000", *FLAGS], repeats=1)
    return path


def quality(streak, args):
    print("### Curved motion against its true path (256x192, unlit, --aa 2; reference: accumulation 3000 of keys=64)\n")
    print("| scene | analytic 2 keys | analytic 3 | analytic 5 | analytic 9 | higher-order n=2 (3 keys) | higher-order n=3 (4 keys) | visibility accuracy n=2 |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    out = os.path.join(streak.tmp, "q.exr")
    curves = {}
    for name in CURVED + MODERATE:
        ref = reference(streak, name)
        linear, curved = [], []
        for keys in (2, 3, 5, 9):
            streak.render(scene(name, keys), "analytic", out, args=FLAGS, repeats=1)
            linear.append((keys, streak.psnr(ref, out)))
        for keys in (3, 4):
            _, stats = streak.render(scene(name, keys, "bezier"), "higher-order", out, args=[*FLAGS, "--option", "check-visibility=20000"], repeats=1)
            curved.append((keys, streak.psnr(ref, out)))
            if keys == 3:
                accuracy = stats["counters"]["visibility_accuracy"]
        curves[name] = (linear, curved)
        print(f"| {name} | " + " | ".join(f"{db:.1f} dB" for _, db in linear + curved) + f" | {100 * accuracy:.2f}% |", flush=True)
    print()
    if args.plot:
        plt = pyplot()
        fig, axes = plt.subplots(2, 3, figsize=(11, 6.5), sharey=True)
        for ax, (name, (linear, curved)) in zip(axes.flat, curves.items()):
            ax.plot([k for k, _ in linear], [db for _, db in linear], "o-", label="analytic, K linear keys")
            ax.plot([k for k, _ in curved], [db for _, db in curved], "s--", color="C3", label="higher-order, n = K - 1")
            ax.axhline(45.0, color="grey", lw=0.8, ls=":", label="target n = 2: 45 dB")
            ax.set_title(name, fontsize=9)
            ax.set_xticks([2, 3, 4, 5, 9])
            ax.set_xlabel("poses (keys) of the true motion")
            ax.grid(alpha=0.3)
        axes[0][0].set_ylabel("PSNR dB vs the true motion")
        axes[1][0].set_ylabel("PSNR dB vs the true motion")
        axes[0][0].legend(fontsize=7)
        fig.suptitle("Curved motion: chords against Bezier curves through the same poses (256x192)", fontsize=10)
        fig.tight_layout()
        fig.savefig(os.path.join(args.plot, "higher_order_quality.png"), dpi=90)
        plt.close(fig)


MODELS = [
    ("CesiumMan", "CesiumMan/glTF-Binary/CesiumMan.glb", ["--frame", "12", "--shutter", "6"]),
    ("Fox (Run)", "Fox/glTF-Binary/Fox.glb", ["--frame", "10", "--shutter", "4", "--animation", "Run"]),
]
SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "scenes")


def gltf(streak, args):
    print("### Skinned models at long shutters (320x240, unlit, --aa 2; reference: accumulation 3000 of 64 keys)\n")
    print("| model | analytic 2 keys | analytic 3 | analytic 5 | analytic 9 | higher-order n=2 (3 keys) | n=2 least squares (9 poses) "
          "| higher-order n=3 (4 keys) | n=3 least squares (13 poses) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    out, ref = os.path.join(streak.tmp, "g.exr"), os.path.join(streak.tmp, "g-ref.exr")
    for name, path, flags in MODELS:
        model = os.path.join(SCENES, path)
        streak.render(model, "accumulation", ref, size="320x240", args=[*flags, *FLAGS, "--samples", "3000", "--motion-keys", "64"], repeats=1)
        row = []
        for keys in (2, 3, 5, 9):
            streak.render(model, "analytic", out, size="320x240", args=[*flags, *FLAGS, "--motion-keys", str(keys)], repeats=1)
            row.append(f"{streak.psnr(ref, out):.1f} dB")
        for keys in (3, 4):
            for fit in (["--motion-fit-samples", "0"], ["--motion-fit-samples", str(4 * (keys - 1) + 1)]):
                streak.render(model, "higher-order", out, size="320x240",
                              args=[*flags, *FLAGS, "--motion-keys", str(keys), "--motion-curve", "bezier", *fit], repeats=1)
                row.append(f"{streak.psnr(ref, out):.1f} dB")
        print(f"| {name} | " + " | ".join(row) + " |", flush=True)
    print()


ADAPTIVE_BUILTINS = ["spin", "clothball", "rotating-cube", "rotating-cube?speed=4", "cubes"]
# A model without a camera is framed from the bounds of its key poses, which differ with the
# keys; each image here is seen through one camera (the framing of the model's default shutter,
# from `streak export`), so that only the motion differs.
CAMERAS = {"CesiumMan": ["--camera-pos=-0.058,0.718,2.386", "--camera-target=-0.058,0.718,0", "--fov", "45"],
           "Fox (Run)": ["--camera-pos=-9.15,37.26,156.15", "--camera-target=-9.15,37.26,0", "--fov", "45"]}


def adaptive(streak, args):
    print("### Chosen keys against chosen Bezier pieces (320x240, unlit, --aa 2; reference: accumulation 3000 of 64 keys)\n")
    print("| scene | linear default (analytic): segments, PSNR, ms | Bezier default n = 2 (higher-order): pieces, PSNR, ms "
          "| n = 3: pieces, PSNR, ms | higher-order on the linear default: ms | 64 linear keys (analytic): PSNR, ms |")
    print("|---|---|---|---|---:|---|")
    out, ref = os.path.join(streak.tmp, "ad.exr"), os.path.join(streak.tmp, "ad-ref.exr")
    scenes = []
    for name in ADAPTIVE_BUILTINS:
        glb = os.path.join(streak.tmp, re.sub(r"[^A-Za-z0-9.-]", "_", name) + "-64.glb")
        subprocess.run([streak.binary, "export", scene(name, 64), glb], check=True)
        scenes.append((name, glb, ["--frame", "0", "--shutter", "24"]))
    scenes += [(name, os.path.join(SCENES, path), [*flags, *CAMERAS[name]]) for name, path, flags in MODELS]
    size = "320x240"
    for name, model, flags in scenes:
        streak.render(model, "accumulation", ref, size=size, args=[*flags, *FLAGS, "--samples", "3000", "--motion-keys", "64"], repeats=1)

        def run(method, extra):
            ms, stats = streak.render(model, method, out, size=size, args=[*flags, *FLAGS, *extra])
            c = stats["counters"]
            pieces = c.get("motion_bezier_pieces", c["motion_keys"] - 1)
            return pieces, streak.psnr(ref, out), ms

        cells = []
        for method, extra in (("analytic", []), ("higher-order", ["--motion-curve", "bezier"]),
                              ("higher-order", ["--motion-curve", "bezier", "--motion-curve-order", "3"])):
            pieces, db, ms = run(method, extra)
            cells.append(f"{pieces:.0f}, {db:.1f} dB, {ms:.0f}")
        _, _, ho_linear = run("higher-order", [])
        _, db, ms = run("analytic", ["--motion-keys", "64"])
        print(f"| {name} | " + " | ".join(cells) + f" | {ho_linear:.0f} | {db:.1f} dB, {ms:.0f} |", flush=True)
    print()


def traversal(streak, args):
    print("### Traversal: sample test efficiency and time (256x192, unlit, --aa 2, keys=3 curve=bezier)\n")
    options = ["traversal=bbox", "intervals=4", "intervals=16", "intervals=64", "traversal=tile&tile=4", "traversal=tile&tile=2",
               "traversal=tile&tile=1"]
    print("| scene | bbox STE | ms | INTERVAL 4 STE | ms | INTERVAL 16 STE | ms | INTERVAL 64 STE | ms | TILE 4x4 STE | ms | TILE 2x2 STE | ms | TILE 1x1 STE | ms |")
    print("|---|" + "---:|" * (2 * len(options)))
    out = os.path.join(streak.tmp, "t.exr")
    results = {}
    for name in CURVED:
        row = []
        for combined in options:
            option = [a for pair in combined.split("&") for a in ("--option", pair)]
            ms, stats = streak.render(scene(name, 3, "bezier"), "higher-order", out, args=[*FLAGS, *option])
            results[name, combined] = (ms, stats["counters"])
            row += [f"{100 * stats['counters']['sample_test_efficiency']:.1f}%", f"{ms:.0f}"]
        print(f"| {name} | " + " | ".join(row) + " |", flush=True)
    print()
    print("TILE's two tests: blocks culled for the whole shutter (of those, by the Triangle-Tile test alone), eighths of the "
          "shutter proved missed (by the Triangle-Tile test), and the speed-up over the bounding box\n")
    print("| scene | blocks | tested | culled | by Triangle-Tile alone | time culled | by Triangle-Tile | speed-up over bbox |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for name in CURVED:
        bbox_ms = results[name, "traversal=bbox"][0]
        for side in (4, 2, 1):
            ms, c = results[name, f"traversal=tile&tile={side}"]
            tested = c["tile_tests"]
            print(f"| {name} | {side}x{side} | {tested:.0f} | {100 * c['tiles_culled'] / tested:.1f}% | "
                  f"{100 * c['tiles_culled_by_triangle_test'] / tested:.1f}% | {100 * c['tile_time_culled_fraction']:.1f}% | "
                  f"{100 * c['tile_time_culled_by_triangle_test']:.1f}% | {bbox_ms / ms:.2f} |", flush=True)
    print()
    if args.plot:
        plt = pyplot()
        fig, axes = plt.subplots(1, len(CURVED), figsize=(12, 3.6))
        for ax, name in zip(axes, CURVED):
            for combined in options:
                ms, c = results[name, combined]
                side = re.search(r"tile=(\d)", combined)
                label = f"TILE {side[1]}x{side[1]}" if side else ("bbox" if "bbox" in combined else "INTERVAL " + combined.split("=")[1])
                marker = "o" if "tile" in combined else ("s" if "bbox" in combined else "^")
                ax.plot(ms, 100 * c["sample_test_efficiency"], marker, color="C0" if "tile" in combined else ("C3" if "bbox" in combined else "C2"))
                ax.annotate(label, (ms, 100 * c["sample_test_efficiency"]), fontsize=7, xytext=(3, 3), textcoords="offset points")
            ax.set_title(name, fontsize=9)
            ax.set_xlabel("ms per frame (256x192, 2 cores)")
            ax.grid(alpha=0.3)
        axes[0].set_ylabel("sample test efficiency %")
        fig.suptitle("Traversal: bounding box (red), INTERVAL (green), TILE (blue)", fontsize=10)
        fig.tight_layout()
        fig.savefig(os.path.join(args.plot, "higher_order_traversal.png"), dpi=90)
        plt.close(fig)


def solvers(streak, args):
    print("### Root solvers: closed form (Ferrari) against Bezier clipping (256x192, unlit, --aa 2, keys=3 curve=bezier)\n")
    print("| scene | closed form ms | clipping ms | PSNR between them |")
    print("|---|---:|---:|---:|")
    a, b = os.path.join(streak.tmp, "a.exr"), os.path.join(streak.tmp, "b.exr")
    for name in CURVED:
        closed, _ = streak.render(scene(name, 3, "bezier"), "higher-order", a, args=[*FLAGS, "--option", "solver=closed-form"])
        clipping, _ = streak.render(scene(name, 3, "bezier"), "higher-order", b, args=[*FLAGS, "--option", "solver=clipping"])
        print(f"| {name} | {closed:.0f} | {clipping:.0f} | {streak.psnr(a, b):.1f} dB |", flush=True)
    print()


def speed(streak, args):
    print("### Time per frame at 1024x768 (phong, --aa 1): higher-order against analytic on the same 3 poses\n")
    print("| scene | analytic (3 linear keys) ms | higher-order (n=2) ms | ratio |")
    print("|---|---:|---:|---:|")
    out = os.path.join(streak.tmp, "s.exr")
    for name in ["spin", "clothball"]:
        an, _ = streak.render(scene(name, 3), "analytic", out, size="1024x768")
        ho, _ = streak.render(scene(name, 3, "bezier"), "higher-order", out, size="1024x768")
        print(f"| {name} | {an:.0f} | {ho:.0f} | {ho / an:.2f} |", flush=True)
    print()


if __name__ == "__main__":
    run_sections({"quality": quality, "gltf": gltf, "adaptive": adaptive, "traversal": traversal, "solvers": solvers, "speed": speed}, default_plot="")
