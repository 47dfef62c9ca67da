#!/usr/bin/env python3
"""Ground truth for streak from Blender Cycles (issue 12): a renderer streak did not write.

Renders a scene streak renders (a glTF 2.0 file, or builtin:NAME, which `streak export` writes
out as glTF first) as streak's `--shading unlit --background 0,0,0` would show it:
  - every material an Emission shader of strength 1 whose colour is the albedo: base colour
    factor x base colour texture (the importer's uv chain: texCoord set, KHR_texture_transform,
    wrap modes), the texture decoded from sRGB to linear *before* bilinear filtering, as glTF
    says (Cycles would filter 8-bit sRGB textures in sRGB, so they are converted to linear float
    first), filter Linear; MASK and BLEND alpha through a Transparent BSDF; single-sided
    materials transparent from behind (streak culls their back faces); primitives without a
    material get glTF's default (white, opaque, single-sided);
  - black world, Standard view transform, box pixel filter 1 px, no denoising, no adaptive
    sampling, a fixed spp;
  - streak's camera, read from `streak render --stats` (camera_open/close_position and
    _rotation_wxyz, camera_vertical_fov_deg, camera_znear), converted from glTF's +y up to
    Blender's +z up as Blender's glTF importer converts the scene; vertical sensor fit;
  - streak's shutter: the animation time [F/R, (F+S)/R] seconds of `--frame F --shutter S --fps R`
    (Cycles' motion blur position START, shutter in Blender frames), widened by the part of it
    Cycles' ray times miss (measured each run, `calibrate_shutter`: Blender 3.4 covers only
    [0, 0.9922] of its shutter); motion steps `--motion-steps` (7, Cycles' most: 2^(7-1) = 64
    even steps of transforms and deformed meshes over the shutter, linear between them; 6 gave
    32, as many as streak's 33 chosen keys, whose 0.1 px from MorphStressTest's true morph the
    reference then shared);
  - the animation streak plays (`--animation`, the first by default), as glTF defines it:
    CUBICSPLINE samplers and LINEAR rotations, which Blender's importer keys differently
    (automatic Bezier handles; component-wise quaternion lerp), resampled into dense LINEAR keys
    over the shutter first (`resample_gltf`).

Usage:
  bench/cycles_reference.py SCENE [--frame F --shutter S --fps R --animation A] [--camera I |
      --camera-pos=x,y,z --camera-target x,y,z ...] [--width 320 --height 240]
      [--spp 1024 | --spp 16,32,64,1024] [--out DIR] [--streak build/streak] [--blender blender]
      [--threads N] [--seed N] [--motion-steps 7] [--srgb-filtering] [--verbose] [--passes]
Writes DIR/cycles-<spp>.exr (linear float) per spp, DIR/cycles.json (seconds per render, the
camera, the shutter in Blender frames) and DIR/blender.log. Compare with streak rendered
`--shading unlit --background 0,0,0` and the same scene flags: `streak compare`. The script also
runs inside Blender, which the command line starts: blender -b --factory-startup -P
bench/cycles_reference.py -- JOB.json; with STREAK_CYCLES_BLEND=file.blend set it also saves
the scene it built there, to look at.
"""
import argparse
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import time

# Cycles' motion steps per object: 2^(steps - 1) even steps over the shutter; 7 is its most.
MOTION_STEPS = 7

CAMERA_FLAGS = ["--camera", "--camera-pos", "--camera-target", "--camera-up", "--camera-pos-end",
                "--camera-target-end", "--fov"]
TIME_FLAGS = ["--frame", "--shutter", "--fps", "--animation"]
STREAK = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "build", "streak")


def streak_scene_args(args):
    """The flags of `args` that streak's render takes for the scene (time and camera)."""
    out = []
    for flag in TIME_FLAGS + CAMERA_FLAGS:
        value = getattr(args, flag[2:].replace("-", "_"))
        if value is not None:
            out.append(f"{flag}={value}")
    return out


def streak_camera(streak, scene, scene_args, width, height, tmp):
    """Runs streak once (accumulation, one time, no anti-aliasing: the camera does not depend on
    the method) and returns its --stats info: the camera it chose and the scene it loaded."""
    stats = os.path.join(tmp, "camera-stats.json")
    subprocess.run([streak, "render", scene, *scene_args, "-m", "accumulation", "--samples", "1",
                    "--width", str(width), "--height", str(height), "-o", os.path.join(tmp, "camera.exr"),
                    "--stats", stats], check=True)
    with open(stats) as f:
        return json.load(f)["info"]


def numbers(text):
    return [float(v) for v in text.split(",")]


