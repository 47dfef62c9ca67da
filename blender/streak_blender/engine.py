"""The render engine: F12 renders Blender's evaluated scene with streak, Ctrl-F12 every frame."""

import time

import bpy
import numpy as np

from . import export, module
from .properties import EXACT_METHODS, LINE_METHODS

# What the last render did (keys, triangles, warnings, streak's stats), for scripts and tests.
last_render = {}

# Blender's pass names for streak's passes: (Blender pass, channels, channel ids, type,
# streak pass, streak channels).
_PASSES = [
    ("use_pass_z", "Depth", 1, "Z", "VALUE", "depth", ["Z"]),
    ("use_pass_normal", "Normal", 3, "XYZ", "VECTOR", "normal", ["normal.X", "normal.Y", "normal.Z"]),
    ("use_pass_diffuse_color", "DiffCol", 3, "RGB", "COLOR", "albedo", ["albedo.R", "albedo.G", "albedo.B"]),
    ("use_pass_vector", "Vector", 4, "XYZW", "VECTOR", "vector", ["vector.X", "vector.Y", "vector.Z", "vector.W"]),
]
_CRYPTO = [("use_pass_cryptomatte_object", "CryptoObject", "object_id"),
           ("use_pass_cryptomatte_material", "CryptoMaterial", "material_id")]


def _crypto_layers(view_layer):
    return (view_layer.pass_cryptomatte_depth + 1) // 2


