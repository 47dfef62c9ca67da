#!/usr/bin/env python3
"""streak against Cycles on every shared model (issue 12): ground truth streak did not write.

Each shared model at 320x240 (its frame, shutter and animation as in
tests/methods/gltf_agreement_test.cpp; the static models from their default camera), through
every CPU method (`streak methods`, without the -gl ones) with `--aa 8 --shading unlit
--background 0,0,0` and otherwise default settings, against Cycles at the reference spp (1024)
from bench/cycles_reference.py: PSNR, foreground PSNR (over the pixels where either image is
above 2/255 in sRGB 8-bit; `streak compare`) and render time (least of --repeats). Then
Cycles' own spp ladder (16, 32, ... 512, each with its own seed) against the same reference:
the fewest spp, and their render time, at which Cycles reaches each method's foreground PSNR.
Since streak and the ladder are measured against the same noisy reference, a rung "reaches" a
method when its error (its noise plus the reference's) is no larger than the method's. Past the
top rung the spp are estimated from the error falling as 1/spp (fitted at the top rung), or the
method is said to be within the reference's own noise.

With --target-fg DB[,DB...] (issue 16's speed target: the time each takes to a given quality),
each method instead climbs --aa-ladder until its foreground PSNR reaches each DB, and Cycles its
spp ladder; the table gives both times (streak's render time, least of --repeats at the chosen --aa; Cycles'
render time, scene sync and BVH included, one render per rung) and their ratio. Cycles' times are
those stored with its renders unless --retime-cycles renders the rungs that reach a target again
in this run (least of --repeats): compare ratios only where both were timed in one window.

Built-in scenes (cubes, fence) are exported with `streak export` and take part when --models
names them, as does ToyCarTurningCamera (issue 32's camera move); `--models hd --width 1024 --height 768` is issue 33's 1024x768 yardstick (CesiumMan,
Fox, ToyCar, AnimatedCube, BoxAnimated, cubes, fence).

Usage: bench/ground_truth_bench.py [--models Fox,CesiumMan] [--methods motion-path,motion-path:shading=sample]
    [--spp 1024] [--ladder 16,32,64,128,256,512] [--out DIR] [--streak build/streak]
    [--blender blender] [--repeats 1] [--reuse-cycles] [--target-fg 40,45 --aa-ladder 1,2,3,4,6,8]
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchlib  # noqa: E402
import cycles_reference  # noqa: E402

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "scenes")
# name, file, scene flags (frame, shutter, animation): where the motion is large but not wild.
MODELS = [
    ("AnimatedTriangle", "AnimatedTriangle/glTF/AnimatedTriangle.gltf", {"frame": 3, "shutter": 2}),
    ("AnimatedCube", "AnimatedCube/glTF/AnimatedCube.gltf", {"frame": 12, "shutter": 2}),
    ("BoxAnimated", "BoxAnimated/glTF-Binary/BoxAnimated.glb", {"frame": 12, "shutter": 3}),
    ("InterpolationTest", "InterpolationTest/glTF-Binary/InterpolationTest.glb",
     {"frame": 12, "shutter": 3, "animation": "CubicSpline Rotation"}),
    ("SimpleSkin", "SimpleSkin/glTF/SimpleSkin.gltf", {"frame": 12, "shutter": 6}),
    ("RiggedSimple", "RiggedSimple/glTF-Binary/RiggedSimple.glb", {"frame": 20, "shutter": 3}),
    ("RiggedFigure", "RiggedFigure/glTF-Binary/RiggedFigure.glb", {"frame": 10, "shutter": 2}),
    ("CesiumMan", "CesiumMan/glTF-Binary/CesiumMan.glb", {"frame": 12, "shutter": 2}),
    ("Fox", "Fox/glTF-Binary/Fox.glb", {"frame": 10, "shutter": 1, "animation": "Run"}),
    ("SimpleMorph", "SimpleMorph/glTF/SimpleMorph.gltf", {"frame": 24, "shutter": 12}),
    ("AnimatedMorphCube", "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", {"frame": 30, "shutter": 6}),
    ("MorphStressTest", "MorphStressTest/glTF-Binary/MorphStressTest.glb",
     {"frame": 24, "shutter": 6, "animation": "TheWave"}),
    ("ToyCar", "ToyCar/glTF/ToyCar.gltf", {}),  # static, its first glTF camera
    ("MetalRoughSpheresNoTextures", "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", {}),
]
# Scenes chosen by name in --models, never by default: the built-in scenes, exported with `streak
# export` for Cycles (bench/cycles_reference.py), and ToyCar under issue 32's turning camera move.
# `--models hd` is issue 33's 1024x768 subset, where magnified and minified textures both occur.
EXTRAS = [("cubes", "builtin:cubes", {}), ("fence", "builtin:fence", {}),
          ("ToyCarTurningCamera", "ToyCar/glTF/ToyCar.gltf",
           {"camera-pos": "0,0.15,0.35", "camera-target": "0,0.05,0", "camera-pos-end": "0.2,0.15,0.3"})]
HD_MODELS = "CesiumMan,Fox,ToyCar,AnimatedCube,BoxAnimated,cubes,fence"
STREAK_FLAGS = ["--aa", "8", "--shading", "unlit", "--background", "0,0,0"]


def cpu_methods(streak):
    out = subprocess.run([streak, "methods"], check=True, capture_output=True, text=True).stdout
    return [line.split()[0] for line in out.splitlines() if line.strip() and not line.split()[0].endswith("-gl")]


def method_spec(spec):
    """A --methods entry: NAME or NAME:key=value[;key=value] (method options, e.g.
    motion-path:shading=sample; an entry starting with -- is a render flag, e.g.
    analytic:--adaptive=0.02), as (method, its flags, a file-name stem)."""
    method, _, options = spec.partition(":")
    flags = [o if o.startswith("--") else f"--option={o}" for o in options.split(";") if o]
    return method, flags, re.sub(r"[^A-Za-z0-9.-]", "_", spec)


def scene_flags(flags):
    return [f"--{key}={value}" for key, value in flags.items()]


def db(value):
    return "inf" if value == float("inf") else f"{value:.1f} dB"


def equal_rung(ladder, target):
    """The first (spp, seconds, fg PSNR) rung of the ladder reaching `target`, or None."""
    return next((rung for rung in ladder if rung[2] >= target), None)


def mse(psnr):
    return 10 ** (-psnr / 10)


def cycles_equal(ladder, reference_spp, reference_seconds, target):
    """What Cycles needs to reach foreground PSNR `target` against the reference: the first rung
    that does, or past the top rung an estimate from the 1/spp model fitted there (error of N
    spp against the reference = v/N + v/R), or the note that the target is past the
    reference's own noise (v/R)."""
    if not ladder:
        return ""
    rung = equal_rung(ladder, target)
    if rung:
        return f"{rung[0]} spp, {rung[1]:.1f} s"
    top_spp, top_seconds, top_fg = ladder[-1]
    variance = mse(top_fg) / (1 / top_spp + 1 / reference_spp)
    left = mse(target) - variance / reference_spp
    if left <= 0:
        return f"> {top_spp} spp ({top_seconds:.1f} s); within the reference's noise"
    spp = variance / left
    return f"> {top_spp} spp ({top_seconds:.1f} s); ~{spp:.0f} spp, ~{spp / reference_spp * reference_seconds:.0f} s est."