def export_builtin(streak, scene, tmp):
    """builtin:NAME as glTF binary, written by `streak export`: its motion keys as morph targets
    over the animation's first second, its camera as the file's camera."""
    path = os.path.join(tmp, "builtin.glb")
    subprocess.run([streak, "export", scene, path], check=True)
    return path


# ---------------------------------------------------------------------------------------------
# The animation as glTF defines it. Blender's importer keys LINEAR rotations as quaternion
# components, which Blender interpolates linearly (normalised lerp, not glTF's slerp: 4 degrees
# off within a 180-degree key interval), and keys CUBICSPLINE curves as Bezier curves with
# automatic handles (the file's tangents ignored). So the samplers it gets wrong are resampled
# here, in glTF's own space, into LINEAR keys dense over the shutter, between which either
# interpolation is exact to well under a thousandth of a degree.

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
FORMATS = {5126: ("f", 4, None), 5120: ("b", 1, 127.0), 5121: ("B", 1, 255.0), 5122: ("h", 2, 32767.0),
           5123: ("H", 2, 65535.0)}


def load_gltf(path):
    """(document, buffers) of a .gltf or .glb; buffers are bytes, in the document's order."""
    with open(path, "rb") as f:
        data = f.read()
    base = os.path.dirname(os.path.abspath(path))
    if data[:4] == b"glTF":
        length = struct.unpack("<I", data[12:16])[0]
        doc = json.loads(data[20:20 + length])
        rest = 20 + length
        glb_bin = data[rest + 8:rest + 8 + struct.unpack("<I", data[rest:rest + 4])[0]] if rest + 8 <= len(data) else b""
    else:
        doc, glb_bin = json.loads(data), b""
    buffers = []
    for buffer in doc.get("buffers", []):
        uri = buffer.get("uri")
        if uri is None:
            buffers.append(glb_bin)
        elif uri.startswith("data:"):
            import base64
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            from urllib.parse import unquote
            with open(os.path.join(base, unquote(uri)), "rb") as f:
                buffers.append(f.read())
    return doc, buffers


def read_accessor(doc, buffers, index):
    """An accessor's elements as tuples of floats (normalised integers mapped as glTF says)."""
    accessor = doc["accessors"][index]
    if "sparse" in accessor or "bufferView" not in accessor:
        raise ValueError(f"animation accessor {index}: sparse or view-less accessors are not handled")
    view = doc["bufferViews"][accessor["bufferView"]]
    code, size, scale = FORMATS[accessor["componentType"]]
    n = COMPONENTS[accessor["type"]]
    stride = view.get("byteStride") or size * n
    data = buffers[view["buffer"]]
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    out = []
    for i in range(accessor["count"]):
        values = struct.unpack_from("<" + code * n, data, start + i * stride)
        out.append(tuple(max(v / scale, -1.0) for v in values) if scale else values)
    return out


def slerp(a, b, s):
    dot = sum(x * y for x, y in zip(a, b))
    if dot < 0:
        b, dot = tuple(-x for x in b), -dot
    if dot > 0.9995:
        q = tuple(x + s * (y - x) for x, y in zip(a, b))
    else:
        theta = math.acos(min(dot, 1.0))
        wa, wb = math.sin((1 - s) * theta) / math.sin(theta), math.sin(s * theta) / math.sin(theta)
        q = tuple(wa * x + wb * y for x, y in zip(a, b))
    norm = math.sqrt(sum(x * x for x in q)) or 1.0
    return tuple(x / norm for x in q)


def evaluate_sampler(times, values, interpolation, width, is_rotation, t):
    """glTF's value of a sampler at time t: `width` consecutive elements per key (morph weights:
    one per target), three such groups per key for CUBICSPLINE (in-tangent, value, out-tangent).
    Held before the first key and after the last."""
    group = 3 if interpolation == "CUBICSPLINE" else 1

    def key(k, part=0):
        base = (k * group + (1 if group == 3 else 0) + part) * width
        return [values[base + j] for j in range(width)]

    if t <= times[0] or len(times) == 1:
        return key(0)
    if t >= times[-1]:
        return key(len(times) - 1)
    k = max(i for i in range(len(times) - 1) if times[i] <= t)
    dt = times[k + 1] - times[k]
    s = (t - times[k]) / dt
    v0, v1 = key(k), key(k + 1)
    if interpolation == "CUBICSPLINE":
        b0, a1 = key(k, 1), key(k + 1, -1)
        h = (2 * s ** 3 - 3 * s ** 2 + 1, s ** 3 - 2 * s ** 2 + s, -2 * s ** 3 + 3 * s ** 2, s ** 3 - s ** 2)
        out = [tuple(h[0] * p + h[1] * dt * m0 + h[2] * q + h[3] * dt * m1 for p, m0, q, m1 in zip(*e))
               for e in zip(v0, b0, v1, a1)]
        if is_rotation:
            out = [tuple(x / (math.sqrt(sum(c * c for c in q)) or 1.0) for x in q) for q in out]
        return out
    if interpolation == "STEP":
        return v0
    if is_rotation:
        return [slerp(v0[0], v1[0], s)]
    return [tuple(p + s * (q - p) for p, q in zip(a, b)) for a, b in zip(v0, v1)]