class StreakRenderEngine(bpy.types.RenderEngine):
    bl_idname = "STREAK"
    bl_label = "streak"
    bl_use_preview = False
    bl_use_postprocess = True

    def update_render_passes(self, scene=None, renderlayer=None):
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", "COLOR")
        for flag, name, channels, ids, kind, _, _ in _PASSES:
            if getattr(renderlayer, flag):
                self.register_pass(scene, renderlayer, name, channels, ids, kind)
        for flag, name, _ in _CRYPTO:
            if getattr(renderlayer, flag):
                for i in range(_crypto_layers(renderlayer)):
                    self.register_pass(scene, renderlayer, f"{name}{i:02d}", 4, "RGBA", "COLOR")

    def should_stop(self):
        """Whether the user cancelled (Esc); asked with every progress step of the render."""
        return self.test_break()

    def render(self, depsgraph):
        global last_render
        last_render = {"status": "started"}
        scene = depsgraph.scene
        try:
            self._render(depsgraph, scene)
        except Exception as e:  # noqa: BLE001: shown to the user as one line, never a traceback
            # Esc while the keys are evaluated (export.Cancelled) or while streak renders
            # (streak.Cancelled): a stop, not an error.
            cancelled = isinstance(e, export.Cancelled) or type(e).__name__ == "Cancelled"
            last_render["status"] = "cancelled" if cancelled else "error"
            if not cancelled:
                last_render["error"] = str(e)
                self.report({"ERROR"}, f"streak: {e}")

    def _render(self, depsgraph, scene):
        preferences = bpy.context.preferences.addons.get(__package__)
        folder = preferences.preferences.module_folder if preferences is not None else ""
        streak = module.load(bpy.path.abspath(folder) if folder else "")
        settings = scene.streak
        width, height = export.image_size(scene)
        started = time.perf_counter()
        self.update_stats("", "streak: evaluating the shutter's keys")
        meshes, materials, textures, camera, frame_cameras, report = export.build(self, depsgraph, settings, height)
        if self.should_stop():
            raise streak.Cancelled("the render was cancelled")
        sc = streak.Scene.from_meshes(meshes, materials, textures, camera, export.world_colour(scene), frame_cameras=frame_cameras)
        sc = sc.with_shutter(export.shutter_curve(scene), export.rolling_duration(scene))
        for line in report.warnings():
            self.report({"WARNING"}, f"streak: {line}")
        export_ms = (time.perf_counter() - started) * 1000.0
        summary = f"streak {settings.method}: {report.objects} objects, {report.triangles} triangles, {report.keys} keys" + (" on the keyframes" if report.keys_on_keyframes else "")
        self.update_stats("", summary)

        view_layer = depsgraph.view_layer
        passes = [p for flag, _, _, _, _, p, _ in _PASSES if getattr(view_layer, flag)]
        passes += [p for flag, _, p in _CRYPTO if getattr(view_layer, flag)]
        options = {}
        if settings.method in ("accumulation", "stochastic", "embree"):
            options["samples"] = str(settings.samples)
        if settings.method in LINE_METHODS and settings.line_samples:
            options["line-samples"] = "1"
            if settings.line_rows > 0:
                options["line-rows"] = str(settings.line_rows)
        region = export.border_region(scene, width, height)
        transparent = scene.render.film_transparent
        last_render.update({"keys": report.keys, "keys_on_keyframes": report.keys_on_keyframes, "objects": report.objects, "triangles": report.triangles,
                            "topology_changes": list(report.topology_changes), "moved_by_velocity": list(report.moved_by_velocity),
                            "camera_baked": report.camera_baked, "warnings": report.warnings(), "export_ms": export_ms})

        def progress(fraction):
            self.update_progress(fraction)

        # Adaptive anti-aliasing is the exact methods', and refines to aa >= 2.
        adaptive = settings.adaptive if settings.method in EXACT_METHODS and settings.aa >= 2 else 0.0
        out = streak.render(sc, method=settings.method, width=width, height=height, aa=settings.aa, adaptive=adaptive,
                            adaptive_full=settings.adaptive_full if adaptive > 0.0 else 0.0,
                            unlit=settings.shading == "UNLIT",
                            options=options, threads=settings.threads, region=region, transparent=True, passes=passes,
                            cryptomatte_ranks=2 * _crypto_layers(view_layer), stats=True, progress=progress, cancel=self.should_stop)
        result_image, stats = out
        layers = result_image if isinstance(result_image, dict) else {"image": result_image}
        rgba = layers["image"]
        if not transparent:
            # Over the world's colour, opaque, as Blender shows a render without Film > Transparent.
            background = np.array(export.world_colour(scene), dtype=np.float32)
            rgba = rgba.copy()
            rgba[..., :3] += background * (1.0 - rgba[..., 3:4])
            rgba[..., 3] = 1.0
        # A border render's result is the border's rectangle (self.size_x by size_y), which
        # Blender places in the frame itself.
        result = self.begin_result(0, 0, rgba.shape[1], rgba.shape[0], layer=view_layer.name)
        try:
            layer = result.layers[0]
            layer.passes["Combined"].rect = _rows_up(rgba)
            for flag, name, channels, _, _, _, names in _PASSES:
                if getattr(view_layer, flag) and name in layer.passes:
                    layer.passes[name].rect = _rows_up(np.stack([layers[c] for c in names], axis=-1))
            for flag, name, _ in _CRYPTO:
                if not getattr(view_layer, flag):
                    continue
                for i in range(_crypto_layers(view_layer)):
                    channels = [f"{name}{i:02d}.{c}" for c in "rgba"]  # streak's layer has Blender's pass name
                    pass_name = f"{name}{i:02d}"
                    if pass_name in layer.passes and channels[0] in layers:
                        layer.passes[pass_name].rect = _rows_up(np.stack([layers[c] for c in channels], axis=-1))
        finally:
            self.end_result(result)
        # Cryptomatte's header (name, hash, conversion, manifest) in the render's metadata, as
        # Cycles writes it: the layer named as Blender names its own, ViewLayer.CryptoObject,
        # and keyed by that name, so each view layer's stays apart.
        whole = self.get_result()
        metadata = layers.get("metadata", {})
        for key, value in metadata.items():
            parts = key.split("/")
            if len(parts) == 3 and parts[0] == "cryptomatte" and parts[2] == "name":
                layer_name = f"{view_layer.name}.{value}"
                prefix = f"cryptomatte/{streak.cryptomatte_key(layer_name)}/"
                whole.stamp_data_add_field(prefix + "name", layer_name)
                for field in ("hash", "conversion", "manifest"):
                    whole.stamp_data_add_field(prefix + field, metadata[f"cryptomatte/{parts[1]}/{field}"])
        last_render.update({"status": "done", "stats": stats, "render_ms": (time.perf_counter() - started) * 1000.0})
        self.update_stats("", f"{summary}, {last_render['render_ms'] / 1000.0:.2f} s")


def _rows_up(image):
    """An H x W x C image (top row first) as Blender's pass rectangle: rows from the bottom."""
    h, w, c = image.shape
    return np.ascontiguousarray(image[::-1].reshape(h * w, c), dtype=np.float32)


def register():
    bpy.utils.register_class(StreakRenderEngine)


def unregister():
    bpy.utils.unregister_class(StreakRenderEngine)
