#!/usr/bin/env python3
"""What the deep image (--deep) holds and costs, and that it flattens to the beauty (issue 29).

Each model at 320x240 (its frame, shutter and animation as bench/ground_truth_bench.py has
them) is rendered by each method with `--aa 8 --transparent`, once plain and once with
`--deep`, --repeats times each. It reports the least `render` time of each (from --stats) and
the deep image's cost as a share of the plain render, its samples (per covered pixel, the most
in a pixel, and the layers the bound joined), the deep file's size against the flat EXR's, and
the largest difference between OpenImageIO's flatten of the deep file (ImageBufAlgo.flatten,
front to back) and the beauty's RGBA, over every pixel and channel.

Usage: bench/deep_bench.py [--models CesiumMan,Fox,BoxAnimated,ToyCar] [--methods analytic,motion-path]
    [--aa 8] [--repeats 3] [--deep-samples 16] [--out DIR] [--streak build/streak]
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import cycles_reference  # noqa: E402
import ground_truth_bench  # noqa: E402


def render(args, scene, flags, method, out, extra):
    """The least `render` ms of --repeats renders, and the last's stats."""
    best, stats = None, None
    for _ in range(args.repeats):
        stats_path = out + ".json"
        subprocess.run([args.streak, "render", scene, *ground_truth_bench.scene_flags(flags), "-m", method, "--width", str(args.width),
                        "--height", str(args.height), "--aa", str(args.aa), "--transparent", "-o", out, "--stats", stats_path, *extra],
                       check=True)
        with open(stats_path) as f:
            stats = json.load(f)
        ms = dict(stats["time_ms"])["render"]
        best = ms if best is None else min(best, ms)
    return best, stats


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--models", default="CesiumMan,Fox,BoxAnimated,ToyCar")
    parser.add_argument("--methods", default="analytic,motion-path")
    parser.add_argument("--aa", type=int, default=8)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--deep-samples", type=int, default=16)
    parser.add_argument("--out", default="/tmp/streak-deep-bench")
    parser.add_argument("--streak", default=cycles_reference.STREAK)
    args = parser.parse_args()
    import OpenImageIO as oiio  # python3-openimageio: an independent reader and flatten

    models = {m[0]: m for m in ground_truth_bench.MODELS}
    print("| model | method | plain ms | with --deep ms | deep cost | samples per covered pixel | most in a pixel | layers joined | "
          "deep file / flat EXR | flatten − beauty (max) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name in args.models.split(","):
        _, path, flags = models[name]
        scene = os.path.join(ground_truth_bench.SCENES, path)
        folder = os.path.join(args.out, name)
        os.makedirs(folder, exist_ok=True)
        for method in args.methods.split(","):
            flat = os.path.join(folder, f"{method}.exr")
            plain_ms, _ = render(args, scene, flags, method, flat, [])
            beauty, deep = os.path.join(folder, f"{method}-beauty.exr"), os.path.join(folder, f"{method}-deep.exr")
            deep_ms, stats = render(args, scene, flags, method, beauty, ["--deep", deep, "--deep-samples", str(args.deep_samples)])
            buf = oiio.ImageBuf(deep)
            data = buf.deepdata()
            counts = np.array([data.samples(i) for i in range(data.pixels)])
            flattened = oiio.ImageBufAlgo.flatten(buf).get_pixels(oiio.FLOAT)[..., :4]
            reference = oiio.ImageBuf(beauty).get_pixels(oiio.FLOAT)[..., :4]
            covered = counts[counts > 0]
            counters = stats["counters"]
            print(f"| {name} | {method} | {plain_ms:.0f} | {deep_ms:.0f} | {100 * (deep_ms / plain_ms - 1):+.0f}% | "
                  f"{covered.mean():.2f} | {counts.max()} | {counters['deep_layers_merged']:.0f} | "
                  f"{os.path.getsize(deep) / os.path.getsize(flat):.1f}× ({os.path.getsize(deep) / 1024:.0f} KB) | "
                  f"{np.abs(flattened - reference).max():.1e} |", flush=True)


if __name__ == "__main__":
    main()
