"""The Blender add-on, headless: blender -b --factory-startup --python-exit-code 1 --python
tests/blender/test_addon.py -- BUILD_DIR STREAK_CLI ADDON_DIR

Builds a scene by script (scene_builder: a textured cube moving and turning, an armature-bent
cylinder, a shape-key animation and a moving camera), renders it with the STREAK engine, and
checks it against two independent renders of the same scene: streak's command line on what
Blender's glTF exporter writes, and Cycles with emission materials."""

import math
import os
import subprocess
import sys
import tempfile
import time
import unittest

import bpy
import numpy as np

ARGS = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
BUILD, CLI, ADDON = ARGS[0], ARGS[1], ARGS[2]
sys.path.insert(0, os.path.join(BUILD, "python"))
sys.path.insert(0, ADDON)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import scene_builder  # noqa: E402
import streak  # noqa: E402
import streak_blender  # noqa: E402
from streak_blender import engine  # noqa: E402

streak_blender.register()
TMP = tempfile.mkdtemp(prefix="streak_blender_")


def render_addon(path, multilayer=False, **settings):
    """Renders the current scene with STREAK (unlit, aa 4) to an EXR (multilayer: with every view
    layer and pass); the engine's report."""
    scene = bpy.context.scene
    scene.render.engine = "STREAK"
    scene.streak.shading = "UNLIT"
    scene.streak.aa = 4
    for key, value in settings.items():
        setattr(scene.streak, key, value)
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER" if multilayer else "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    if os.path.exists(path):
        os.remove(path)
    bpy.ops.render.render(write_still=True)
    return dict(engine.last_render)


def render_gltf(path, *flags):
    """The same scene through Blender's glTF exporter and streak's command line, under the
    scene's motion blur (shut when it is off)."""
    glb = os.path.join(TMP, "scene.glb")
    bpy.ops.export_scene.gltf(filepath=glb, export_format="GLB", export_cameras=True, export_animations=True,
                              export_nla_strips=False)
    scene = bpy.context.scene
    shutter = scene.render.motion_blur_shutter if scene.render.use_motion_blur else 0.0
    subprocess.run([CLI, "render", glb, "--camera", "0", "--frame", str(scene.frame_current), "--fps", str(scene.render.fps),
                    "--shutter", str(shutter), "--shutter-position", scene.cycles.motion_blur_position.lower(),
                    "--width", str(scene_builder.WIDTH), "--height", str(scene_builder.HEIGHT), "--aa", "4", "--shading", "unlit",
                    "--transparent", "-o", path, *flags], check=True, stdout=subprocess.DEVNULL)


def emission_materials():
    """Every material's Principled BSDF replaced by an Emission shader of its base colour; an 8-bit
    texture decoded to linear float first, so Cycles filters linear values as streak does."""
    for material in bpy.data.materials:
        nodes, links = material.node_tree.nodes, material.node_tree.links
        colour = nodes["Principled BSDF"].inputs["Base Color"]
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Strength"].default_value = 1.0
        if colour.is_linked:
            texture = colour.links[0].from_node
            w, h = texture.image.size
            pixels = np.empty(w * h * 4, dtype=np.float32)
            texture.image.pixels.foreach_get(pixels)
            rgb = pixels.reshape(-1, 4)[:, :3]
            pixels.reshape(-1, 4)[:, :3] = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
            linear = bpy.data.images.new(texture.image.name + " linear", w, h, float_buffer=True)
            linear.colorspace_settings.name = "Linear"
            linear.pixels.foreach_set(pixels)
            texture.image = linear
            links.new(emission.inputs["Color"], texture.outputs["Color"])
        else:
            emission.inputs["Color"].default_value = colour.default_value
        links.new(nodes["Material Output"].inputs["Surface"], emission.outputs["Emission"])


def render_cycles(path, spp, multilayer=False):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device, c.samples, c.seed = "CPU", spp, 1
    c.use_adaptive_sampling = c.use_denoising = False
    c.pixel_filter_type, c.filter_width = "BOX", 1.0
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER" if multilayer else "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def psnr(a, b, threshold=2.0 / 255.0):
    """(PSNR, foreground PSNR) of two RGBA images, as streak compare gives them."""
    c = streak.compare(a, b, threshold)
    return c["psnr"], c["foreground_psnr"]