def earlier_renders(out, job, spp_list):
    """The Cycles renders an earlier run wrote to out/cycles.json for the same size, frame, shutter
    and animation, if it has every spp asked for; else None."""
    try:
        with open(os.path.join(out, "cycles.json")) as f:
            earlier = json.load(f)
    except (OSError, ValueError):
        return None
    if any(earlier["job"].get(key) != value for key, value in job.items()):
        return None
    renders = {int(spp): r for spp, r in earlier["result"]["renders"].items()}
    if any(spp not in renders or not os.path.exists(renders[spp]["path"]) for spp in spp_list):
        return None
    return renders


def selection(args):
    """The models, methods and Cycles ladder (spp) the command line chose."""
    names = (HD_MODELS if args.models == "hd" else args.models).split(",") if args.models else []
    chosen = [m for m in MODELS + EXTRAS if m in MODELS and not names or m[0] in names]
    methods = args.methods.split(",") if args.methods else cpu_methods(args.streak)
    ladder_spp = [int(s) for s in args.ladder.split(",")] if args.ladder else []
    return chosen, methods, ladder_spp


def cycles_job(args, scene, flags):
    """The size, time and motion steps of a model's Cycles renders (cycles_reference.render's
    keywords, and what an earlier run's cycles.json must hold to be reused)."""
    job = {"width": args.width, "height": args.height, "frame": float(flags.get("frame", 0)),
           "shutter": float(flags.get("shutter", 0.5)), "animation": flags.get("animation"),
           "motion_steps": cycles_reference.MOTION_STEPS}
    if scene.startswith("builtin:"):  # the shutter as cycles_reference.render exports it: the first second, at 24 fps
        job.update(frame=0.0, shutter=24.0)
    return job


def model_renders(args, name, path, flags, ladder_spp):
    """A model's scene file, its folder under args.out and its Cycles renders at the ladder's spp
    and the reference's: rendered now, or an earlier run's with --reuse-cycles."""
    is_builtin = path.startswith("builtin:")
    scene, out = path if is_builtin else os.path.join(SCENES, path), os.path.join(args.out, name)
    os.makedirs(out, exist_ok=True)
    spp_list = ladder_spp + [args.spp]
    job = cycles_job(args, scene, flags)
    renders = earlier_renders(out, job, spp_list) if args.reuse_cycles else None
    if renders is None:
        renders = cycles_reference.render(scene, scene_flags(flags), spp_list, out, streak=args.streak,
                                          blender=args.blender, **job)
    return scene, out, renders


