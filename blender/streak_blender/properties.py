"""The engine's settings, per scene (scene.streak), and the add-on's preferences."""

import bpy

# The CPU methods (`streak methods`): the exact ones first, then the sampled references.
METHODS = [
    ("motion-path", "Motion path", "Exact visible spans by motion paths (Hong & Oh); the default"),
    ("analytic", "Analytic", "Exact visible spans by the edge equations in time (Gribel et al. 2010)"),
    ("higher-order", "Higher order", "Exact spans of curved motion (Gribel et al. 2013)"),
    ("accumulation", "Accumulation", "Reference: the average of rasterized instants (Samples)"),
    ("stochastic", "Stochastic", "Reference: stochastic rasterization (Samples per pixel sample)"),
    ("embree", "Embree", "Peer: ray tracing with Embree's motion blur (Samples rays per pixel sample)"),
]

# The methods that find exact visible spans (and refine adaptively).
EXACT_METHODS = {"motion-path", "analytic", "higher-order"}
# The exact methods that take line samples where nothing in a tile moves.
LINE_METHODS = {"motion-path", "analytic"}


class StreakRenderSettings(bpy.types.PropertyGroup):
    method: bpy.props.EnumProperty(name="Method", items=METHODS, default="motion-path")
    aa: bpy.props.IntProperty(name="Spatial Samples", description="N x N sub-pixel samples per pixel (box filter)",
                              default=4, min=1, max=16)
    adaptive: bpy.props.FloatProperty(name="Adaptive Threshold", description="Exact methods: one sample per pixel first, then the "
                                      "Spatial Samples (or half as many a side: Full Samples Above) where a pixel and a neighbour differ by more than this in display colour or coverage, "
                                      "or where a thin part no pixel centre saw lies (0: every pixel takes them all; 0.02 refines what "
                                      "aliasing shows)", default=0.0, min=0.0, max=1.0, precision=3)
    adaptive_full: bpy.props.FloatProperty(name="Full Samples Above", description="With an Adaptive Threshold and 3 or more Spatial "
                                           "Samples: a refined pixel whose largest difference is at most this takes half the samples a "
                                           "side (at least 2), the rest all of them (0: three times the threshold; the threshold itself: "
                                           "every refined pixel all of them)", default=0.0, min=0.0, max=1.0, precision=3)
    line_samples: bpy.props.BoolProperty(name="Line Samples", description="Motion path and analytic: where nothing in a tile moves, "
                                         "each sample is the line through it across its pixel, so edges and texture are integrated "
                                         "exactly along x and sampled only at the lines' rows", default=False)
    line_rows: bpy.props.IntProperty(name="Line Rows", description="Lines per pixel where samples are lines (0: the Spatial Samples' "
                                     "N x N rows); fewer trade edges near horizontal for time", default=0, min=0, max=256)
    keys: bpy.props.IntProperty(name="Motion Keys", description="Poses evaluated over the shutter: vertices move on straight lines between "
                                "them (0: as many as Key Tolerance needs, up to 33, or fewer on the animation's keyframes where an even grid holds "
                                "them within Key Tolerance)", default=0, min=0, max=65)
    key_tolerance: bpy.props.FloatProperty(name="Key Tolerance", description="With Motion Keys 0: keys are doubled until a vertex half-way "
                                           "between two keys is within this many pixels of its straight line", default=0.125, min=0.01, max=16.0)
    shading: bpy.props.EnumProperty(name="Shading", items=[("PHONG", "Phong", "streak's directional light and ambient"),
                                                           ("UNLIT", "Unlit", "The base colour times the texture, as an emission shader")],
                                    default="PHONG")
    samples: bpy.props.IntProperty(name="Samples", description="Accumulation: instants; stochastic and embree: times per pixel sample",
                                   default=16, min=1, max=4096)
    threads: bpy.props.IntProperty(name="Threads", description="Worker threads (0: every core)", default=0, min=0, max=1024)


class StreakPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_folder: bpy.props.StringProperty(name="streak module folder", subtype="DIR_PATH",
                                            description="A folder holding the streak Python module (a build's python/ folder); "
                                            "empty: the module in the add-on's zip, or on Python's path")

    def draw(self, context):
        self.layout.prop(self, "module_folder")


def register():
    bpy.utils.register_class(StreakRenderSettings)
    bpy.utils.register_class(StreakPreferences)
    bpy.types.Scene.streak = bpy.props.PointerProperty(type=StreakRenderSettings)


def unregister():
    del bpy.types.Scene.streak
    bpy.utils.unregister_class(StreakPreferences)
    bpy.utils.unregister_class(StreakRenderSettings)
