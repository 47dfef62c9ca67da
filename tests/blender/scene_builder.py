"""The add-on test's scene, built by script in a factory-fresh Blender: a textured cube moving
and turning, an armature-deformed cylinder, a shape-key animation and a moving camera, all
keyed LINEAR so that Blender's subframes and glTF's per-frame samples move alike."""

import math
import os

import bpy
import numpy as np

WIDTH, HEIGHT = 160, 120
FRAME = 5


def linear(obj_or_data):
    animation = obj_or_data.animation_data
    if animation and animation.action:
        for fcurve in animation.action.fcurves:
            for point in fcurve.keyframe_points:
                point.interpolation = "LINEAR"


def _material(name, colour, image=None):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    if image is not None:
        tex = material.node_tree.nodes.new("ShaderNodeTexImage")
        tex.image = image
        material.node_tree.links.new(bsdf.inputs["Base Color"], tex.outputs["Color"])
    return material


def _checker(folder):
    size = 64
    y, x = np.mgrid[0:size, 0:size]
    cells = ((x // 16) + (y // 16)) % 2
    pixels = np.zeros((size, size, 4), dtype=np.float32)
    pixels[..., 0] = np.where(cells, 0.9, 0.1)
    pixels[..., 1] = np.where(cells, 0.7, 0.2) * (0.5 + 0.5 * x / size)
    pixels[..., 2] = np.where(cells, 0.1, 0.8)
    pixels[..., 3] = 1.0
    image = bpy.data.images.new("checker", size, size)
    image.pixels.foreach_set(pixels.reshape(-1))
    path = os.path.join(folder, "checker.png")
    image.filepath_raw = path
    image.file_format = "PNG"
    image.save()
    image.source = "FILE"
    image.reload()
    return image


def _cube(folder):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(-2.2, 0.0, 0.3))
    cube = bpy.context.object
    cube.name = "Cube"
    cube.data.materials.append(_material("Checker", (1.0, 1.0, 1.0), _checker(folder)))
    cube.keyframe_insert("location", frame=4)
    cube.keyframe_insert("rotation_euler", frame=4)
    cube.location.x += 1.2
    cube.rotation_euler.z += math.radians(80)
    cube.keyframe_insert("location", frame=6)
    cube.keyframe_insert("rotation_euler", frame=6)
    linear(cube)
    return cube


def _cylinder():
    rings, segments = 9, 16
    verts, faces = [], []
    for r in range(rings):
        z = -1.0 + 2.0 * r / (rings - 1)
        for s in range(segments):
            a = 2.0 * math.pi * s / segments
            verts.append((0.3 * math.cos(a), 0.3 * math.sin(a), z))
    for r in range(rings - 1):
        for s in range(segments):
            a, b = r * segments + s, r * segments + (s + 1) % segments
            faces.append((a, b, b + segments, a + segments))
    mesh = bpy.data.meshes.new("Cylinder")
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    cylinder = bpy.data.objects.new("Cylinder", mesh)
    bpy.context.collection.objects.link(cylinder)
    cylinder.location = (1.3, 0.0, 0.0)
    cylinder.data.materials.append(_material("Orange", (0.9, 0.4, 0.1)))
    lower, upper = cylinder.vertex_groups.new(name="Lower"), cylinder.vertex_groups.new(name="Upper")
    for i, v in enumerate(verts):
        w = min(1.0, max(0.0, (v[2] + 0.25) / 0.5))
        lower.add([i], 1.0 - w, "REPLACE")
        upper.add([i], w, "REPLACE")

    armature = bpy.data.armatures.new("Rig")
    rig = bpy.data.objects.new("Rig", armature)
    bpy.context.collection.objects.link(rig)
    rig.location = cylinder.location
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode="EDIT")
    low = armature.edit_bones.new("Lower")
    low.head, low.tail = (0, 0, -1), (0, 0, 0)
    up = armature.edit_bones.new("Upper")
    up.head, up.tail = (0, 0, 0), (0, 0, 1)
    up.parent = low
    bpy.ops.object.mode_set(mode="OBJECT")
    bone = rig.pose.bones["Upper"]
    bone.rotation_mode = "XYZ"
    bone.keyframe_insert("rotation_euler", frame=4)
    bone.rotation_euler.x = math.radians(50)
    bone.keyframe_insert("rotation_euler", frame=6)
    linear(rig)
    cylinder.parent = rig
    cylinder.location = (0, 0, 0)
    modifier = cylinder.modifiers.new("Armature", "ARMATURE")
    modifier.object = rig
    return cylinder


def _shape_keys():
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=12, y_subdivisions=12, size=1.4, location=(0.0, 0.8, 1.3))
    grid = bpy.context.object
    grid.name = "Grid"
    grid.rotation_euler.x = math.radians(90)
    grid.data.materials.append(_material("Teal", (0.1, 0.6, 0.6)))
    grid.shape_key_add(name="Basis")
    bulge = grid.shape_key_add(name="Bulge")
    for point in bulge.data:
        x, y, _ = point.co
        point.co.z += 0.5 * math.exp(-4.0 * (x * x + y * y))
        point.co.x *= 1.3
    bulge.value = 0.0
    bulge.keyframe_insert("value", frame=4)
    bulge.value = 1.0
    bulge.keyframe_insert("value", frame=6)
    linear(grid.data.shape_keys)
    return grid


def _camera():
    data = bpy.data.cameras.new("Camera")
    data.lens = 35.0
    camera = bpy.data.objects.new("Camera", data)
    bpy.context.collection.objects.link(camera)
    camera.location = (0.0, -7.0, 0.6)
    camera.rotation_euler = (math.radians(88), 0.0, 0.0)
    camera.keyframe_insert("location", frame=4)
    camera.location.x += 0.6
    camera.keyframe_insert("location", frame=6)
    linear(camera)
    return camera


def build(folder):
    """A fresh scene at frame FRAME, motion blur on (0.5 frames, centred), a black world."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = WIDTH, HEIGHT, 100
    scene.render.fps, scene.render.fps_base = 24, 1.0
    scene.frame_start, scene.frame_end = 1, 10
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 0.5
    scene.cycles.motion_blur_position = "CENTER"
    scene.render.film_transparent = True
    world = bpy.data.worlds.new("World")
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    _cube(folder)
    _cylinder()
    _shape_keys()
    scene.camera = _camera()
    scene.frame_set(FRAME)
    return scene
