"""Shared pieces of the benchmark scripts: running streak and reading its figures."""
import argparse
import json
import os
import platform
import re
import subprocess
import tempfile

SCENES = ["rotating-cube", "crossing", "twist", "fence", "pan", "translucent", "cubes"]


class Streak:
    def __init__(self, binary, tmp, repeats):
        self.binary, self.tmp, self.repeats = binary, tmp, repeats
        self.stats = os.path.join(tmp, "stats.json")

    def render(self, scene, method, out, size="256x192", args=(), repeats=None):
        """Renders; returns (least render ms over the repeats, stats of the last run)."""
        w, h = size.split("x")
        best = None
        for _ in range(repeats or self.repeats):
            subprocess.run([self.binary, "render", scene, "-m", method, "--width", w, "--height", h, "-o", out,
                            "--stats", self.stats, *args], check=True)
            with open(self.stats) as f:
                stats = json.load(f)
            ms = stats["time_ms"]["render"]
            best = ms if best is None else min(best, ms)
        return best, stats

    def reference(self, name, samples=3000):
        """Accumulation with 3000 shutter times (Hong & Oh's reference) of builtin:name, rendered once."""
        path = os.path.join(self.tmp, re.sub(r"[^A-Za-z0-9.-]", "_", name) + "-ref.exr")
        if not os.path.exists(path):
            self.render("builtin:" + name, "accumulation", path, args=["--samples", str(samples)], repeats=1)
        return path

    def psnr(self, a, b):
        out = subprocess.run([self.binary, "compare", a, b], check=True, capture_output=True, text=True).stdout
        return float(re.search(r"PSNR: (\S+) dB", out).group(1))


def compare(streak, a, b):
    """(PSNR, foreground PSNR, foreground pixels) from `streak compare`."""
    out = subprocess.run([streak, "compare", a, b], check=True, capture_output=True, text=True).stdout
    psnr = float(re.search(r"^PSNR: (\S+) dB", out, re.M).group(1))
    m = re.search(r"^foreground PSNR: (\S+) dB \((\d+) pixels\)", out, re.M)
    return psnr, float(m.group(1)), int(m.group(2))


LADDER = [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 384, 512, 768, 1024, 1536, 2048]


def equal_quality_count(streak, scene, method, ref, target, ladder=LADDER, size="256x192", args=()):
    """The smallest --samples of `method` whose PSNR against `ref` reaches `target`: a ladder
    first (PSNR is not quite monotonic in the count: stratified times can line up with the
    motion), then bisection between the last rung below and the first above. Returns (count,
    its PSNR, the image path), or (None, best PSNR, path) when the top rung falls short."""
    out = os.path.join(streak.tmp, method + "-equal.exr")
    cache = {}

    def psnr_at(n):
        if n not in cache:
            streak.render(scene, method, out, size=size, args=["--samples", str(n), *args], repeats=1)
            cache[n] = streak.psnr(ref, out)
        return cache[n]

    hi = next((r for r in ladder if psnr_at(r) >= target), None)
    if hi is None:
        return None, psnr_at(ladder[-1]), out
    lo = ladder[max(0, ladder.index(hi) - 1)]
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if psnr_at(mid) >= target:
            hi = mid
        else:
            lo = mid
    return hi, psnr_at(hi), out


def pyplot():
    """matplotlib.pyplot on the file-only Agg backend (no display on the bench machines)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def machine():
    cpu = "unknown CPU"
    if os.path.exists("/proc/cpuinfo"):
        m = re.search(r"model name\s*:\s*(.*)", open("/proc/cpuinfo").read())
        cpu = m.group(1) if m else cpu
    return f"{cpu}, {os.cpu_count()} cores ({platform.system()})"


def run_sections(sections, default_plot):
    """The scripts' command line: runs the chosen sections (name -> f(streak, args)) in order,
    against one temporary folder, so references are rendered once."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--streak", default="build/streak")
    parser.add_argument("--sections", default=",".join(sections))
    parser.add_argument("--plot", default=default_plot)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    print(f"Machine: {machine()}. Least of {args.repeats} runs per timed render.\n")
    chosen = args.sections.split(",")
    with tempfile.TemporaryDirectory() as tmp:
        streak = Streak(args.streak, tmp, args.repeats)
        for name, section in sections.items():
            if name in chosen:
                section(streak, args)
