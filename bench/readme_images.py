#!/usr/bin/python3
"""The two images at the top of README.md (issue 31, item 7), regenerated.

- docs/images/cubes.png: the README's first render (`builtin:cubes`, 1024x768, the defaults),
  halved to 512x384 by averaging 2x2 pixels in linear light.
- docs/images/sheet.png: a shared model (--model, BoxAnimated) at the ground-truth bench's
  settings (320x240, its frame and shutter, unlit on black, --aa 8) from the exact method
  (motion-path), and at about its
  time from accumulation (instants chosen to take that long), the post-process filter, and Cycles
  (the ladder's render closest in time), beside Cycles at 1024 spp, the reference every panel's
  foreground PSNR is measured against; below, the 80x60 window where accumulation errs most
  (yellow), 4x.

The Cycles renders come from bench/ground_truth_bench.py's folder (--cycles-out, with
--reuse-cycles there), or are rendered now with Blender (about a minute). Prints the figures as a
markdown table for docs/BENCHMARKS.md. Needs the Python module: `scripts/build.sh --all`.

usage: /usr/bin/python3 bench/readme_images.py [--streak build/streak] [--cycles-out DIR] [--out docs/images] [--repeats 3] [--aa 8] [--model BoxAnimated]
"""
import argparse
import os
import sys
import tempfile
import types

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchlib  # noqa: E402
import ground_truth_bench as gt  # noqa: E402

LADDER = [16, 32, 64, 128, 256, 512]


def half(image):
    """The image at half size, each pixel the mean of 2x2 (linear light)."""
    h, w = image.shape[0] // 2 * 2, image.shape[1] // 2 * 2
    x = image[:h, :w]
    return (x[0::2, 0::2] + x[1::2, 0::2] + x[0::2, 1::2] + x[1::2, 1::2]) / 4


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--streak", default="build/streak")
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--cycles-out", default=os.path.join(tempfile.gettempdir(), "streak-ground-truth"))
    parser.add_argument("--out", default="docs/images")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--aa", type=int, default=8, help="samples per pixel side, for every streak panel")
    parser.add_argument("--model", default="BoxAnimated", help="a model of bench/ground_truth_bench.py")
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(args.streak)), "python"))
    import streak as sk  # the module beside the command line
    from PIL import Image, ImageDraw

    os.makedirs(args.out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="streak-readme-")
    runner = benchlib.Streak(args.streak, tmp, args.repeats)

    # The first render, halved.
    full = os.path.join(tmp, "cubes.exr")
    runner.render("builtin:cubes", "motion-path", full, size="1024x768", args=[], repeats=1)
    sk.write_image(half(sk.read_image(full)), os.path.join(args.out, "cubes.png"))

    # The sheet: each panel's image, time and foreground PSNR against Cycles 1024 spp.
    name, path, flags = next(m for m in gt.MODELS if m[0] == args.model)
    options = types.SimpleNamespace(width=320, height=240, spp=1024, reuse_cycles=True, out=args.cycles_out, streak=args.streak,
                                    blender=args.blender)
    scene, _, renders = gt.model_renders(options, name, path, flags, LADDER)
    reference = renders[1024]["path"]
    base = gt.scene_flags(flags) + gt.with_aa(gt.STREAK_FLAGS, args.aa)

    def streak_panel(method, extra, label):
        image = os.path.join(tmp, f"{method}.exr")
        ms, _ = runner.render(scene, method, image, size="320x240", args=base + extra)
        return label, image, ms / 1000.0, gt.compare(args.streak, image, reference)[1]

    panels = [streak_panel("motion-path", [], "exact (motion-path)")]
    exact_seconds = panels[0][2]
    probe = os.path.join(tmp, "probe.exr")
    ms, _ = runner.render(scene, "accumulation", probe, size="320x240", args=base + ["--samples", "8"])
    instants = max(1, round(8 * exact_seconds / (ms / 1000.0)))
    panels.append(streak_panel("accumulation", ["--samples", str(instants)], f"accumulation, {instants} instants"))
    panels.append(streak_panel("post-filter", [], "post-process filter"))
    spp = min(LADDER, key=lambda s: abs(renders[s]["seconds"] - exact_seconds))
    panels.append((f"Cycles {spp} spp", renders[spp]["path"], renders[spp]["seconds"],
                   gt.compare(args.streak, renders[spp]["path"], reference)[1]))
    panels.append(("Cycles 1024 spp (reference)", reference, renders[1024]["seconds"], float("inf")))

    # The second row: an 80x60 window, 4x, where accumulation errs most (its banding), found by
    # the largest windowed sum of its error against the reference.
    error = abs(sk.read_image(panels[1][1]) - sk.read_image(reference)).sum(axis=2)
    sums = error.cumsum(0).cumsum(1)
    wh, ww = 60, 80
    window = sums[wh:, ww:] - sums[:-wh, ww:] - sums[wh:, :-ww] + sums[:-wh, :-ww]
    y0, x0 = (int(v) + 1 for v in divmod(int(window.argmax()), window.shape[1]))
    caption = 34
    sheet = Image.new("RGB", (320 * len(panels), 2 * 240 + caption), "white")
    draw = ImageDraw.Draw(sheet)
    print(f"Machine: {benchlib.machine()}. {args.model}, 320x240, {' '.join(base)}; foreground PSNR against Cycles 1024 spp.\n")
    print("| panel | time | foreground PSNR |\n|---|---:|---:|")
    for i, (label, image, seconds, fg) in enumerate(panels):
        png = os.path.join(tmp, f"panel{i}.png")
        sk.write_image(sk.read_image(image), png)
        with Image.open(png) as panel:
            rgb = panel.convert("RGB")
            sheet.paste(rgb, (320 * i, 0))
            sheet.paste(rgb.crop((x0, y0, x0 + ww, y0 + wh)).resize((320, 240), Image.NEAREST), (320 * i, 240))
        draw.rectangle((320 * i + x0, y0, 320 * i + x0 + ww - 1, y0 + wh - 1), outline="yellow")
        quality = "reference" if fg == float("inf") else gt.db(fg)
        draw.text((320 * i + 6, 482), label, fill="black")
        draw.text((320 * i + 6, 498), f"{seconds:.2f} s, {quality}", fill="black")
        print(f"| {label} | {seconds:.2f} s | {quality} |")
    sheet.save(os.path.join(args.out, "sheet.png"), optimize=True)


if __name__ == "__main__":
    main()