def with_aa(flags, aa):
    """STREAK_FLAGS with --aa set to `aa`."""
    out = list(flags)
    out[out.index("--aa") + 1] = str(aa)
    return out


def rung_flags(flags, aa, options):
    """The render flags of one rung of the --aa ladder: at --aa 1 adaptive sampling has nothing to
    refine (the render is the plain one), and is left out."""
    kept = [o for o in options if not (aa == 1 and o.startswith("--adaptive"))]
    return scene_flags(flags) + with_aa(STREAK_FLAGS, aa) + kept


def retimed(args, scene, flags, out, cycles_rungs, targets):
    """cycles_rungs with the rungs that reach a target rendered again now, in the window streak is
    timed in (a stored render's time is its own session's: the same ToyCar job took 3.10 s at
    32 spp in one and 0.78 s in another), each the least of args.repeats renders; their images
    are written beside the stored ones and not scored."""
    reaching = (next((rung for rung in cycles_rungs if rung[1] >= target), None) for target in targets)
    needed = sorted({rung[0] for rung in reaching if rung})
    if not needed:
        return cycles_rungs
    seconds = {}
    for _ in range(args.repeats):
        again = cycles_reference.render(scene, scene_flags(flags), needed, os.path.join(out, "retimed"), streak=args.streak,
                                        blender=args.blender, **cycles_job(args, scene, flags))
        for spp in needed:
            seconds[spp] = min(seconds.get(spp, math.inf), again[spp]["seconds"])
    return [(spp, fg, seconds.get(spp, s)) for spp, fg, s in cycles_rungs]