def resample_gltf(path, begin, end, out_dir, samples=256):
    """Writes out_dir/resampled.gltf: `path` with every CUBICSPLINE sampler and every LINEAR
    rotation sampler replaced by LINEAR keys: the original keys plus `samples` + 1 even times
    over [begin, end] seconds (the shutter). Buffers and images are referenced where they are
    (a .glb's binary chunk is written out). Returns the new path, or `path` when nothing needs
    resampling."""
    doc, buffers = load_gltf(path)
    rotation_samplers = {(a, c["sampler"]) for a, anim in enumerate(doc.get("animations", []))
                         for c in anim["channels"] if c["target"].get("path") == "rotation"}
    # The samplers Blender's importer misreads: CUBICSPLINE ones and LINEAR rotations.
    misread = [(a, i) for a, anim in enumerate(doc.get("animations", [])) for i, sampler in enumerate(anim["samplers"])
               if sampler.get("interpolation", "LINEAR") == "CUBICSPLINE" or
               (sampler.get("interpolation", "LINEAR") == "LINEAR" and (a, i) in rotation_samplers)]
    if not misread:
        return path
    blob = bytearray()

    def add_accessor(rows, kind):
        doc["bufferViews"].append({"buffer": len(buffers), "byteOffset": len(blob), "byteLength": 4 * sum(map(len, rows))})
        for row in rows:
            blob.extend(struct.pack("<%df" % len(row), *row))
        accessor = {"bufferView": len(doc["bufferViews"]) - 1, "componentType": 5126, "count": len(rows), "type": kind}
        if kind == "SCALAR":
            accessor["min"], accessor["max"] = [min(r[0] for r in rows)], [max(r[0] for r in rows)]
        doc["accessors"].append(accessor)
        return len(doc["accessors"]) - 1

    for a, i in misread:
        sampler = doc["animations"][a]["samplers"][i]
        interpolation = sampler.get("interpolation", "LINEAR")
        times = [t[0] for t in read_accessor(doc, buffers, sampler["input"])]
        values = read_accessor(doc, buffers, sampler["output"])
        width = len(values) // (len(times) * (3 if interpolation == "CUBICSPLINE" else 1))
        dense = [begin + (end - begin) * k / samples for k in range(samples + 1)] if end > begin else [begin]
        new_times = sorted(set(times) | {t for t in dense if times[0] < t < times[-1]})
        is_rotation = (a, i) in rotation_samplers
        new_values = [v for t in new_times for v in evaluate_sampler(times, values, interpolation, width, is_rotation, t)]
        kind = doc["accessors"][sampler["output"]]["type"]
        sampler["input"] = add_accessor([(t,) for t in new_times], "SCALAR")
        sampler["output"] = add_accessor(new_values, kind)
        sampler["interpolation"] = "LINEAR"
    from urllib.parse import unquote
    base = os.path.dirname(os.path.abspath(path))
    for index, buffer in enumerate(doc.get("buffers", [])):
        uri = buffer.get("uri")
        if uri is None:
            bin_path = os.path.join(out_dir, "glb-binary.bin")
            with open(bin_path, "wb") as f:
                f.write(buffers[index])
            buffer["uri"] = bin_path
        elif not uri.startswith("data:"):
            buffer["uri"] = os.path.join(base, unquote(uri))
    for image in doc.get("images", []):
        if "uri" in image and not image["uri"].startswith("data:"):
            image["uri"] = os.path.join(base, unquote(image["uri"]))
    blob_path = os.path.join(out_dir, "resampled.bin")
    with open(blob_path, "wb") as f:
        f.write(blob)
    doc["buffers"].append({"uri": blob_path, "byteLength": len(blob)})
    out = os.path.join(out_dir, "resampled.gltf")
    with open(out, "w") as f:
        json.dump(doc, f)
    return out


