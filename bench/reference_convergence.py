#!/usr/bin/python3
"""Quality against time: motion paths and the two reference renderers.

For each scene, renders the converged reference (accumulation, 3000 shutter times, as in
Hong & Oh), then motion-path, and accumulation and stochastic at increasing sample counts. It records the render
time (the "render" phase in --stats) and the PSNR/SSIM against the reference, as reported by
`streak compare`. Prints a Markdown table for docs/BENCHMARKS.md.

usage: bench/reference_convergence.py [--streak build/streak] [--size 256x192] [--scenes a,b]
"""
import argparse
import json
import os
import platform
import re
import subprocess
import tempfile


def render(streak, scene, method, samples, size, out, stats):
    w, h = size.split("x")
    extra = ["--samples", str(samples)] if samples else []
    subprocess.run([streak, "render", scene, "-m", method, *extra, "--width", w, "--height", h,
                    "-o", out, "--stats", stats], check=True)
    with open(stats) as f:
        return json.load(f)["time_ms"]["render"]


def compare(streak, a, b):
    out = subprocess.run([streak, "compare", a, b], check=True, capture_output=True, text=True).stdout
    psnr = re.search(r"PSNR: (\S+) dB", out).group(1)
    ssim = re.search(r"SSIM: (\S+)", out).group(1)
    return float(psnr), float(ssim)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--streak", default="build/streak")
    parser.add_argument("--size", default="256x192")
    parser.add_argument("--scenes", default="rotating-cube,crossing,twist,fence,pan,translucent,cubes")
    parser.add_argument("--reference-samples", type=int, default=3000)
    args = parser.parse_args()
    sweeps = {"accumulation": [16, 64, 256, 1024], "stochastic": [4, 16, 64, 256]}
    cpu = "unknown CPU"
    if os.path.exists("/proc/cpuinfo"):
        m = re.search(r"model name\s*:\s*(.*)", open("/proc/cpuinfo").read())
        cpu = m.group(1) if m else cpu
    print(f"Machine: {cpu}, {os.cpu_count()} cores ({platform.system()}). Size {args.size}, phong shading, aa 1.")
    print(f"Reference: accumulation with {args.reference_samples} shutter times.\n")
    print("| scene | method | samples | render ms | PSNR dB | SSIM |")
    print("|---|---|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.json")
        for name in args.scenes.split(","):
            scene = "builtin:" + name
            ref = os.path.join(tmp, name + "-ref.png")
            ref_ms = render(args.streak, scene, "accumulation", args.reference_samples, args.size, ref, stats)
            print(f"| {name} | accumulation (reference) | {args.reference_samples} | {ref_ms:.0f} | – | – |", flush=True)
            out = os.path.join(tmp, f"{name}-motion-path.png")
            ms = render(args.streak, scene, "motion-path", None, args.size, out, stats)
            psnr, ssim = compare(args.streak, out, ref)
            print(f"| {name} | motion-path | – | {ms:.0f} | {psnr:.2f} | {ssim:.4f} |", flush=True)
            for method, counts in sweeps.items():
                for s in counts:
                    out = os.path.join(tmp, f"{name}-{method}-{s}.png")
                    ms = render(args.streak, scene, method, s, args.size, out, stats)
                    psnr, ssim = compare(args.streak, out, ref)
                    print(f"| {name} | {method} | {s} | {ms:.0f} | {psnr:.2f} | {ssim:.4f} |", flush=True)


if __name__ == "__main__":
    main()
