"""The engine's panels in Render Properties: streak's settings, and Blender's own Motion Blur
and Film settings (the Cycles names streak honours), drawn while streak is the engine."""

import bpy

from .properties import EXACT_METHODS, LINE_METHODS


class StreakPanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"STREAK"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES


class RENDER_PT_streak(StreakPanel, bpy.types.Panel):
    bl_label = "streak"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        settings = context.scene.streak
        layout.prop(settings, "method")
        layout.prop(settings, "aa")
        if settings.method in EXACT_METHODS:
            layout.prop(settings, "adaptive")
            if settings.adaptive > 0.0:
                layout.prop(settings, "adaptive_full")
        if settings.method in LINE_METHODS:
            layout.prop(settings, "line_samples")
            if settings.line_samples:
                layout.prop(settings, "line_rows")
        if settings.method in {"accumulation", "stochastic", "embree"}:
            layout.prop(settings, "samples")
        layout.prop(settings, "keys")
        if settings.keys == 0:
            layout.prop(settings, "key_tolerance")
        layout.prop(settings, "shading")
        layout.prop(settings, "threads")


class RENDER_PT_streak_motion_blur(StreakPanel, bpy.types.Panel):
    bl_label = "Motion Blur"

    def draw_header(self, context):
        self.layout.prop(context.scene.render, "use_motion_blur", text="")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        scene = context.scene
        r = scene.render
        layout.active = r.use_motion_blur
        cycles = getattr(scene, "cycles", None)
        if cycles is not None:
            layout.prop(cycles, "motion_blur_position", text="Position")
        layout.prop(r, "motion_blur_shutter")
        if cycles is not None:
            layout.prop(cycles, "rolling_shutter_type", text="Rolling Shutter")
            sub = layout.column()
            sub.active = cycles.rolling_shutter_type != "NONE"
            sub.prop(cycles, "rolling_shutter_duration")
        layout.label(text="Shutter Curve")
        layout.template_curve_mapping(r, "motion_blur_shutter_curve")


class RENDER_PT_streak_film(StreakPanel, bpy.types.Panel):
    bl_label = "Film"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(context.scene.render, "film_transparent")


class VIEWLAYER_PT_streak_passes(StreakPanel, bpy.types.Panel):
    bl_label = "Passes"
    bl_context = "view_layer"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        view_layer = context.view_layer
        layout.prop(view_layer, "use_pass_z")
        layout.prop(view_layer, "use_pass_normal")
        layout.prop(view_layer, "use_pass_diffuse_color")
        layout.prop(view_layer, "use_pass_cryptomatte_object")
        layout.prop(view_layer, "use_pass_cryptomatte_material")
        layout.prop(view_layer, "pass_cryptomatte_depth")


_CLASSES = (RENDER_PT_streak, RENDER_PT_streak_motion_blur, RENDER_PT_streak_film, VIEWLAYER_PT_streak_passes)


def _generic_panels():
    """Blender's panels every engine shares (format, frame range, output, metadata...): those
    that name the built-in 'BLENDER_RENDER' among their engines, as Blender's own example does."""
    for panel in bpy.types.Panel.__subclasses__():
        if "BLENDER_RENDER" in getattr(panel, "COMPAT_ENGINES", ()):
            yield panel


def register():
    for c in _CLASSES:
        bpy.utils.register_class(c)
    for panel in _generic_panels():
        panel.COMPAT_ENGINES.add("STREAK")


def unregister():
    for panel in _generic_panels():
        panel.COMPAT_ENGINES.discard("STREAK")
    for c in reversed(_CLASSES):
        bpy.utils.unregister_class(c)
