#!/usr/bin/env python3
"""streak's alpha and Cryptomatte coverage against Cycles' (issue 29): ground truth streak did not write.

Each model at 320x240 (its frame, shutter and animation as bench/ground_truth_bench.py has them)
is rendered by Cycles twice at --spp (1024; seeds 0 and 1) with a transparent film and
Cryptomatte object and material layers and the Normal pass (bench/cycles_reference.py
--passes), and by streak with `--aa 8 --shading unlit --transparent --passes
object_id,material_id,normal` (--method, analytic by default). For the alpha, for each object's
and material's matte (the coverage of its name summed over the ranks, as a compositor's
Cryptomatte node reads it) and for the normal (Blender's z-up axes turned to glTF's y-up, as its
importer turns the scene; RMS of the vector difference) it reports:
  - noise: Cycles' own RMS noise, RMS(seed 0 - seed 1) / sqrt(2);
  - error: RMS(streak - Cycles seed 0), which is noise and streak's own error together;
  - excess: sqrt(max(error^2 - noise^2, 0)), the part of the error Cycles' noise does not
    explain (0: streak agrees with Cycles within its noise).
RMS are over every pixel of the image (mattes: over the pixels where either has coverage).
Names are matched exactly between the two manifests; unmatched names are listed.

Usage: bench/passes_bench.py [--models CesiumMan,Fox,BoxAnimated] [--method analytic] [--samples S] [--aa 8]
    [--spp 1024] [--out DIR] [--streak build/streak] [--blender blender] [--reuse-cycles]
"""
import argparse
import json
import math
import os
import struct
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import cycles_reference  # noqa: E402
import ground_truth_bench  # noqa: E402


def streak_module(streak):
    """The streak Python module built beside the CLI (it reads the multilayer EXRs)."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(streak)), "python"))
    import streak as module  # noqa: E402
    return module


def manifest(layers, type_name):
    """{name: float ID} of the Cryptomatte type whose metadata name ends in type_name."""
    metadata = layers["metadata"]
    for key, value in metadata.items():
        if key.endswith("/name") and value.split(".")[-1] == type_name:
            text = metadata.get(key[:-len("name")] + "manifest", "{}")
            return {name: struct.unpack(">f", bytes.fromhex(hexid))[0] for name, hexid in json.loads(text).items()}, value
    return {}, None


def matte(layers, layer_name, name_id):
    """The coverage of one ID summed over the ranks of layer `layer_name` ({layer}00.r ...)."""
    out = None
    for level in range(100):
        base = f"{layer_name}{level:02d}"
        if base + ".r" not in layers:
            break
        for idc, cov in ((".r", ".g"), (".b", ".a")):
            ids = layers[base + idc]
            term = np.where(ids == np.float32(name_id), layers[base + cov], 0.0)
            out = term if out is None else out + term
    return out


def alpha_of(layers):
    if "ViewLayer.Combined.A" in layers:
        return layers["ViewLayer.Combined.A"]
    return layers["image"][..., 3]


def normal_of(layers, is_blender):
    """The normal pass as H x W x 3 in glTF's axes."""
    if is_blender:
        x, y, z = (layers[f"ViewLayer.Normal.{c}"] for c in "XYZ")
        return np.stack([x, z, -y], axis=-1)  # Blender z-up to glTF y-up: (x, y, z) -> (x, z, -y)
    return np.stack([layers[f"normal.{c}"] for c in "XYZ"], axis=-1)


def rms(a, mask=None):
    """RMS over the pixels (of a vector's length, for H x W x 3)."""
    squared = np.square(a) if a.ndim == 2 else np.sum(np.square(a), axis=-1)
    d = squared if mask is None else squared[mask]
    return float(np.sqrt(np.mean(d))) if d.size else 0.0