def time_to_quality(args):
    """Each method's and Cycles' time to each foreground PSNR of args.target_fg against the reference."""
    chosen, methods, ladder_spp = selection(args)
    aa_ladder = [int(a) for a in args.aa_ladder.split(",")]
    targets = [float(t) for t in args.target_fg.split(",")]
    size = f"{args.width}x{args.height}"
    print(f"Machine: {benchlib.machine()}. Time to {' and '.join(f'{t:g}' for t in targets)} dB foreground PSNR at {size} "
          f"against Cycles {args.spp} spp: streak {' '.join(with_aa(STREAK_FLAGS, 'N'))} for N in {args.aa_ladder} "
          f"(render time, least of {args.repeats} at the first N that reaches it); Cycles at {args.ladder} spp (render "
          "time, scene sync and BVH included, " +
          (f"the rungs reaching a target rendered again in this run, least of {args.repeats}" if args.retime_cycles
           else "one render each, as stored with reused renders" if args.reuse_cycles else "one render each, in this run") + ").\n")
    print("| model | target | Cycles: spp, fg PSNR, time | method | --aa | fg PSNR | time | Cycles / method |\n"
          "|---|---:|---|---|---:|---:|---:|---:|")
    streak = benchlib.Streak(args.streak, args.out, args.repeats)
    for name, path, flags in chosen:
        scene, out, renders = model_renders(args, name, path, flags, ladder_spp)
        reference = renders[args.spp]["path"]
        cycles_rungs = []  # (spp, fg, seconds), climbed until every target is reached
        for spp in ladder_spp:
            _, fg, _ = benchlib.compare(args.streak, renders[spp]["path"], reference)
            cycles_rungs.append((spp, fg, renders[spp]["seconds"]))
            if fg >= max(targets):
                break
        if args.retime_cycles:
            cycles_rungs = retimed(args, scene, flags, out, cycles_rungs, targets)
        for spec in methods:
            method, options, stem = method_spec(spec)
            image = os.path.join(out, f"{stem}-target.exr")
            rungs = []  # (aa, fg, seconds of one render), climbed until every target is reached
            for aa in aa_ladder:
                ms, _ = streak.render(scene, method, image, size=size, args=rung_flags(flags, aa, options), repeats=1)
                _, fg, _ = benchlib.compare(args.streak, image, reference)
                rungs.append((aa, fg, ms / 1000))
                if fg >= max(targets):
                    break
            for target in targets:
                cycles = next((r for r in cycles_rungs if r[1] >= target), None)
                cycles_text = f"{cycles[0]} spp, {db(cycles[1])}, {cycles[2]:.2f} s" if cycles else f"> {ladder_spp[-1]} spp"
                found = next((r for r in rungs if r[1] >= target), None)
                if not found:
                    print(f"| {name} | {target:g} dB | {cycles_text} | {spec} | > {aa_ladder[-1]} | {db(rungs[-1][1])} | — | — |",
                          flush=True)
                    continue
                seconds = found[2]
                if args.repeats > 1:
                    ms, _ = streak.render(scene, method, image, size=size, args=rung_flags(flags, found[0], options))
                    seconds = min(seconds, ms / 1000)
                ratio = f"{cycles[2] / seconds:.2f}" if cycles else "—"
                print(f"| {name} | {target:g} dB | {cycles_text} | {spec} | {found[0]} | {db(found[1])} | {seconds:.2f} s | {ratio} |",
                      flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--streak", default=cycles_reference.STREAK)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--models", default="",
                        help="comma-separated model names: the shared models', cubes, fence (built-in scenes), ToyCarTurningCamera; hd: "
                             f"{HD_MODELS} (default: every shared model)")
    parser.add_argument("--methods", default="",
                        help="comma-separated methods, each NAME or NAME:key=value;... with method options (default: every CPU method)")
    parser.add_argument("--spp", type=int, default=1024, help="Cycles spp of the reference")
    parser.add_argument("--ladder", default="16,32,64,128,256,512", help="Cycles spp compared with the reference")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--repeats", type=int, default=1, help="streak renders per method; the least time counts")
    parser.add_argument("--out", default=os.path.join(tempfile.gettempdir(), "streak-ground-truth"))
    parser.add_argument("--reuse-cycles", action="store_true",
                        help="reuse the Cycles renders an earlier run left in --out for the same job (streak re-rendered only)")
    parser.add_argument("--retime-cycles", action="store_true",
                        help="with --target-fg: render the Cycles rungs that reach a target again, least of --repeats, so that "
                             "Cycles is timed in the same window as streak (the stored renders are still the ones scored)")
    parser.add_argument("--target-fg", default=None,
                        help="time to these foreground PSNRs (comma-separated dB, e.g. 40,45): streak climbs --aa-ladder, Cycles its spp ladder")
    parser.add_argument("--aa-ladder", default="1,2,3,4,6,8", help="streak --aa values tried with --target-fg")
    parser.add_argument("--aa", default="8", help="streak's --aa in the table without --target-fg")
    args = parser.parse_args()
    if args.target_fg is not None:
        time_to_quality(args)
        return
    chosen, methods, ladder_spp = selection(args)
    size = f"{args.width}x{args.height}"
    streak_flags = with_aa(STREAK_FLAGS, args.aa)
    print(f"Machine: {benchlib.machine()}. streak {' '.join(streak_flags)} at {size}, least of {args.repeats}; "
          f"reference: Cycles {args.spp} spp; ladder: {args.ladder} spp (its own seeds) against that reference.\n")
    print("| model | method | PSNR | fg PSNR | time | Cycles to equal fg PSNR |\n|---|---|---:|---:|---:|---|")
    ladders = []
    streak = benchlib.Streak(args.streak, args.out, args.repeats)
    for name, path, flags in chosen:
        scene, out, renders = model_renders(args, name, path, flags, ladder_spp)
        reference = renders[args.spp]["path"]
        ladder = []
        for spp in ladder_spp:
            _, fg, _ = benchlib.compare(args.streak, renders[spp]["path"], reference)
            ladder.append((spp, renders[spp]["seconds"], fg))
        ladders.append((name, ladder, renders[args.spp]["seconds"]))
        for spec in methods:
            method, options, stem = method_spec(spec)
            image = os.path.join(out, f"{stem}.exr")
            ms, _ = streak.render(scene, method, image, size=size, args=scene_flags(flags) + streak_flags + options)
            psnr, fg, pixels = benchlib.compare(args.streak, image, reference)
            equal = cycles_equal(ladder, args.spp, renders[args.spp]["seconds"], fg)
            print(f"| {name} | {spec} | {db(psnr)} | {db(fg)} ({pixels} px) | {ms / 1000:.2f} s | {equal} |", flush=True)
    if ladder_spp:
        print("\nCycles' ladder: foreground PSNR against the reference and render time (scene sync and BVH "
              "included); the reference's own noise floor, estimated from the top rung as if the error fell as 1/spp "
              "(what an exact renderer would score against it)\n")
        print("| model | " + " | ".join(f"{s} spp" for s in ladder_spp) + f" | {args.spp} spp | reference noise floor |")
        print("|---|" + "---:|" * (len(ladder_spp) + 2))
        for name, ladder, seconds in ladders:
            top_spp, _, top_fg = ladder[-1]
            floor = top_fg + 10 * math.log10(args.spp / top_spp + 1)  # v/R, with v from the top rung
            print(f"| {name} | " + " | ".join(f"{db(fg)}, {s:.1f} s" for _, s, fg in ladder) +
                  f" | {seconds:.1f} s | {db(floor)} |")


if __name__ == "__main__":
    main()
