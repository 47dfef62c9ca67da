#!/usr/bin/python3
"""The blur shell (Jones 2004) figures of docs/BENCHMARKS.md.

Sections (all by default, or pick with --sections):
  tables  The thesis' Tables 1-2 on streak, at 1024x768 (phong): the skinned models and a UV
          sphere of 500 to 500k triangles moving rigidly (builtin:sphere), default options
          (length 0.2 s, 10 subdivisions). Per model: triangles, SoM edges (mean per update),
          shell triangles and their ratio to sqrt(n) x subdivisions (the thesis' bound), the SoM
          time per update, the shell build, and the frame: the mesh alone (accumulation
          --samples 1, the frame without the method) against the mesh with its shell, on the
          CPU and through GL (blur-shell-gl; GPU timer where the driver has one, llvmpipe
          otherwise). The thesis reports the overhead as a share of the frame; so do the last
          columns.
  sheet   The quality trade-offs: Fox running, seen from its side (320x240, phong) at T = frame 14, the shell for
          subdivisions 2, 5, 10, 20 and lengths 0.1, 0.2, 0.3, 0.5 s beside accumulation
          (--samples 256) over [T - length, T] of the same animation, with the PSNR between
          them: docs/blur_shell_sheet.png (--plot) and a table.

usage: bench/blur_shell_bench.py [--streak build/streak] [--sections tables,sheet] [--plot docs/blur_shell_sheet.png] [--repeats 3]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import pyplot, run_sections  # noqa: E402

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "scenes")
MODELS = [
    ("CesiumMan", os.path.join(SCENES, "CesiumMan/glTF-Binary/CesiumMan.glb"), ["--frame", "20"]),
    ("Fox (Run)", os.path.join(SCENES, "Fox/glTF-Binary/Fox.glb"), ["--frame", "14", "--animation", "Run"]),
    ("RiggedFigure", os.path.join(SCENES, "RiggedFigure/glTF-Binary/RiggedFigure.glb"), ["--frame", "20"]),
]
SPHERES = [500, 2000, 8000, 32000, 128000, 500000]
SUBDIVISIONS = 10


def row(streak, name, spec, flags):
    out = os.path.join(streak.tmp, "t.png")
    size = "1024x768"
    mesh_cpu, _ = streak.render(spec, "accumulation", out, size=size, args=[*flags, "--samples", "1"])
    shell_cpu, stats = streak.render(spec, "blur-shell", out, size=size, args=flags)
    mesh_gl, mesh_gl_stats = streak.render(spec, "accumulation-gl", out, size=size, args=[*flags, "--samples", "1", "--repeat", "2"])
    shell_gl, gl_stats = streak.render(spec, "blur-shell-gl", out, size=size, args=[*flags, "--repeat", "2"])
    c, t = stats["counters"], stats["time_ms"]
    n = c["triangles"]  # the scene's, before the shell
    som_per_update = t["silhouette"] / SUBDIVISIONS
    bound = c["shell_triangles"] / (math.sqrt(n) * SUBDIVISIONS)
    gpu = "gpu passes" in gl_stats["time_ms"]
    gl_mesh = mesh_gl_stats["time_ms"].get("gpu passes", mesh_gl)
    gl_shell = gl_stats["time_ms"].get("gpu passes", shell_gl)
    print(f"| {name} | {int(n)} | {c['silhouette_edges_per_update']:.0f} | {int(c['shell_triangles'])} | {bound:.2f} "
          f"| {som_per_update:.3f} | {t['shell build'] + t['shell scene']:.2f} | {mesh_cpu:.1f} | {shell_cpu:.1f} "
          f"| {100 * t['silhouette'] / mesh_cpu:.1f}% | {100 * (shell_cpu - mesh_cpu) / mesh_cpu:.1f}% "
          f"| {gl_mesh:.1f} | {gl_shell:.1f}{'' if gpu else ' (wall)'} |", flush=True)


def tables(streak, args):
    print(f"### Jones' Tables 1-2 on streak (1024x768, phong; length 0.2 s, {SUBDIVISIONS} subdivisions)\n")
    print("| model | triangles n | SoM edges per update | shell triangles | shell / (sqrt(n) x subdivisions) | SoM ms per update "
          "| shell build ms | CPU frame, mesh only ms | CPU frame with shell ms | SoM share of the mesh frame | shell overhead "
          "| GL mesh only ms | GL with shell ms |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, path, flags in MODELS:
        if os.path.exists(path):
            row(streak, name, path, flags)
    for n in SPHERES:
        row(streak, f"sphere {n}", f"builtin:sphere?triangles={n}", [])
    print()


LENGTHS = [0.1, 0.2, 0.3, 0.5]
SHEET_SUBDIVISIONS = [2, 5, 10, 20]
FOX = os.path.join(SCENES, "Fox/glTF-Binary/Fox.glb")
T_FRAME, FPS = 14.0, 24.0


def sheet(streak, args):
    if not os.path.exists(FOX):
        print("(the sheet needs ../shared/scenes/Fox)\n")
        return
    print(f"### Quality trade-offs: Fox running seen from its side, T = frame {T_FRAME:g} (320x240, phong); PSNR of the shell against accumulation "
          "256 over [T - length, T]\n")
    print("| length | " + " | ".join(f"{s} subdivisions" for s in SHEET_SUBDIVISIONS) + " | accumulation ms | shell ms (10 subdivisions) |")
    print("|---" * (len(SHEET_SUBDIVISIONS) + 3) + "|")
    size, common = "320x240", ["--animation", "Run", "--camera-pos=150,45,60", "--camera-target=0,30,0"]
    images = {}
    for length in LENGTHS:
        ref = os.path.join(streak.tmp, f"acc-{length}.png")
        acc_ms, _ = streak.render(FOX, "accumulation", ref, size=size, repeats=1,
                                  args=[*common, "--frame", f"{T_FRAME - length * FPS:g}", "--shutter", f"{length * FPS:g}", "--samples", "256"])
        images[(length, "acc")] = ref
        cells, shell_ms = [], 0.0
        for s in SHEET_SUBDIVISIONS:
            out = os.path.join(streak.tmp, f"shell-{length}-{s}.png")
            ms, _ = streak.render(FOX, "blur-shell", out, size=size, repeats=1,
                                  args=[*common, "--frame", f"{T_FRAME:g}", "--option", f"length={length}", "--option", f"subdivisions={s}"])
            p = streak.psnr(ref, out)
            images[(length, s)] = (out, p)
            cells.append(f"{p:.1f} dB")
            if s == 10:
                shell_ms = ms
        print(f"| {length} s | " + " | ".join(cells) + f" | {acc_ms:.0f} | {shell_ms:.0f} |", flush=True)
    print()
    if args.plot:
        plt = pyplot()
        import matplotlib.image as mpimg
        cols = len(SHEET_SUBDIVISIONS) + 1
        fig, axes = plt.subplots(len(LENGTHS), cols, figsize=(2.6 * cols, 2.05 * len(LENGTHS)))
        for r, length in enumerate(LENGTHS):
            for c in range(cols):
                ax = axes[r][c]
                if c < len(SHEET_SUBDIVISIONS):
                    s = SHEET_SUBDIVISIONS[c]
                    path, p = images[(length, s)]
                    title = f"shell, {s} subdiv., {length} s: {p:.1f} dB"
                else:
                    path, title = images[(length, "acc")], f"accumulation over {length} s"
                ax.imshow(mpimg.imread(path))
                ax.set_title(title, fontsize=7)
                ax.axis("off")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"(sheet: {args.plot})\n")


if __name__ == "__main__":
    run_sections({"tables": tables, "sheet": sheet}, default_plot="docs/blur_shell_sheet.png")
