#!/usr/bin/env python3
"""Fidelity figures (issue 12) on the shared glTF models, with default settings.

Sections:
  frames  every animated model at frames 0, 10, 17, 30 (shutter 1 frame, 160x120, unlit,
          --aa 2): motion-path and analytic against accumulation (512 times) of the same keys.
  keys    the skinned characters at 320x240 --aa 2: motion-path and analytic with 2 keys and
          with the default (chosen) keys, against accumulation (1024 times) of 65 keys, the
          animation itself to within a hundredth of a pixel; render time and keys chosen.
  hard    the classes of motion where motion-path once trailed analytic (issue 12, item 5):
          thin bars crossing many pixels, camera-only motion over a textured world, skinned
          figures with 8 keys, stacked translucent layers; 256x192 Phong, against accumulation
          (3000 times): both methods' PSNR and the gap.

Usage: bench/fidelity_bench.py [--streak build/streak] [--sections frames,keys,hard] [--repeats N]
"""
import os

import benchlib

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "scenes")
ANIMATED = ["AnimatedTriangle/glTF/AnimatedTriangle.gltf", "AnimatedCube/glTF/AnimatedCube.gltf",
            "BoxAnimated/glTF-Binary/BoxAnimated.glb", "InterpolationTest/glTF-Binary/InterpolationTest.glb",
            "SimpleSkin/glTF/SimpleSkin.gltf", "RiggedSimple/glTF-Binary/RiggedSimple.glb",
            "RiggedFigure/glTF-Binary/RiggedFigure.glb", "CesiumMan/glTF-Binary/CesiumMan.glb", "Fox/glTF-Binary/Fox.glb",
            "SimpleMorph/glTF/SimpleMorph.gltf", "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb",
            "MorphStressTest/glTF-Binary/MorphStressTest.glb"]
CHARACTERS = [("Fox/glTF-Binary/Fox.glb", ["--animation", "Run", "--frame", "10", "--shutter", "2"]),
              ("CesiumMan/glTF-Binary/CesiumMan.glb", ["--frame", "12", "--shutter", "2"]),
              ("RiggedFigure/glTF-Binary/RiggedFigure.glb", ["--frame", "10", "--shutter", "2"])]


def name_of(path):
    return path.split("/")[0]


def frames(streak, args):
    print("| model | frame | motion-path | analytic |\n|---|---:|---:|---:|")
    ref, out = os.path.join(streak.tmp, "ref.exr"), os.path.join(streak.tmp, "out.exr")
    for model in ANIMATED:
        for frame in ["0", "10", "17", "30"]:
            common = ["--frame", frame, "--shutter", "1", "--shading", "unlit", "--aa", "2"]
            path = os.path.join(SCENES, model)
            streak.render(path, "accumulation", ref, size="160x120", args=common + ["--samples", "512"], repeats=1)
            cells = []
            for method in ["motion-path", "analytic"]:
                streak.render(path, method, out, size="160x120", args=common, repeats=1)
                cells.append(f"{streak.psnr(ref, out):.1f} dB")
            print(f"| {name_of(model)} | {frame} | " + " | ".join(cells) + " |", flush=True)
    print()


def keys(streak, args):
    print("| model | keys | motion-path | analytic | keys chosen, deviation left |\n|---|---|---:|---:|---|")
    ref, out = os.path.join(streak.tmp, "ref.exr"), os.path.join(streak.tmp, "out.exr")
    for model, shutter in CHARACTERS:
        path = os.path.join(SCENES, model)
        common = shutter + ["--shading", "unlit", "--aa", "2"]
        streak.render(path, "accumulation", ref, size="320x240", args=common + ["--samples", "1024", "--motion-keys", "65"], repeats=1)
        for label, extra in [("2", ["--motion-keys", "2"]), ("default", [])]:
            cells, chosen = [], ""
            for method in ["motion-path", "analytic"]:
                ms, stats = streak.render(path, method, out, size="320x240", args=common + extra)
                cells.append(f"{streak.psnr(ref, out):.1f} dB, {ms:.0f} ms")
                c = stats["counters"]
                chosen = f"{c.get('motion_keys', 0):.0f}" + (f", {c['motion_key_deviation_px']:.3f} px" if "motion_key_deviation_px" in c else "")
            print(f"| {name_of(model)} | {label} | " + " | ".join(cells) + f" | {chosen} |", flush=True)
    print()


HARD = [("thin bars", "builtin:fence?bars=40&travel=3", []),
        ("camera-only, textured", "builtin:pan", []),
        ("camera-only, textured glTF, 8 keys", os.path.join(SCENES, "ToyCar/glTF/ToyCar.gltf"),
         ["--camera-pos=-0.03,0.025,0.05", "--camera-target", "0,0,0", "--camera-target-end=0.01,0,0", "--fov", "40", "--motion-keys", "8"]),
        ("skinned figure, 8 keys", os.path.join(SCENES, "CesiumMan/glTF-Binary/CesiumMan.glb"), ["--frame", "12", "--shutter", "2", "--motion-keys", "8"]),
        ("skinned figure, 8 keys", os.path.join(SCENES, "Fox/glTF-Binary/Fox.glb"), ["--animation", "Run", "--frame", "10", "--shutter", "2", "--motion-keys", "8"]),
        ("stacked translucent layers", "builtin:translucent", [])]


def hard(streak, args):
    print("| class | scene | motion-path | analytic | gap |\n|---|---|---:|---:|---:|")
    ref, out = os.path.join(streak.tmp, "ref.exr"), os.path.join(streak.tmp, "out.exr")
    for label, scene, extra in HARD:
        streak.render(scene, "accumulation", ref, size="256x192", args=extra + ["--samples", "3000"], repeats=1)
        db = {}
        for method in ["motion-path", "analytic"]:
            streak.render(scene, method, out, size="256x192", args=extra, repeats=1)
            db[method] = streak.psnr(ref, out)
        name = scene.split("/")[-1] if not scene.startswith("builtin:") else f"`{scene}`"
        print(f"| {label} | {name} | {db['motion-path']:.1f} dB | {db['analytic']:.1f} dB | {db['motion-path'] - db['analytic']:+.1f} dB |",
              flush=True)
    print()


if __name__ == "__main__":
    benchlib.run_sections({"frames": frames, "keys": keys, "hard": hard}, default_plot="")
