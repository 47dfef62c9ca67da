# streak inside Blender: a render engine (bl_idname "STREAK") that renders the scene Blender
# evaluates (modifiers, armatures, shape keys, geometry nodes, caches) with streak's exact motion
# blur, under Blender's own motion-blur settings. README, "Blender", says how to install it.

bl_info = {
    "name": "streak",
    "author": "streak",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > streak",
    "description": "Analytic motion blur: the exact time spans in which each triangle is visible",
    "category": "Render",
}

from . import engine, properties, ui  # noqa: E402


def register():
    properties.register()
    engine.register()
    ui.register()


def unregister():
    ui.unregister()
    engine.unregister()
    properties.unregister()