def blender_environment():
    """The environment for Blender. Debian's Blender embeds the system Python and finds its home
    through the first python3.x on PATH; a virtualenv or pyenv Python running this script would
    hand it that interpreter's library (no numpy, which Blender's glTF importer needs)."""
    env = dict(os.environ)
    ours = {os.path.realpath(p) for p in (sys.prefix, sys.base_prefix) if os.path.realpath(p) not in ("/usr", "/usr/local")}
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep)
                                  if not any(os.path.realpath(p).startswith(o) for o in ours) and "/.pyenv/" not in p)
    for key in ["PYTHONHOME", "PYTHONPATH"] + [k for k in env if k.startswith("PYENV")]:
        env.pop(key, None)
    return env


def render(scene, scene_args, spp_list, out_dir, streak=STREAK, blender="blender", width=320, height=240,
           frame=0.0, shutter=0.5, fps=24.0, animation=None, threads=0, seed=0, motion_steps=MOTION_STEPS, linear_textures=True,
           quiet=True, passes=False):
    """Renders `scene` with Cycles at every spp of `spp_list` (each with its own seed, so their
    noise is independent). Returns {spp: {"path": exr, "seconds": render time}} and writes it,
    with the job, to out_dir/cycles.json. With passes, each render is a multilayer EXR with a
    transparent film (ViewLayer.Combined.A) and Cryptomatte object and material layers (6
    levels) and the Normal pass, and is named cycles-passes-<spp>.exr."""
    os.makedirs(out_dir, exist_ok=True)
    if scene.startswith("builtin:"):
        if scene_args:
            raise ValueError("a built-in scene takes no time or camera flags: " + " ".join(scene_args))
        # streak export writes the shutter t in [0, 1] as the animation's first second.
        frame, shutter, fps, animation = 0.0, 24.0, 24.0, None
    with tempfile.TemporaryDirectory() as tmp:
        info = streak_camera(streak, scene, scene_args, width, height, tmp)
        path = export_builtin(streak, scene, tmp) if scene.startswith("builtin:") else os.path.abspath(scene)
        path = resample_gltf(path, frame / fps, (frame + shutter) / fps, tmp)
        job = {
            "scene": scene, "gltf": path, "width": width, "height": height, "frame": frame, "shutter": shutter, "fps": fps,
            "animation": animation, "threads": threads or os.cpu_count(), "motion_steps": motion_steps,
            "linear_textures": linear_textures, "passes": passes,
            # (The camera's numbers: its poses, field of view and near plane, not where it came from.)
            "camera": {key[len("camera_"):]: numbers(value) for key, value in info.items()
                       if key.startswith("camera_") and key != "camera_source"},
            "renders": [{"spp": spp, "seed": seed + i,
                         "path": os.path.join(os.path.abspath(out_dir), f"cycles-{'passes-' if passes else ''}{spp}.exr")}
                        for i, spp in enumerate(spp_list)],
            "result": os.path.join(tmp, "result.json"),
        }
        job_path = os.path.join(tmp, "job.json")
        with open(job_path, "w") as f:
            json.dump(job, f, indent=1)
        log = os.path.join(os.path.abspath(out_dir), "blender.log")
        with open(log, "w") as f:
            run = subprocess.run([blender, "-b", "--factory-startup", "-noaudio", "--python-exit-code", "3",
                                  "--python", os.path.abspath(__file__), "--", job_path],
                                 stdout=f if quiet else None, stderr=subprocess.STDOUT if quiet else None,
                                 env=blender_environment())
        if run.returncode != 0 or not os.path.exists(job["result"]):
            raise RuntimeError(f"Blender failed (exit {run.returncode}); see {log}")
        with open(job["result"]) as f:
            result = json.load(f)
    job.pop("result")
    with open(os.path.join(out_dir, "cycles.json"), "w") as f:
        json.dump({"job": job, "result": result}, f, indent=1)
    return {int(spp): r for spp, r in result["renders"].items()}


# ---------------------------------------------------------------------------------------------
# Inside Blender.