class Addon(unittest.TestCase):
    def setUp(self):
        scene_builder.build(TMP)

    def test_matches_streak_on_blenders_gltf_export(self):
        report = render_addon(os.path.join(TMP, "addon.exr"))
        self.assertEqual(report["status"], "done", report)
        self.assertEqual(report["objects"], 3)
        self.assertGreaterEqual(report["keys"], 3)  # the turning cube needs more than the shutter's ends
        self.assertFalse(report["camera_baked"])  # a camera moving without turning is streak's own
        render_gltf(os.path.join(TMP, "gltf.exr"))
        whole, fg = psnr(streak.read_image(os.path.join(TMP, "addon.exr")), streak.read_image(os.path.join(TMP, "gltf.exr")))
        print(f"add-on against the glTF export: {whole:.1f} dB, foreground {fg:.1f} dB")
        self.assertGreaterEqual(whole, 45.0)
        self.assertGreaterEqual(fg, 45.0)

    def test_adaptive_threshold_is_the_command_lines_adaptive_flag(self):
        render_addon(os.path.join(TMP, "adaptive.exr"), adaptive=0.02)
        render_gltf(os.path.join(TMP, "adaptive_gltf.exr"), "--adaptive", "0.02")
        whole, fg = psnr(streak.read_image(os.path.join(TMP, "adaptive.exr")), streak.read_image(os.path.join(TMP, "adaptive_gltf.exr")))
        print(f"adaptive add-on against the glTF export's --adaptive: {whole:.1f} dB, foreground {fg:.1f} dB")
        self.assertGreaterEqual(whole, 45.0)
        self.assertGreaterEqual(fg, 45.0)
        # Full Samples Above is --adaptive-full: at the threshold every refined pixel takes all aa x aa.
        render_addon(os.path.join(TMP, "adaptive_full.exr"), adaptive=0.02, adaptive_full=0.02)
        render_gltf(os.path.join(TMP, "adaptive_full_gltf.exr"), "--adaptive", "0.02", "--adaptive-full", "0.02")
        full_addon, full_gltf = (streak.read_image(os.path.join(TMP, name)) for name in ("adaptive_full.exr", "adaptive_full_gltf.exr"))
        whole, fg = psnr(full_addon, full_gltf)
        print(f"adaptive-full add-on against the glTF export's --adaptive-full: {whole:.1f} dB, foreground {fg:.1f} dB")
        self.assertGreaterEqual(whole, 45.0)
        self.assertGreaterEqual(fg, 45.0)
        self.assertFalse(np.array_equal(full_addon, streak.read_image(os.path.join(TMP, "adaptive.exr"))))
        bpy.context.scene.streak.adaptive_full = 0.0
        # A sampled method has nothing to refine adaptively: the setting is left out, not an error.
        report = render_addon(os.path.join(TMP, "adaptive_accumulation.exr"), adaptive=0.02, method="accumulation", samples=4)
        self.assertEqual(report["status"], "done", report)

    def test_line_samples_are_the_command_lines_line_samples(self):
        # With motion blur off nothing moves, so every tile takes line samples: the add-on's
        # Line Samples and Line Rows are the command line's options (its image is the command
        # line's with them, nearer than the add-on's own points are), and a sampled method,
        # which has none, leaves them out.
        bpy.context.scene.render.use_motion_blur = False
        report = render_addon(os.path.join(TMP, "lines.exr"), line_samples=True, line_rows=3)
        self.assertEqual(report["status"], "done", report)
        self.assertEqual(report["stats"]["counters"]["line_samples"], 1)
        render_gltf(os.path.join(TMP, "lines_gltf.exr"), "--option", "line-samples=1", "--option", "line-rows=3")
        render_addon(os.path.join(TMP, "points.exr"), line_samples=False, line_rows=0)  # (settings persist)
        cli = streak.read_image(os.path.join(TMP, "lines_gltf.exr"))
        _, lines_fg = psnr(streak.read_image(os.path.join(TMP, "lines.exr")), cli)
        _, points_fg = psnr(streak.read_image(os.path.join(TMP, "points.exr")), cli)
        print(f"add-on lines against the command line's: foreground {lines_fg:.1f} dB; the add-on's points: {points_fg:.1f} dB")
        self.assertGreaterEqual(lines_fg, 45.0)
        self.assertGreater(lines_fg, points_fg + 3.0)
        report = render_addon(os.path.join(TMP, "lines_accumulation.exr"), line_samples=True, method="accumulation", samples=1)
        self.assertEqual(report["status"], "done", report)

    def test_a_turning_camera_streak_follows_matches_the_gltf_export(self):
        # Looking down and panning: its up vector turns with it, and streak's camera, told the
        # pose at each end, turns by slerp as Blender's single-axis Euler curve does.
        camera = bpy.context.scene.camera
        camera.animation_data_clear()
        camera.location, camera.rotation_euler = (0.0, -6.0, 4.0), (math.radians(55), 0.0, math.radians(-4))
        camera.keyframe_insert("rotation_euler", frame=4)
        camera.rotation_euler.z = math.radians(6)
        camera.keyframe_insert("rotation_euler", frame=6)
        scene_builder.linear(camera)
        report = render_addon(os.path.join(TMP, "pan.exr"))
        self.assertFalse(report["camera_baked"])
        render_gltf(os.path.join(TMP, "pan_gltf.exr"))
        whole, fg = psnr(streak.read_image(os.path.join(TMP, "pan.exr")), streak.read_image(os.path.join(TMP, "pan_gltf.exr")))
        print(f"a panning camera against the glTF export: {whole:.1f} dB, foreground {fg:.1f} dB")
        self.assertGreaterEqual(fg, 45.0)

    @staticmethod
    def against_cycles(name, label):
        """The add-on's render of the scene and Cycles' (emission shaders, 256 spp): its report,
        PSNR and foreground PSNR."""
        report = render_addon(os.path.join(TMP, f"{name}.exr"))
        emission_materials()
        render_cycles(os.path.join(TMP, f"{name}_cycles.exr"), 256)
        whole, fg = psnr(streak.read_image(os.path.join(TMP, f"{name}.exr")), streak.read_image(os.path.join(TMP, f"{name}_cycles.exr")))
        print(f"{label} against Cycles 256 spp: {whole:.1f} dB, foreground {fg:.1f} dB")
        return report, whole, fg

    def test_matches_cycles(self):
        _, _, fg = self.against_cycles("addon", "add-on")
        self.assertGreaterEqual(fg, 35.0)

    def test_a_zooming_turning_camera_is_baked_and_matches_cycles(self):
        # A path streak's open/close camera cannot follow (its focal length changes, and it turns
        # about a point off its own centre) is carried by the geometry.
        scene = bpy.context.scene
        camera = scene.camera
        camera.data.lens = 30.0
        camera.data.keyframe_insert("lens", frame=4)
        camera.keyframe_insert("rotation_euler", frame=4)
        camera.data.lens = 45.0
        camera.rotation_euler.z += math.radians(8.0)
        camera.data.keyframe_insert("lens", frame=6)
        camera.keyframe_insert("rotation_euler", frame=6)
        scene_builder.linear(camera)
        scene_builder.linear(camera.data)
        report, _, fg = self.against_cycles("zoom", "zooming, turning camera")
        self.assertTrue(report["camera_baked"])
        self.assertGreaterEqual(fg, 35.0)

    def test_shutter_curve_and_rolling_shutter_are_streaks_flags(self):
        scene = bpy.context.scene
        render_addon(os.path.join(TMP, "box.exr"))
        mapping = scene.render.motion_blur_shutter_curve
        points = mapping.curves[0].points
        while len(points) > 2:
            points.remove(points[1])
        points[0].location, points[1].location = (0.0, 0.0), (1.0, 1.0)
        for p in points:
            p.handle_type = "VECTOR"
        mapping.update()
        scene.cycles.rolling_shutter_type = "TOP"
        scene.cycles.rolling_shutter_duration = 0.5
        render_addon(os.path.join(TMP, "curve.exr"))
        render_gltf(os.path.join(TMP, "curve_gltf.exr"), "--shutter-curve", "0:0,1:1", "--rolling-shutter", "0.5")
        curve = streak.read_image(os.path.join(TMP, "curve.exr"))
        whole, fg = psnr(curve, streak.read_image(os.path.join(TMP, "curve_gltf.exr")))
        print(f"ramp curve and rolling shutter against the flags: {whole:.1f} dB, foreground {fg:.1f} dB")
        self.assertGreaterEqual(whole, 45.0)
        self.assertGreaterEqual(fg, 45.0)
        _, changed = psnr(curve, streak.read_image(os.path.join(TMP, "box.exr")))
        self.assertLess(changed, 35.0)  # and they change the image
        # Cycles reads the same two settings the same way (its rows roll from the top too).
        emission_materials()
        render_cycles(os.path.join(TMP, "curve_cycles.exr"), 256)
        _, fg = psnr(curve, streak.read_image(os.path.join(TMP, "curve_cycles.exr")))
        print(f"ramp curve and rolling shutter against Cycles 256 spp: foreground {fg:.1f} dB")
        self.assertGreaterEqual(fg, 35.0)

    def test_cancel_stops_the_render_within_a_second(self):
        original = engine.StreakRenderEngine.should_stop
        deadline = [0.0]
        engine.StreakRenderEngine.should_stop = lambda self: time.perf_counter() > deadline[0]
        try:
            scene = bpy.context.scene
            scene.render.engine = "STREAK"
            scene.streak.method, scene.streak.samples, scene.streak.aa = "accumulation", 4096, 8
            start = time.perf_counter()
            deadline[0] = start + 1.0
            bpy.ops.render.render()
            stopped = time.perf_counter() - deadline[0]
        finally:
            engine.StreakRenderEngine.should_stop = original
        print(f"cancelled {stopped:.3f} s after the cancel")
        self.assertEqual(engine.last_render["status"], "cancelled")
        self.assertLess(stopped, 1.0)
        # Cancelled before the first key is evaluated: nothing is exported.
        engine.StreakRenderEngine.should_stop = lambda self: True
        try:
            bpy.ops.render.render()
        finally:
            engine.StreakRenderEngine.should_stop = original
        self.assertEqual(engine.last_render, {"status": "cancelled"})
        # Uncancelled, the same render takes far longer than the second it was given.
        scene.streak.samples = 64
        report = render_addon(os.path.join(TMP, "short.exr"), method="accumulation", samples=64, aa=8)
        self.assertEqual(report["status"], "done")
        print(f"64 instants take {report['stats']['time_ms']['render']:.0f} ms")
        self.assertGreater(report["stats"]["time_ms"]["render"] * 4096 / 64, 2000.0)

    def test_the_vector_pass_is_cycles_with_motion_blur_off(self):
        # Issue 29's check of streak's Vector pass (the command line's, on Blender's glTF export):
        # with motion blur off Cycles writes one, here under the trucking camera and the moving,
        # turning, bending objects. Where both see a surface over the whole pixel, the vectors agree.
        scene = bpy.context.scene
        scene.render.use_motion_blur = False
        ours = os.path.join(TMP, "vector_streak.exr")
        render_gltf(ours, "--passes", "vector")
        scene.view_layers[0].use_pass_vector = True
        render_cycles(os.path.join(TMP, "vector_cycles.exr"), 16, multilayer=True)
        a, b = streak.read_layers(ours), streak.read_layers(os.path.join(TMP, "vector_cycles.exr"))
        inside = (a["image"][..., 3] > 0.999) & (b["ViewLayer.Combined.A"] > 0.999)
        self.assertGreater(int(inside.sum()), 1000)
        for channel in "XYZW":
            x, y = a[f"vector.{channel}"][inside], b[f"ViewLayer.Vector.{channel}"][inside]
            rms = float(np.sqrt(((x - y) ** 2).mean()))
            print(f"vector.{channel}: streak mean {x.mean():.4f} px, Cycles {y.mean():.4f} px, RMS difference {rms:.4f} px, "
                  f"values up to {np.abs(y).max():.2f} px")
            self.assertLess(rms, 0.05)
            self.assertLess(abs(float(x.mean() - y.mean())), 0.01)
            self.assertGreater(float(np.abs(y).max()), 3.0)  # the scene moves by pixels a frame
        # At silhouettes too: the vector is the mean motion of what shows, not premultiplied by
        # its coverage, as Cycles divides its motion by its weight (premultiplied, a half-covered
        # pixel moving 10 px would read 5).
        edge = (a["image"][..., 3] > 0.05) & (b["ViewLayer.Combined.A"] > 0.05) & ~inside
        self.assertGreater(int(edge.sum()), 100)
        for channel in "XYZW":
            d = a[f"vector.{channel}"][edge] - b[f"ViewLayer.Vector.{channel}"][edge]
            print(f"vector.{channel} at edges: median difference {np.median(np.abs(d)):.4f} px, RMS {np.sqrt((d ** 2).mean()):.4f} px")
            self.assertLess(float(np.median(np.abs(d))), 0.02)
            self.assertLess(float(np.sqrt((d ** 2).mean())), 0.15)
        # The add-on's own Vector pass: the frames evaluated in Blender, against Cycles' the same way.
        report = render_addon(os.path.join(TMP, "vector_addon.exr"), multilayer=True)
        self.assertEqual(report["status"], "done", report)
        self.assertFalse(any("Vector" in w for w in report["warnings"]), report["warnings"])
        c = streak.read_layers(os.path.join(TMP, "vector_addon.exr"))
        inside = (c["ViewLayer.Combined.A"] > 0.999) & (b["ViewLayer.Combined.A"] > 0.999)
        self.assertGreater(int(inside.sum()), 1000)
        for channel in "XYZW":
            x, y = c[f"ViewLayer.Vector.{channel}"][inside], b[f"ViewLayer.Vector.{channel}"][inside]
            rms = float(np.sqrt(((x - y) ** 2).mean()))
            print(f"add-on Vector.{channel}: mean {x.mean():.4f} px, Cycles {y.mean():.4f} px, RMS difference {rms:.4f} px")
            self.assertLess(rms, 0.05)
            self.assertLess(abs(float(x.mean() - y.mean())), 0.01)
        # With motion blur on (Cycles then writes no Vector pass), the mean motion over the
        # shutter of what shows: near the shut shutter's where the motion is steady.
        scene.render.use_motion_blur = True
        report = render_addon(os.path.join(TMP, "vector_addon_blur.exr"), multilayer=True)
        self.assertEqual(report["status"], "done", report)
        blurred = streak.read_layers(os.path.join(TMP, "vector_addon_blur.exr"))
        both = inside & (blurred["ViewLayer.Combined.A"] > 0.999)
        for channel in "XZ":
            self.assertLess(abs(float(blurred[f"ViewLayer.Vector.{channel}"][both].mean() - c[f"ViewLayer.Vector.{channel}"][both].mean())), 0.5)

    def test_changing_topology_moves_from_the_frame(self):
        # Shutter [5, 5.5] (Start on Frame): a sphere whose faces grow, with a velocity of one unit
        # a frame along x, sweeps from where it is at frame 5 to half a unit on.
        scene = bpy.context.scene
        scene.cycles.motion_blur_position = "START"
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.4, location=(-1.5, -1.0, -0.7))
        sphere = bpy.context.object
        velocity = sphere.data.attributes.new("velocity", "FLOAT_VECTOR", "POINT")
        velocity.data.foreach_set("vector", [24.0, 0.0, 0.0] * len(sphere.data.vertices))
        sphere.modifiers.new("Build", "BUILD").frame_duration = 100
        for other in ("Cube", "Cylinder", "Grid"):
            bpy.data.objects[other].hide_render = True
        scene.camera.animation_data_clear()
        moving = render_addon(os.path.join(TMP, "swept.exr"))
        self.assertEqual(moving["moved_by_velocity"], ["Sphere"])
        scene.render.use_motion_blur = False
        render_addon(os.path.join(TMP, "at_frame.exr"))
        swept = streak.read_image(os.path.join(TMP, "swept.exr"))[..., 3]
        still = streak.read_image(os.path.join(TMP, "at_frame.exr"))[..., 3]
        columns = np.arange(still.shape[1])
        centre = lambda alpha: float((alpha.sum(axis=0) * columns).sum() / alpha.sum())
        # The mean of the sweep is a quarter unit on: in pixels at the sphere's view depth.
        view = scene.camera.matrix_world.inverted() @ sphere.matrix_world.translation
        fov = 2.0 * math.atan(0.5 * scene.camera.data.sensor_width / scene.camera.data.lens)  # horizontal: the image is wider
        quarter = 0.25 * (0.5 * scene_builder.WIDTH) / (-view.z * math.tan(0.5 * fov))
        shift = centre(swept) - centre(still)
        print(f"velocity sweep: the coverage's centre moves {shift:.2f} px, a quarter unit is {quarter:.2f} px")
        self.assertAlmostEqual(shift, quarter, delta=0.1 * quarter)

    def test_keys_fall_on_linear_keyframes_that_halving_misses(self):
        # A quad with LINEAR keyframes at frames 5, 6, 7 and 8 (x: 0, 1, 1, 0: out, held, back)
        # under a shutter of 3 frames from frame 5. Its path kinks at frames 6 and 7, a third and
        # two thirds of the shutter, which no grid of halving's (2, 3, 5 ... 33 keys) holds. The
        # keys must be the four keyframes, the image the one a fixed 4 keys gives, and the
        # coverage's centre where the quad spends its time on average: 2/3 unit from frame 5's.
        scene = bpy.context.scene
        scene.render.motion_blur_shutter = 3.0
        scene.cycles.motion_blur_position = "START"
        for other in ("Cube", "Cylinder", "Grid"):
            bpy.data.objects[other].hide_render = True
        scene.camera.animation_data_clear()
        bpy.ops.mesh.primitive_plane_add(size=0.4, location=(-1.0, -1.0, -0.7))
        quad = bpy.context.object
        base = quad.location.x
        for frame, x in ((5, 0.0), (6, 1.0), (7, 1.0), (8, 0.0)):
            quad.location.x = base + x
            quad.keyframe_insert("location", index=0, frame=frame)
        scene_builder.linear(quad)
        scene.frame_set(scene_builder.FRAME)
        report = render_addon(os.path.join(TMP, "keyframes.exr"))
        self.assertEqual(report["keys"], 4)
        self.assertTrue(report["keys_on_keyframes"])
        fixed = render_addon(os.path.join(TMP, "keyframes_fixed.exr"), keys=4)
        self.assertFalse(fixed["keys_on_keyframes"])
        blurred = streak.read_image(os.path.join(TMP, "keyframes.exr"))
        self.assertEqual(psnr(blurred, streak.read_image(os.path.join(TMP, "keyframes_fixed.exr")))[0], float("inf"))
        scene.render.use_motion_blur = False
        render_addon(os.path.join(TMP, "keyframes_still.exr"), keys=0)
        still = streak.read_image(os.path.join(TMP, "keyframes_still.exr"))[..., 3]
        columns = np.arange(still.shape[1])
        centre = lambda alpha: float((alpha.sum(axis=0) * columns).sum() / alpha.sum())
        view = scene.camera.matrix_world.inverted() @ quad.matrix_world.translation
        fov = 2.0 * math.atan(0.5 * scene.camera.data.sensor_width / scene.camera.data.lens)  # horizontal: the image is wider
        expected = (2.0 / 3.0) * (0.5 * scene_builder.WIDTH) / (-view.z * math.tan(0.5 * fov))
        shift = centre(blurred[..., 3]) - centre(still)
        print(f"keyframe keys: the coverage's centre moves {shift:.2f} px, 2/3 unit is {expected:.2f} px")
        self.assertAlmostEqual(shift, expected, delta=0.05 * expected)

    def test_changing_topology_is_reported_not_crashed_on(self):
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=0.5, location=(0.0, -1.0, -0.6))
        still = bpy.context.object
        still.name = "Growing"
        build = still.modifiers.new("Build", "BUILD")
        build.frame_start, build.frame_duration = 1, 8
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=0.4, location=(-1.5, -1.0, -0.7))
        moving = bpy.context.object
        moving.name = "Flowing"
        velocity = moving.data.attributes.new("velocity", "FLOAT_VECTOR", "POINT")
        velocity.data.foreach_set("vector", [24.0, 0.0, 0.0] * len(moving.data.vertices))  # one unit a frame
        build = moving.modifiers.new("Build", "BUILD")
        build.frame_start, build.frame_duration = 1, 8
        report = render_addon(os.path.join(TMP, "topology.exr"))
        self.assertEqual(report["status"], "done", report)
        self.assertEqual(sorted(report["topology_changes"]), ["Flowing", "Growing"])
        self.assertEqual(report["moved_by_velocity"], ["Flowing"])
        self.assertTrue(any("change topology" in w for w in report["warnings"]))
        # The velocity streaks the sphere over the half frame's half unit; without it, it stands.
        velocity = moving.data.attributes["velocity"]
        velocity.data.foreach_set("vector", [0.0, 0.0, 0.0] * len(moving.data.vertices))
        moving.data.update()
        still_report = render_addon(os.path.join(TMP, "topology_still.exr"))
        self.assertEqual(still_report["status"], "done")
        streaked = streak.read_image(os.path.join(TMP, "topology.exr"))[..., 3]
        standing = streak.read_image(os.path.join(TMP, "topology_still.exr"))[..., 3]
        partial = lambda alpha: int(((alpha > 0.05) & (alpha < 0.95)).sum())
        self.assertGreater(partial(streaked), partial(standing) + 50)

    def test_an_orthographic_camera_is_an_error_not_a_traceback(self):
        bpy.context.scene.camera.data.type = "ORTHO"
        # The engine's report({'ERROR'}): shown in Blender's status bar, raised by the operator
        # when a script calls it.
        with self.assertRaisesRegex(RuntimeError, "streak: camera 'Camera' is ortho: streak renders perspective cameras only"):
            render_addon(os.path.join(TMP, "ortho.exr"))
        self.assertEqual(engine.last_render["status"], "error")

    def test_every_pass_is_the_command_lines_on_the_gltf_export(self):
        scene = bpy.context.scene
        layer = scene.view_layers[0]
        layer.use_pass_z = layer.use_pass_normal = layer.use_pass_diffuse_color = True
        layer.use_pass_cryptomatte_object = layer.use_pass_cryptomatte_material = True
        second = scene.view_layers.new("Second")
        second.use_pass_z = True
        path = os.path.join(TMP, "all_passes.exr")
        report = render_addon(path, multilayer=True)
        self.assertEqual(report["status"], "done")
        # The add-on's keys (halving within the tolerance), so that depths agree to 1e-4: the
        # command line may put its keys on the export's keyframes instead, a truer motion.
        render_gltf(os.path.join(TMP, "all_gltf.exr"), "--motion-keys", str(report["keys"]), "--passes",
                    "depth,normal,albedo,object_id,material_id")
        ours, theirs = streak.read_layers(path), streak.read_layers(os.path.join(TMP, "all_gltf.exr"))
        alpha = ours["ViewLayer.Combined.A"]
        np.testing.assert_allclose(alpha, theirs["image"][..., 3], atol=1e-4)
        covered = alpha > 0.999
        # A segment's depth at a sample is linear in time between its ends. The command line
        # merges the segments of a triangle whose corners and normals go on along one line
        # through the keys (the glTF's morphed normals do); the add-on's Blender normals of the
        # deformed surface turn otherwise, so it merges fewer (178 slots against 386 when this
        # was written) and keeps those joints, where the depth is sampled once more.
        np.testing.assert_allclose(ours["ViewLayer.Depth.Z"][covered], theirs["Z"][covered], rtol=5e-4)
        # Normals on the rigid cube: the deformed ones differ by construction (Blender normals the
        # deformed surface, glTF skinning and morphing turn the rest normals).
        cube = streak.cryptomatte_matte(path, "ViewLayer.CryptoObject", "Cube") > 0.999
        self.assertGreater(int(cube.sum()), 200)
        for axis in "XYZ":
            # The glTF's world is y-up, Blender's z-up: the exporter turns (x, y, z) into (x, z, -y).
            gltf_axis = {"X": "normal.X", "Y": "normal.Z", "Z": "normal.Y"}[axis]
            sign = -1.0 if axis == "Y" else 1.0
            np.testing.assert_allclose(ours[f"ViewLayer.Normal.{axis}"][cube], sign * theirs[gltf_axis][cube], atol=2e-3)
        for ours_channel, theirs_channel in zip("RGB", ("albedo.R", "albedo.G", "albedo.B")):
            np.testing.assert_allclose(ours[f"ViewLayer.DiffCol.{ours_channel}"], theirs[theirs_channel], atol=2e-3)
        for kind, names in (("CryptoObject", ("Cube", "Cylinder", "Grid")), ("CryptoMaterial", ("Checker", "Orange", "Teal"))):
            for name in names:
                np.testing.assert_allclose(streak.cryptomatte_matte(path, f"ViewLayer.{kind}", name),
                                           streak.cryptomatte_matte(os.path.join(TMP, "all_gltf.exr"), kind, name), atol=1e-4)
        # The second view layer is rendered into its own layer, not over the first.
        np.testing.assert_array_equal(ours["Second.Combined.A"], alpha)
        np.testing.assert_array_equal(ours["Second.Depth.Z"], ours["ViewLayer.Depth.Z"])
        keys = {k.split("/")[1] for k in ours["metadata"] if k.startswith("cryptomatte/")}
        self.assertEqual(keys, {streak.cryptomatte_key("ViewLayer.CryptoObject"), streak.cryptomatte_key("ViewLayer.CryptoMaterial")})

    def test_without_film_transparent_the_world_shows_behind(self):
        scene = bpy.context.scene
        render_addon(os.path.join(TMP, "over.exr"))
        over = streak.read_image(os.path.join(TMP, "over.exr"))
        scene.render.film_transparent = False
        scene.world.color = (0.2, 0.3, 0.4)
        render_addon(os.path.join(TMP, "world.exr"))
        world = streak.read_image(os.path.join(TMP, "world.exr"))
        expected = over[..., :3] + np.array([0.2, 0.3, 0.4]) * (1.0 - over[..., 3:4])
        np.testing.assert_allclose(world[..., :3], expected, atol=1e-5)
        np.testing.assert_array_equal(world[..., 3], np.ones_like(world[..., 3]))

    def test_border_render_is_the_whole_renders_pixels(self):
        scene = bpy.context.scene
        render_addon(os.path.join(TMP, "whole.exr"), shading="PHONG")
        scene.render.use_border, scene.render.use_crop_to_border = True, False
        scene.render.border_min_x, scene.render.border_max_x = 0.2371, 0.7513
        scene.render.border_min_y, scene.render.border_max_y = 0.3037, 0.8011
        render_addon(os.path.join(TMP, "border.exr"), shading="PHONG")
        whole = streak.read_image(os.path.join(TMP, "whole.exr"))
        border = streak.read_image(os.path.join(TMP, "border.exr"))
        w, h = scene_builder.WIDTH, scene_builder.HEIGHT
        x0, x1, y0, y1 = int(0.2371 * w), int(0.7513 * w), h - int(0.8011 * h), h - int(0.3037 * h)  # rows from the top
        self.assertTrue(np.array_equal(border[y0:y1, x0:x1], whole[y0:y1, x0:x1]))
        self.assertGreater(float(whole[y0:y1, x0:x1, 3].sum()), 100.0)  # something is there
        outside = np.ones((h, w), dtype=bool)
        outside[y0:y1, x0:x1] = False
        self.assertEqual(float(np.abs(border[outside]).max()), 0.0)

    def test_an_animation_renders_every_frame(self):
        scene = bpy.context.scene
        scene.render.engine = "STREAK"
        scene.streak.shading, scene.streak.aa = "UNLIT", 1
        scene.frame_start, scene.frame_end = 4, 6
        scene.render.image_settings.file_format = "OPEN_EXR"
        scene.render.filepath = os.path.join(TMP, "anim_####")
        bpy.ops.render.render(animation=True)
        frames = [streak.read_image(os.path.join(TMP, f"anim_{f:04d}.exr")) for f in (4, 5, 6)]
        self.assertLess(psnr(frames[0], frames[1])[0], 40.0)
        self.assertLess(psnr(frames[1], frames[2])[0], 40.0)


result = unittest.main(argv=["test_addon"], exit=False, verbosity=2).result
if not result.wasSuccessful():
    raise SystemExit(1)
