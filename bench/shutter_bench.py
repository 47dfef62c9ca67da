#!/usr/bin/python3
"""The shutter model's figures of docs/BENCHMARKS.md: one scene under each shutter.

builtin:fence (bars moving fast over a textured wall; 320x240, phong) under a box, a triangle
and a trapezoid curve, and rolling shutters of D = 0.25 and 0.05 (the curve box): the exact
methods (analytic, motion-path) and stochastic (64 times per pixel) against accumulation with
3000 shutter times (under a rolling shutter 3000 / D instants, each row weighing its own), with
their times; and the image sheet docs/shutter_sheet.png (--plot; needs ImageMagick's montage):
the analytic image per shutter, labelled.

Section agreement: every built-in scene at 64x48 (phong) under a triangle curve and under
--rolling-shutter 0.25, each method (exact ones at their defaults, stochastic and embree at
64 times per pixel, the GL twins at theirs) against accumulation --samples 3000 under the same
shutter: the PSNR table (tests/methods/shutter_methods_test.cpp enforces 45 dB exact, 40 dB
sampling at 48x36).

usage: bench/shutter_bench.py [--streak build/streak] [--sections sheet,agreement] [--plot docs/shutter_sheet.png] [--repeats 3]
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import run_sections  # noqa: E402

SCENE = "builtin:fence?bars=8"
SIZE = "320x240"
SHUTTERS = [
    ("box", []),
    ("triangle", ["--shutter-curve", "triangle"]),
    ("trapezoid:0.25", ["--shutter-curve", "trapezoid:0.25"]),
    ("rolling 0.25", ["--rolling-shutter", "0.25"]),
    ("rolling 0.05", ["--rolling-shutter", "0.05"]),
]
METHODS = [("analytic", []), ("motion-path", []), ("stochastic", ["--samples", "64"])]


def sheet(streak, args):
    print(f"### {SCENE} under each shutter ({SIZE}, phong)\n")
    print("PSNR against accumulation --samples 3000 under the same shutter; times in ms (least of the repeats).\n")
    print("| shutter | accumulation 3000 ms | " + " | ".join(f"{m} ms | {m} dB" for m, _ in METHODS) + " |")
    print("|---|---|" + "---|---|" * len(METHODS))
    tiles = []
    for name, flags in SHUTTERS:
        tag = name.replace(" ", "_").replace(":", "_")
        ref = os.path.join(streak.tmp, f"ref-{tag}.exr")
        ref_ms, _ = streak.render(SCENE, "accumulation", ref, size=SIZE, args=["--samples", "3000", *flags], repeats=1)
        cells = []
        for method, extra in METHODS:
            out = os.path.join(streak.tmp, f"{method}-{tag}.exr")
            ms, _ = streak.render(SCENE, method, out, size=SIZE, args=[*extra, *flags])
            cells.append(f"{ms:.0f} | {streak.psnr(ref, out):.1f}")
            if method == "analytic":
                png = os.path.join(streak.tmp, f"{tag}.png")
                streak.render(SCENE, method, png, size=SIZE, args=flags, repeats=1)
                tiles.append((name, png))
        print(f"| {name} | {ref_ms:.0f} | " + " | ".join(cells) + " |", flush=True)
    if args.plot:
        command = ["montage"]
        for name, png in tiles:
            command += ["-label", name, png]
        command += ["-tile", f"{len(tiles)}x1", "-geometry", "+4+4", "-pointsize", "18", args.plot]
        subprocess.run(command, check=True)
        print(f"\nSheet: {args.plot}")


BUILTINS = ["cubes", "rotating-cube", "spin", "clothball", "sphere", "crossing", "twist", "fence", "pan", "translucent"]
AGREEMENT = [("analytic", []), ("higher-order", []), ("motion-path", []), ("stochastic", ["--samples", "64"]),
             ("embree", ["--samples", "64"]), ("accumulation-gl", []), ("motion-path-gl", [])]


def agreement(streak, args):
    print("### Agreement under the shutter (64x48, phong): PSNR (dB) against accumulation --samples 3000\n")
    print("| scene | shutter | " + " | ".join(m + (" 64" if extra else "") for m, extra in AGREEMENT) + " |")
    print("|---|---|" + "---:|" * len(AGREEMENT))
    for scene in BUILTINS:
        for name, flags in [("triangle", ["--shutter-curve", "triangle"]), ("rolling 0.25", ["--rolling-shutter", "0.25"])]:
            ref = os.path.join(streak.tmp, "agree-ref.exr")
            streak.render("builtin:" + scene, "accumulation", ref, size="64x48", args=["--samples", "3000", *flags], repeats=1)
            cells = []
            for method, extra in AGREEMENT:
                out = os.path.join(streak.tmp, "agree.exr")
                streak.render("builtin:" + scene, method, out, size="64x48", args=[*extra, *flags], repeats=1)
                cells.append(f"{streak.psnr(ref, out):.1f}")
            print(f"| {scene} | {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    run_sections({"sheet": sheet, "agreement": agreement}, "docs/shutter_sheet.png")