def gltf_json(path):
    """The JSON chunk of a .glb, or the .gltf file."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        length = struct.unpack("<I", data[12:16])[0]
        return json.loads(data[20:20 + length])
    return json.loads(data)


def calibrate_shutter(threads, spp=1024):
    """The part of the nominal shutter Cycles' ray times actually cover, as fractions (a, b) of
    it. Cycles maps its time samples through a 256-entry table (the inverted shutter curve)
    whose ends fall short of the shutter's: Blender 3.4 covers [0, (255/256)^2 = 0.9922], so a
    moving edge stops 0.8% of its travel early. Measured rather than assumed: an orthographic
    view of an emissive half-plane whose edge moves 256 pixels over the shutter; a pixel fully
    inside the ramp sees it for (b - x/256) / (b - a) of the time, a line in x."""
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples, scene.cycles.seed = spp, 1
    scene.cycles.use_adaptive_sampling = scene.cycles.use_denoising = False
    scene.cycles.pixel_filter_type, scene.cycles.filter_width = "BOX", 1.0
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 320, 2, 100
    scene.render.threads_mode, scene.render.threads = "FIXED", threads
    scene.render.use_motion_blur, scene.render.motion_blur_shutter = True, 1.0
    scene.cycles.motion_blur_position = "START"
    mesh = bpy.data.meshes.new("half-plane")  # x in [-1000, 0], y in [-10, 10]
    mesh.from_pydata([(-1000, -10, 0), (0, -10, 0), (0, 10, 0), (-1000, 10, 0)], [], [(0, 1, 2, 3)])
    plane = bpy.data.objects.new("half-plane", mesh)
    scene.collection.objects.link(plane)
    material = bpy.data.materials.new("white")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    tree.links.new(tree.nodes.new("ShaderNodeOutputMaterial").inputs["Surface"],
                   tree.nodes.new("ShaderNodeEmission").outputs["Emission"])
    mesh.materials.append(material)
    for frame, x in [(1, 32.0), (2, 288.0)]:  # the edge crosses pixels 32 to 288
        plane.location = (x, 0, 0)
        plane.keyframe_insert("location", frame=frame)
    for curve in plane.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.type, camera.data.ortho_scale = "ORTHO", 320.0
    camera.location = (160.0, 0.0, 10.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.frame_set(1)
    bpy.ops.render.render()
    path = os.path.join(tempfile.gettempdir(), f"streak-shutter-calibration-{os.getpid()}.exr")
    scene.render.image_settings.file_format, scene.render.image_settings.color_depth = "OPEN_EXR", "32"
    bpy.data.images["Render Result"].save_render(path, scene=scene)
    image = bpy.data.images.load(path)
    pixels = image.pixels[:]
    os.remove(path)
    xs, vs = [], []
    for x in range(320):
        v = sum(pixels[4 * (row * 320 + x)] for row in range(2)) / 2
        if 0.05 < v < 0.95:
            xs.append((x + 0.5 - 32.0) / 256.0)
            vs.append(v)
    n, mx, mv = len(xs), sum(xs) / len(xs), sum(vs) / len(vs)
    slope = sum((x - mx) * (v - mv) for x, v in zip(xs, vs)) / sum((x - mx) ** 2 for x in xs)
    length = -1.0 / slope
    end = (mv - slope * mx) * length
    return end - length, end


class CyclesScene:
    def __init__(self, job):
        import bpy
        self.bpy, self.job = bpy, job
        self.linear_images = {}

    # Time: Blender's glTF importer keys animation time t at frame t * render.fps (an integer),
    # so streak's [F/R, (F+S)/R] seconds are frames [F fps/R, (F+S) fps/R].
    def setup_time(self):
        scene, job = self.bpy.context.scene, self.job
        scene.render.fps = max(1, round(job["fps"])) if abs(job["fps"] - round(job["fps"])) < 1e-9 else 24
        scene.render.fps_base = 1.0
        self.blender_fps = scene.render.fps
        self.open_frame = job["frame"] * self.blender_fps / job["fps"]
        self.shutter_frames = job["shutter"] * self.blender_fps / job["fps"]

    def import_gltf(self):
        import numpy
        if "bool" not in numpy.__dict__:
            numpy.bool = bool  # Blender 3.4's importer uses np.bool, which numpy 1.24 removed
        self.bpy.ops.import_scene.gltf(filepath=self.job["gltf"])

    def choose_animation(self):
        """Plays the animation streak plays: --animation NAME or INDEX, else the first. The
        importer stashes each animation as NLA tracks named as below and activates the first."""
        from io_scene_gltf2.blender.imp.gltf2_blender_gltf import BlenderGlTF
        animations = gltf_json(self.job["gltf"]).get("animations", [])
        names = set()
        tracks = []
        for i, a in enumerate(animations):
            tracks.append(BlenderGlTF.find_unused_name(names, a.get("name") or "Anim_%d" % i))
            names.add(tracks[-1])
        wanted = self.job["animation"]
        index = 0
        if wanted is not None:
            by_name = [i for i, a in enumerate(animations) if a.get("name") == wanted]
            index = by_name[0] if by_name else int(wanted)
        self.animation_track = tracks[index] if tracks else None
        for ob in self.bpy.context.scene.objects:
            owners = [ob] + ([ob.data.shape_keys] if getattr(ob.data, "shape_keys", None) else [])
            for owner in owners:
                data = owner.animation_data
                if not data:
                    continue
                data.action = next((t.strips[0].action for t in data.nla_tracks
                                    if t.name == self.animation_track and t.strips), None)
        # Shape key values are clamped to their sliders: let weights outside [0, 1] through.
        for key in self.bpy.data.shape_keys:
            for block in key.key_blocks:
                block.slider_min, block.slider_max = -10.0, 10.0

    def setup_camera(self):
        from mathutils import Matrix, Quaternion, Vector
        bpy, cam, job = self.bpy, self.job["camera"], self.job
        for ob in list(bpy.context.scene.objects):
            if ob.type == "CAMERA":
                bpy.data.objects.remove(ob)
        data = bpy.data.cameras.new("streak")
        data.sensor_fit = "VERTICAL"
        data.angle_y = math.radians(cam["vertical_fov_deg"][0])
        data.clip_start = cam["znear"][0]
        data.clip_end = 1e8
        ob = bpy.data.objects.new("streak", data)
        bpy.context.scene.collection.objects.link(ob)
        bpy.context.scene.camera = ob
        ob.rotation_mode = "QUATERNION"
        y_up_to_z_up = Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))
        p0, p1 = Vector(cam["open_position"]), Vector(cam["close_position"])
        q0, q1 = Quaternion(cam["open_rotation_wxyz"]), Quaternion(cam["close_rotation_wxyz"])
        if q0.dot(q1) < 0:
            q1.negate()  # streak's slerp takes the short way

        def pose(t):
            world = Matrix.Translation(p0.lerp(p1, t)) @ q0.slerp(q1, t).to_matrix().to_4x4()
            return (y_up_to_z_up @ world).decompose()

        moving = p0 != p1 or q0 != q1
        keys = 33 if moving and self.shutter_frames > 0 else 1
        previous = None
        for k in range(keys):
            t = k / (keys - 1) if keys > 1 else 0.0
            location, rotation, _ = pose(t)
            if previous is not None and previous.dot(rotation) < 0:
                rotation.negate()
            previous = rotation
            ob.location, ob.rotation_quaternion = location, rotation
            if keys > 1:
                frame = self.open_frame + t * self.shutter_frames
                ob.keyframe_insert("location", frame=frame)
                ob.keyframe_insert("rotation_quaternion", frame=frame)
        if ob.animation_data and ob.animation_data.action:
            for curve in ob.animation_data.action.fcurves:
                for point in curve.keyframe_points:
                    point.interpolation = "LINEAR"

    # Materials -----------------------------------------------------------------------------

    def linear_image(self, image):
        """A float copy of an 8-bit image, decoded from sRGB to linear, so Cycles filters linear
        values (it filters 8-bit sRGB textures before decoding them). Alpha as stored."""
        if image.name in self.linear_images:
            return self.linear_images[image.name]
        bpy = self.bpy
        width, height = image.size
        if image.is_float or width == 0:
            result = image  # float images are converted to linear when Cycles loads them
        else:
            import numpy as np  # Blender's glTF importer needs it too
            pixels = np.empty(width * height * 4, np.float32)
            image.pixels.foreach_get(pixels)
            rgb = pixels.reshape(-1, 4)[:, :3]
            rgb[:] = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
            result = bpy.data.images.new(image.name + ".linear", width, height, alpha=True, float_buffer=True)
            result.colorspace_settings.name = "Linear"
            result.pixels.foreach_set(pixels)
            result.pack()  # kept in the .blend (as EXR: it is float); Cycles reads it from memory
        result.alpha_mode = "CHANNEL_PACKED"  # colour never multiplied or divided by alpha
        self.linear_images[image.name] = result
        return result

    @staticmethod
    def upstream(socket):
        """Every node that feeds `socket`."""
        nodes, stack = [], [link.from_node for link in socket.links]
        while stack:
            node = stack.pop()
            if node not in nodes:
                nodes.append(node)
                stack.extend(link.from_node for s in node.inputs for link in s.links)
        return nodes

    def emission_material(self, material):
        """Replaces the material's surface by emission of its base colour (Principled BSDF's
        Base Color input as the importer built it), with its alpha mode and sidedness."""
        tree = material.node_tree
        nodes, links = tree.nodes, tree.links
        principled = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
        colour = principled.inputs["Base Color"] if principled else None
        alpha = principled.inputs["Alpha"] if principled else None
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Strength"].default_value = 1.0
        if colour is not None and colour.links:
            links.new(emission.inputs["Color"], colour.links[0].from_socket)
        elif colour is not None:
            emission.inputs["Color"].default_value = colour.default_value
        else:
            emission.inputs["Color"].default_value = tuple(material.diffuse_color)
        for node in self.upstream(emission.inputs["Color"]) + (self.upstream(alpha) if alpha else []):
            if node.type == "TEX_IMAGE" and node.image is not None:
                if self.job.get("linear_textures", True):
                    node.image = self.linear_image(node.image)
                node.interpolation = "Linear"
        surface = emission.outputs["Emission"]
        if material.blend_method in ("BLEND", "CLIP") and alpha is not None:
            factor = alpha.links[0].from_socket if alpha.links else None
            if material.blend_method == "CLIP":  # glTF MASK: opaque where alpha >= cutoff
                below = nodes.new("ShaderNodeMath")
                below.operation = "LESS_THAN"
                if factor is not None:
                    links.new(below.inputs[0], factor)
                else:
                    below.inputs[0].default_value = alpha.default_value
                below.inputs[1].default_value = material.alpha_threshold
                keep = nodes.new("ShaderNodeMath")
                keep.operation = "SUBTRACT"
                keep.inputs[0].default_value = 1.0
                links.new(keep.inputs[1], below.outputs[0])
                factor = keep.outputs[0]
            surface = self.mix_transparent(tree, surface, factor, alpha.default_value, transparent_first=True)
        if material.use_backface_culling:  # single-sided: streak culls back faces
            geometry = nodes.new("ShaderNodeNewGeometry")
            surface = self.mix_transparent(tree, surface, geometry.outputs["Backfacing"], 0.0, transparent_first=False)
        output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output), None)
        if output is None:
            output = nodes.new("ShaderNodeOutputMaterial")
        output.target = "ALL"
        for socket in output.inputs:
            for link in list(socket.links):
                links.remove(link)
        links.new(output.inputs["Surface"], surface)

    @staticmethod
    def mix_transparent(tree, surface, factor, default, transparent_first):
        """Mix of a Transparent BSDF and `surface`: factor 1 picks the second shader."""
        mix = tree.nodes.new("ShaderNodeMixShader")
        transparent = tree.nodes.new("ShaderNodeBsdfTransparent")
        transparent.inputs["Color"].default_value = (1, 1, 1, 1)
        first, second = (transparent.outputs[0], surface) if transparent_first else (surface, transparent.outputs[0])
        tree.links.new(mix.inputs[1], first)
        tree.links.new(mix.inputs[2], second)
        if factor is not None:
            tree.links.new(mix.inputs["Fac"], factor)
        else:
            mix.inputs["Fac"].default_value = default
        return mix.outputs[0]

    def setup_materials(self):
        bpy = self.bpy
        default = bpy.data.materials.new("glTF default")  # white, opaque, single-sided
        default.use_nodes = True
        default.use_backface_culling = True
        principled = next(n for n in default.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
        principled.inputs["Base Color"].default_value = (1, 1, 1, 1)
        used = []
        for ob in bpy.context.scene.objects:
            if ob.type != "MESH":
                continue
            if not ob.material_slots:
                ob.data.materials.append(default)
            for slot in ob.material_slots:
                if slot.material is None:
                    slot.material = default
                if slot.material not in used:
                    used.append(slot.material)
        for material in used:
            material.use_nodes = True
            self.emission_material(material)

    def setup_render(self):
        scene, job = self.bpy.context.scene, self.job
        scene.render.engine = "CYCLES"
        scene.cycles.device = "CPU"
        scene.cycles.use_adaptive_sampling = False
        scene.cycles.use_denoising = False
        scene.cycles.pixel_filter_type = "BOX"
        scene.cycles.filter_width = 1.0
        scene.cycles.transparent_max_bounces = 256
        scene.cycles.sample_clamp_direct = scene.cycles.sample_clamp_indirect = 0.0
        scene.render.resolution_x, scene.render.resolution_y = job["width"], job["height"]
        scene.render.resolution_percentage = 100
        scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
        scene.render.film_transparent = False
        scene.render.threads_mode = "FIXED"
        scene.render.threads = job["threads"]
        scene.render.dither_intensity = 0.0
        scene.view_settings.view_transform = "Standard"
        scene.view_settings.look = "None"
        scene.view_settings.exposure = 0.0
        scene.view_settings.gamma = 1.0
        world = self.bpy.data.worlds.new("black")
        world.use_nodes = False
        world.color = (0, 0, 0)
        scene.world = world
        settings = scene.render.image_settings
        settings.file_format, settings.color_mode, settings.color_depth, settings.exr_codec = "OPEN_EXR", "RGB", "32", "ZIP"
        if job.get("passes"):
            # Alpha and Cryptomatte as a compositor takes them: Film > Transparent, object and
            # material Cryptomatte at Blender's default 6 levels, one multilayer EXR.
            scene.render.film_transparent = True
            layer = scene.view_layers[0]
            layer.use_pass_cryptomatte_object = layer.use_pass_cryptomatte_material = True
            layer.pass_cryptomatte_depth = 6
            layer.use_pass_normal = True
            settings.file_format, settings.color_mode = "OPEN_EXR_MULTILAYER", "RGBA"
        frame = int(math.floor(self.open_frame))
        # Cycles' ray times cover [a, b] of its nominal shutter: widen and shift it so they cover
        # exactly [open, open + shutter].
        a, b = self.shutter_coverage
        nominal = self.shutter_frames / (b - a)
        start = self.open_frame - a * nominal if self.shutter_frames > 0 else self.open_frame
        frame = int(math.floor(start))
        scene.frame_set(frame, subframe=start - frame)
        scene.render.use_motion_blur = self.shutter_frames > 0
        scene.render.motion_blur_shutter = max(nominal, 1e-6)
        scene.cycles.motion_blur_position = "START"
        for ob in scene.objects:
            ob.cycles.use_motion_blur = True
            ob.cycles.use_deform_motion = True
            ob.cycles.motion_steps = job["motion_steps"]

    def render_all(self):
        bpy, scene = self.bpy, self.bpy.context.scene
        results = {}
        for r in self.job["renders"]:
            scene.cycles.samples = r["spp"]
            scene.cycles.seed = r["seed"]
            start = time.perf_counter()
            bpy.ops.render.render()
            seconds = time.perf_counter() - start
            bpy.data.images["Render Result"].save_render(r["path"], scene=scene)
            results[str(r["spp"])] = {"path": r["path"], "seconds": seconds}
            print(f"cycles_reference: {r['spp']} spp in {seconds:.2f} s -> {r['path']}", flush=True)
        return results


def blender_main(job_path):
    with open(job_path) as f:
        job = json.load(f)
    import bpy
    coverage = calibrate_shutter(job["threads"]) if job["shutter"] > 0 else (0.0, 1.0)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    cycles = CyclesScene(job)
    cycles.shutter_coverage = coverage
    cycles.setup_time()
    cycles.import_gltf()
    cycles.choose_animation()
    cycles.setup_camera()
    cycles.setup_materials()
    cycles.setup_render()
    if os.environ.get("STREAK_CYCLES_BLEND"):
        bpy.ops.wm.save_as_mainfile(filepath=os.environ["STREAK_CYCLES_BLEND"])
    renders = cycles.render_all()
    with open(job["result"], "w") as f:
        json.dump({"renders": renders, "blender_fps": cycles.blender_fps, "open_frame": cycles.open_frame,
                   "shutter_frames": cycles.shutter_frames, "shutter_coverage": coverage, "animation_track": cycles.animation_track,
                   "blender": bpy.app.version_string}, f, indent=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", help="a .gltf/.glb file or builtin:NAME[?k=v...]")
    parser.add_argument("--streak", default=STREAK)
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--out", default=os.path.join(tempfile.gettempdir(), "streak-cycles"))
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--spp", default="1024", help="samples per pixel, or a comma-separated ladder")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=0, help="Cycles threads (0: all cores)")
    parser.add_argument("--motion-steps", type=int, default=MOTION_STEPS, help="Cycles motion steps per object (1-7: 2^(steps-1) steps)")
    parser.add_argument("--srgb-filtering", action="store_true",
                        help="keep 8-bit textures as Blender loads them (Cycles filters them in sRGB, before decoding)")
    parser.add_argument("--verbose", action="store_true", help="show Blender's output")
    parser.add_argument("--passes", action="store_true",
                        help="a transparent film and Cryptomatte object and material layers, in multilayer EXRs")
    for flag in TIME_FLAGS + CAMERA_FLAGS:
        parser.add_argument(flag)
    args = parser.parse_args()
    frame = float(args.frame) if args.frame is not None else 0.0
    shutter = float(args.shutter) if args.shutter is not None else 0.5
    fps = float(args.fps) if args.fps is not None else 24.0
    spp = [int(s) for s in args.spp.split(",")]
    results = render(args.scene, streak_scene_args(args), spp, args.out, streak=args.streak, blender=args.blender,
                     width=args.width, height=args.height, frame=frame, shutter=shutter, fps=fps,
                     animation=args.animation, threads=args.threads, seed=args.seed, motion_steps=args.motion_steps,
                     linear_textures=not args.srgb_filtering, quiet=not args.verbose, passes=args.passes)
    for n, r in sorted(results.items()):
        print(f"{n} spp: {r['seconds']:.2f} s  {r['path']}")


if __name__ == "__main__":
    try:
        import bpy  # noqa: F401  (present only inside Blender)
        inside_blender = True
    except ImportError:
        inside_blender = False
    if inside_blender:
        blender_main(sys.argv[sys.argv.index("--") + 1])
    else:
        main()