def row(label, streak_values, cycles0, cycles1, mask=None):
    noise = rms(cycles0 - cycles1, mask) / math.sqrt(2.0)
    error = rms(streak_values - cycles0, mask)
    excess = math.sqrt(max(error * error - noise * noise, 0.0))
    return {"what": label, "noise": noise, "error": error, "excess": excess}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--models", default="CesiumMan,Fox,BoxAnimated")
    parser.add_argument("--method", default="analytic")
    parser.add_argument("--aa", type=int, default=8)
    parser.add_argument("--spp", type=int, default=1024)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--out", default="/tmp/streak-passes-bench")
    parser.add_argument("--streak", default=cycles_reference.STREAK)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--reuse-cycles", action="store_true")
    parser.add_argument("--samples", type=int, help="the sampled methods' --samples (accumulation, stochastic, embree)")
    args = parser.parse_args()
    sk = streak_module(args.streak)
    models = {m[0]: m for m in ground_truth_bench.MODELS}
    results = []
    for name in args.models.split(","):
        _, path, flags = models[name]
        scene = os.path.join(ground_truth_bench.SCENES, path)
        out = os.path.join(args.out, name)
        cycles = []
        for seed in (0, 1):
            folder = os.path.join(out, f"seed{seed}")
            exr = os.path.join(folder, f"cycles-passes-{args.spp}.exr")
            if not (args.reuse_cycles and os.path.exists(exr)):
                cycles_reference.render(scene, ground_truth_bench.scene_flags(flags), [args.spp], folder, streak=args.streak,
                                        blender=args.blender, width=args.width, height=args.height, frame=float(flags.get("frame", 0)),
                                        shutter=float(flags.get("shutter", 0.5)), animation=flags.get("animation"), seed=seed, passes=True)
            cycles.append(sk.read_layers(exr))
        mine = os.path.join(out, f"streak-{args.method}.exr")
        command = [args.streak, "render", scene, *ground_truth_bench.scene_flags(flags), "-m", args.method, "--width", str(args.width),
                   "--height", str(args.height), "--aa", str(args.aa), "--shading", "unlit", "--transparent",
                   "--passes", "object_id,material_id,normal", "-o", mine]
        if args.samples:
            command += ["--samples", str(args.samples)]
        start = time.perf_counter()
        subprocess.run(command, check=True)
        seconds = time.perf_counter() - start
        streak_layers = sk.read_layers(mine)
        rows = [row("alpha", alpha_of(streak_layers), alpha_of(cycles[0]), alpha_of(cycles[1]))]
        rows.append(row("normal", normal_of(streak_layers, False), normal_of(cycles[0], True), normal_of(cycles[1], True),
                        (alpha_of(streak_layers) > 0) | (alpha_of(cycles[0]) > 0) | (alpha_of(cycles[1]) > 0)))
        unmatched = []
        for type_name in ("CryptoObject", "CryptoMaterial"):
            ours, our_layer = manifest(streak_layers, type_name)
            theirs, their_layer = manifest(cycles[0], type_name)
            theirs1, _ = manifest(cycles[1], type_name)
            for object_name, object_id in sorted(ours.items()):
                if object_name not in theirs:
                    unmatched.append(f"{type_name}:{object_name}")
                    continue
                s = matte(streak_layers, our_layer, object_id)
                c0 = matte(cycles[0], their_layer, theirs[object_name])
                c1 = matte(cycles[1], their_layer, theirs1[object_name])
                mask = (s > 0) | (c0 > 0) | (c1 > 0)
                if mask.any():
                    rows.append(row(f"{type_name} {object_name}", s, c0, c1, mask))
        results.append({"model": name, "streak_seconds": seconds, "rows": rows, "unmatched": unmatched})
        print(f"{name}: streak {args.method} --aa {args.aa} {seconds:.2f} s (process); unmatched names: {', '.join(unmatched) or 'none'}")
        print(f"  {'what':40s} {'Cycles noise':>12s} {'error':>10s} {'excess':>10s}")
        for r in rows:
            print(f"  {r['what']:40s} {r['noise']:12.5f} {r['error']:10.5f} {r['excess']:10.5f}")
    with open(os.path.join(args.out, "passes_bench.json"), "w") as f:
        json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
