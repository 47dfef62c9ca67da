"""The scene as Blender evaluates it, at the shutter's key times, as streak arrays.

Every mesh object (and every instance of one) is evaluated at each key time with the depsgraph
(frame_set with subframes), so whatever Blender animates moves: modifiers, armatures, shape
keys, geometry nodes, and the caches Blender reads. Each loop triangle's corners become the
mesh's vertices (Blender's uvs and split normals live on corners), in world space, split by
material slot. Objects whose triangles change between keys cannot be interpolated: they move
along their `velocity` attribute where they have one, and stand still otherwise; both are
counted. The camera is taken at each key too."""

import math

import numpy as np

# Cycles' names; its add-on is in every Blender build, but is not required.
_POSITIONS = {"START": 0.0, "CENTER": -0.5, "END": -1.0}


class Report:
    """What the export did, for the engine's stats line and its warnings."""

    def __init__(self):
        self.keys = 0
        self.keys_on_keyframes = False  # the keys are on an even grid through the animation's keyframes
        self.objects = 0
        self.triangles = 0
        self.topology_changes = []   # names of objects whose triangles change between keys
        self.moved_by_velocity = []  # those of them moved along their velocity attribute
        self.camera_baked = False    # the camera's path is carried by the geometry
        self.unsupported = []        # what the export could not carry, one line each

    def warnings(self):
        out = []
        if self.topology_changes:
            still = [n for n in self.topology_changes if n not in self.moved_by_velocity]
            out.append(f"{len(self.topology_changes)} object(s) change topology over the shutter: "
                       f"{len(self.moved_by_velocity)} moved by their velocity attribute, {len(still)} held still "
                       f"({', '.join(self.topology_changes[:5])})")
        out.extend(self.unsupported)
        return out


def shutter_times(scene, frame, keys):
    """The key times (in frames, fractional) over the shutter at `frame`, as Blender's Motion
    Blur sets it: (times, shutter length in frames)."""
    r = scene.render
    if not r.use_motion_blur or r.motion_blur_shutter <= 0.0:
        return [frame, frame], 0.0
    length = r.motion_blur_shutter
    position = getattr(getattr(scene, "cycles", None), "motion_blur_position", "CENTER")
    start = frame + _POSITIONS.get(position, -0.5) * length
    return [start + length * k / (keys - 1) for k in range(keys)], length


def keyframe_frames(scene):
    """The frames of every keyframe in the actions that animate the scene's objects, their data
    (a camera's lens, a light) and their shape keys."""
    frames = set()
    for obj in scene.objects:
        data = obj.data
        for block in (obj, data, getattr(data, "shape_keys", None)):
            animation = getattr(block, "animation_data", None) if block is not None else None
            if animation and animation.action:
                for fcurve in getattr(animation.action, "fcurves", ()):  # (on Blender 4.4+, a layered action's first slot)
                    frames.update(point.co.x for point in fcurve.keyframe_points)
    return frames


def keyframe_grid_pieces(frames, start, length, most=32):
    """The fewest even pieces (up to `most`) of the shutter [start, start + length] whose ends hold
    every keyframe strictly inside it (to a thousandth of a piece), or 0 where there is none inside
    or no such grid: the command line's rule (gltf_loader's keyframeGridPieces)."""
    if not length > 0.0:
        return 0
    inside = [u for u in ((f - start) / length for f in frames) if 1e-6 < u < 1.0 - 1e-6]
    if not inside:
        return 0
    for pieces in range(1, most + 1):
        if all(abs(u * pieces - round(u * pieces)) <= 1e-3 for u in inside):
            return pieces
    return 0


def shutter_curve(scene, points=32):
    """Blender's Shutter Curve as streak's piecewise-linear curve T0:W0,...; "box" when flat or
    when motion blur is off."""
    if not scene.render.use_motion_blur:
        return "box"
    mapping = scene.render.motion_blur_shutter_curve
    mapping.initialize()
    curve = mapping.curves[0]
    xs = np.linspace(0.0, 1.0, points)
    ws = np.array([max(0.0, mapping.evaluate(curve, float(x))) for x in xs])
    if ws.max() <= 0.0:
        raise ValueError("the shutter curve is zero everywhere")
    if np.allclose(ws, ws[0], rtol=0.0, atol=1e-6):
        return "box"
    return ",".join(f"{x:.6g}:{w:.6g}" for x, w in zip(xs, ws))


def rolling_duration(scene):
    """Rolling Shutter: Top-Bottom with its duration, or 1 (a global shutter)."""
    cycles = getattr(scene, "cycles", None)
    if cycles is None or getattr(cycles, "rolling_shutter_type", "NONE") != "TOP":
        return 1.0
    return min(1.0, max(1e-3, float(cycles.rolling_shutter_duration)))


def image_size(scene):
    r = scene.render
    return max(1, int(r.resolution_x * r.resolution_percentage / 100)), max(1, int(r.resolution_y * r.resolution_percentage / 100))


def border_region(scene, width, height):
    """Border render as streak's region (x0, y0, x1, y1), top row 0; None for the whole frame."""
    r = scene.render
    if not r.use_border:
        return None
    # Blender truncates the border to pixels (render_init_from_main); its y counts from the bottom.
    x0, x1 = int(r.border_min_x * width), int(r.border_max_x * width)
    y0, y1 = height - int(r.border_max_y * height), height - int(r.border_min_y * height)
    if x1 <= x0 or y1 <= y0:
        return None
    return (x0, y0, x1, y1)


# --- The camera ---------------------------------------------------------------------------

class CameraKey:
    def __init__(self, matrix, fov):
        m = np.array(matrix, dtype=np.float64)
        self.rotation = m[:3, :3] / np.linalg.norm(m[:3, :3], axis=0)  # camera axes in world space, scale removed
        self.position = m[:3, 3].copy()
        self.fov = fov  # vertical, radians

    def pose(self):
        forward = -self.rotation[:, 2]
        return {"position": self.position.tolist(), "target": (self.position + forward).tolist(), "up": self.rotation[:, 1].tolist()}

    def to_camera(self, points):
        """World points in this key's camera space."""
        return (points - self.position) @ self.rotation


def vertical_fov(camera, scene):
    """The vertical field of view (radians) of a perspective camera under the render's aspect."""
    data = camera.data
    if data.type != "PERSP":
        raise ValueError(f"camera '{camera.name}' is {data.type.lower()}: streak renders perspective cameras only")
    r = scene.render
    width, height = r.resolution_x * r.pixel_aspect_x, r.resolution_y * r.pixel_aspect_y
    fit = data.sensor_fit
    if fit == "AUTO":
        fit = "HORIZONTAL" if width >= height else "VERTICAL"
        sensor = data.sensor_width
    else:
        sensor = data.sensor_width if fit == "HORIZONTAL" else data.sensor_height
    half = sensor / (2.0 * data.lens)
    if fit == "HORIZONTAL":
        half *= height / width
    return 2.0 * math.atan(half)


def _slerp_rotation(a, b, s):
    """The rotation s of the way from a to b (3x3 matrices), as a slerp of quaternions does."""
    relative = a.T @ b
    angle = math.acos(max(-1.0, min(1.0, (np.trace(relative) - 1.0) / 2.0)))
    if angle < 1e-9:
        return a
    axis = np.array([relative[2, 1] - relative[1, 2], relative[0, 2] - relative[2, 0], relative[1, 0] - relative[0, 1]])
    axis /= max(np.linalg.norm(axis), 1e-12)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    theta = angle * s
    return a @ (np.eye(3) + math.sin(theta) * k + (1.0 - math.cos(theta)) * (k @ k))


def camera_follows_streak(keys, tolerance=1e-4):
    """Whether streak's camera, moving from the first key to the last (position linearly,
    rotation by slerp, one field of view), passes through every key."""
    first, last = keys[0], keys[-1]
    scale = max(1.0, float(np.linalg.norm(last.position - first.position)))
    for k, key in enumerate(keys):
        s = k / (len(keys) - 1)
        if abs(key.fov - first.fov) > 1e-6:
            return False
        if np.linalg.norm(key.position - ((1 - s) * first.position + s * last.position)) > tolerance * scale:
            return False
        if np.abs(key.rotation - _slerp_rotation(first.rotation, last.rotation, s)).max() > tolerance:
            return False
    return True


# --- Materials and textures ---------------------------------------------------------------

def _linked_image(socket):
    """The image of an Image Texture node feeding `socket` directly, or None."""
    if not socket.is_linked:
        return None
    node = socket.links[0].from_node
    return node.image if node.type == "TEX_IMAGE" else None


def _surface_node(material):
    if not material.use_nodes or material.node_tree is None:
        return None
    for node in material.node_tree.nodes:
        if node.type == "OUTPUT_MATERIAL" and node.is_active_output and node.inputs["Surface"].is_linked:
            return node.inputs["Surface"].links[0].from_node
    return None


def texture_array(image):
    """An image as streak takes it: top row first; 8-bit sRGB as bytes, anything else as linear floats."""
    width, height = image.size
    if width == 0 or height == 0:
        raise ValueError(f"image '{image.name}' has no pixels (missing file?)")
    pixels = np.empty(width * height * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(height, width, 4)[::-1]
    if not image.is_float and image.colorspace_settings.name == "sRGB":
        return np.ascontiguousarray(np.clip(np.round(pixels * 255.0), 0, 255).astype(np.uint8))
    return np.ascontiguousarray(pixels)


class Materials:
    """streak materials for Blender's, each once: the surface shader's colour (Principled BSDF's
    Base Color, a Diffuse or Emission shader's Color, times an Emission shader's strength), an
    Image Texture linked straight to it, Principled's Alpha as opacity, and double-sidedness from
    Backface Culling."""

    def __init__(self, report):
        self.report = report
        self.materials = []
        self.textures = []
        self._index = {}
        self._images = {}

    def index(self, material):
        key = material.name_full if material is not None else None  # linked libraries may repeat a name
        if key not in self._index:
            self._index[key] = len(self.materials)
            self.materials.append(self._convert(material))
        return self._index[key]

    def _texture(self, image):
        if image.name_full not in self._images:
            self._images[image.name_full] = len(self.textures)
            self.textures.append(texture_array(image))
        return self._images[image.name_full]

    def _convert(self, material):
        if material is None:
            return {"base_color": [0.8, 0.8, 0.8], "double_sided": True, "name": "default"}
        out = {"base_color": list(material.diffuse_color[:3]), "double_sided": not material.use_backface_culling,
               "name": material.name}
        node = _surface_node(material)
        if node is None:
            return out
        colour_input = {"BSDF_PRINCIPLED": "Base Color", "BSDF_DIFFUSE": "Color", "EMISSION": "Color"}.get(node.type)
        if colour_input is None:
            self.report.unsupported.append(f"material '{material.name}': a {node.type.lower()} shader, shaded by its viewport colour")
            return out
        socket = node.inputs[colour_input]
        scale = node.inputs["Strength"].default_value if node.type == "EMISSION" else 1.0
        image = _linked_image(socket)
        if image is not None:
            out["texture"] = self._texture(image)
            out["base_color"] = [scale] * 3
        else:
            if socket.is_linked:
                self.report.unsupported.append(f"material '{material.name}': {colour_input} comes from a "
                                               f"{socket.links[0].from_node.type.lower()} node, shaded by its default value")
            out["base_color"] = [c * scale for c in socket.default_value[:3]]
        if node.type == "BSDF_PRINCIPLED" and not node.inputs["Alpha"].is_linked:
            out["opacity"] = float(node.inputs["Alpha"].default_value)
        return out


# --- Geometry -----------------------------------------------------------------------------

class Pose:
    """One object instance at one key: its loop triangles' corners in world space."""

    def __init__(self, mesh, matrix):
        mesh.calc_loop_triangles()
        if hasattr(mesh, "calc_normals_split"):
            mesh.calc_normals_split()
        tris = len(mesh.loop_triangles)
        loops = np.empty(tris * 3, dtype=np.int32)
        mesh.loop_triangles.foreach_get("loops", loops)
        vertex_of_loop = np.empty(len(mesh.loops), dtype=np.int32)
        mesh.loops.foreach_get("vertex_index", vertex_of_loop)
        co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", co)
        co = co.reshape(-1, 3)
        m = np.array(matrix, dtype=np.float64)
        corners = co[vertex_of_loop[loops]].astype(np.float64)
        self.positions = corners @ m[:3, :3].T + m[:3, 3]
        normals = np.empty(tris * 9, dtype=np.float32)
        mesh.loop_triangles.foreach_get("split_normals", normals)
        normal_matrix = np.linalg.inv(m[:3, :3]).T
        n = normals.reshape(-1, 3).astype(np.float64) @ normal_matrix.T
        self.normals = n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-20)
        # What must not change between keys for the corners to be interpolated.
        self.signature = (len(mesh.vertices), tris, hash(loops.tobytes()), hash(vertex_of_loop.tobytes()))
        self.mirrored = np.linalg.det(m[:3, :3]) < 0.0
        self.material_index = np.empty(tris, dtype=np.int32)
        mesh.loop_triangles.foreach_get("material_index", self.material_index)
        uv_layer = next((layer for layer in mesh.uv_layers if layer.active_render), None)  # what image textures sample
        self.uvs = None
        if uv_layer is not None:
            uv = np.empty(len(mesh.loops) * 2, dtype=np.float32)
            uv_layer.data.foreach_get("uv", uv)
            uv = uv.reshape(-1, 2)[loops]
            uv[:, 1] = 1.0 - uv[:, 1]  # Blender's v runs up from the bottom row, streak's down from the top
            self.uvs = uv
        self.velocity = None
        attribute = mesh.attributes.get("velocity") or mesh.attributes.get(".velocities")  # Blender's, Alembic's
        if attribute is not None and attribute.domain == "POINT" and attribute.data_type == "FLOAT_VECTOR":
            v = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
            attribute.data.foreach_get("vector", v)
            self.velocity = v.reshape(-1, 3)[vertex_of_loop[loops]].astype(np.float64) @ m[:3, :3].T


def _instance_key(instance):
    obj = instance.object
    name = (obj.original or obj).name_full
    if instance.is_instance:
        return (name, tuple(instance.persistent_id), instance.parent.original.name_full if instance.parent else "")
    return (name,)


def snapshot(depsgraph, scene):
    """The mesh instances and the camera at the depsgraph's current time."""
    poses = {}
    for instance in depsgraph.object_instances:
        obj = instance.object
        if obj.type not in {"MESH", "CURVE", "SURFACE", "FONT", "META"} or not instance.show_self:
            continue
        if obj.hide_render:
            continue
        key = _instance_key(instance)
        matrix = [list(row) for row in instance.matrix_world]
        evaluated = obj.evaluated_get(depsgraph) if not instance.is_instance else obj
        mesh = evaluated.to_mesh()
        try:
            if mesh is None or len(mesh.polygons) == 0:
                continue
            pose = Pose(mesh, matrix)
            pose.name = (obj.original or obj).name
            pose.slots = [slot.material for slot in evaluated.material_slots]
            poses[key] = pose
        finally:
            evaluated.to_mesh_clear()
    if scene.camera is None:
        raise ValueError("the scene has no camera")
    camera = scene.camera.evaluated_get(depsgraph)
    return poses, CameraKey(camera.matrix_world, vertical_fov(camera, scene))


class Cancelled(Exception):
    """The user stopped the render while its keys were being evaluated."""


class Keys:
    """Snapshots at the key times, taken through the engine's frame_set. With `count` 0 the keys
    start at the shutter's ends and double (as the command line's --key-tolerance does) until
    every vertex half-way between two keys is within `tolerance` pixels of the straight line
    between them, up to 33. Then, as the command line does, where the animation's keyframes
    inside the shutter fall on an even grid of fewer pieces, the keys go on that grid once it is
    measured within the tolerance the same way: linear keyframes (a LINEAR morph, a zigzag
    path) are straight between them, kinks and all, where halving's grid misses the kinks."""

    def __init__(self, engine, depsgraph, scene, should_stop=lambda: False):
        self.engine, self.depsgraph, self.scene, self.should_stop = engine, depsgraph, scene, should_stop
        self.frame = scene.frame_current + scene.frame_subframe  # frame_set moves the scene's
        self.cache = {}
        self.on_keyframes = False

    def at(self, time):
        if time not in self.cache:
            if self.should_stop():
                raise Cancelled("the render was cancelled")
            whole = math.floor(time)
            self.engine.frame_set(int(whole), float(time - whole))
            self.cache[time] = snapshot(self.depsgraph, self.scene)
        return self.cache[time]

    def choose(self, count, tolerance, height):
        times, length = shutter_times(self.scene, self.frame, 2)
        if length == 0.0:
            pose = self.at(times[0])
            return [times[0], times[0]], [pose, pose]
        if count >= 2:
            times, _ = shutter_times(self.scene, self.frame, count)
            return times, [self.at(t) for t in times]
        keys = 2
        while True:
            times, _ = shutter_times(self.scene, self.frame, keys)
            snaps = [self.at(t) for t in times]
            if keys >= 33 or self._holds(times, snaps, tolerance, height):
                break
            keys = 2 * keys - 1
        pieces = keyframe_grid_pieces(keyframe_frames(self.scene), times[0], length)
        if keys > 2 and 0 < pieces and pieces + 1 < keys:
            grid, _ = shutter_times(self.scene, self.frame, pieces + 1)
            grid_snaps = [self.at(t) for t in grid]
            if self._holds(grid, grid_snaps, tolerance, height):
                self.on_keyframes = True
                return grid, grid_snaps
        return times, snaps

    def _holds(self, times, snaps, tolerance, height):
        """Whether every vertex half-way between two of the keys `times` lies within `tolerance`
        pixels of the straight line between them."""
        finer, _ = shutter_times(self.scene, self.frame, 2 * len(times) - 1)
        return all(self._deviation(snaps[i], snaps[i + 1], self.at(finer[2 * i + 1]), height) <= tolerance
                   for i in range(len(times) - 1))

    @staticmethod
    def _deviation(a, b, middle, height):
        """How far (pixels) the middle snapshot's vertices are from half-way between a and b, seen
        from the middle's camera; the camera's own path counts as its vertices' motion does."""
        (poses_a, cam_a), (poses_b, cam_b), (poses_m, cam_m) = a, b, middle
        worst = 0.0
        scale = 0.5 * height / math.tan(0.5 * cam_m.fov)
        for key, pm in poses_m.items():
            pa, pb = poses_a.get(key), poses_b.get(key)
            if pa is None or pb is None or pa.signature != pm.signature or pb.signature != pm.signature:
                continue
            # Each end seen from its own camera, as the render interpolates them.
            ca, cb, cm = cam_a.to_camera(pa.positions), cam_b.to_camera(pb.positions), cam_m.to_camera(pm.positions)
            depth = np.maximum(-cm[:, 2], 1e-6)
            error = np.linalg.norm((0.5 * (ca + cb) - cm)[:, :2], axis=1) / depth * scale
            worst = max(worst, float(error.max()) if len(error) else 0.0)
        return worst


def build(engine, depsgraph, settings, height):
    """(meshes, materials, textures, camera dict, frame cameras, Report) for streak.Scene.from_meshes.
    With the view layer's Vector pass, each mesh also has its frame_positions and the frame
    cameras are the camera at the frames before, at and after the shutter's (else None)."""
    scene = depsgraph.scene
    report = Report()
    keys = Keys(engine, depsgraph, scene, engine.should_stop)
    frame = scene.frame_current
    subframe = scene.frame_subframe
    frame_time = frame + subframe
    wants_vector = depsgraph.view_layer.use_pass_vector
    try:
        times, snaps = keys.choose(settings.keys, settings.key_tolerance, height)
        # The scene at the frame itself: which objects are drawn, and the pose of those whose
        # topology changes over the shutter (they stand there, or move from there by velocity).
        reference = keys.at(frame_time)[0]
        # The Vector pass's frames: the scene standing still a frame before and after (Blender's
        # vectors are to the previous frame and from the next, each seen by its own camera).
        frames = [keys.at(frame_time + d) for d in (-1.0, 0.0, 1.0)] if wants_vector else None
    finally:
        engine.frame_set(frame, subframe)
    report.keys = len(times)
    report.keys_on_keyframes = keys.on_keyframes
    cameras = [camera for _, camera in snaps]
    bake = not camera_follows_streak(cameras)
    report.camera_baked = bake
    fps = scene.render.fps / scene.render.fps_base
    materials = Materials(report)
    def baked(cams, points):
        """Corners relative to each key's (or frame's) camera, zoom included, as a still camera sees them."""
        zoom = [math.tan(0.5 * cameras[0].fov) / math.tan(0.5 * c.fov) for c in cams]
        return [c.to_camera(p) * np.array([z, z, 1.0]) for c, p, z in zip(cams, points, zoom)]

    meshes = []
    for key in reference:
        at_frame = reference[key]  # its triangles, uvs and slots: the same in every key, or held from the frame
        name = at_frame.name

        def held(seconds):
            """Where the frame's corners are `seconds` from it: moved by velocity, or standing still."""
            return at_frame.positions if at_frame.velocity is None else at_frame.positions + at_frame.velocity * seconds

        poses = [poses_k.get(key) for poses_k, _ in snaps]
        changes = any(p is None or p.signature != at_frame.signature for p in poses)
        if changes:
            report.topology_changes.append(name)
            # Stand still at the frame, or move along the velocity (units per second) from there.
            if at_frame.velocity is not None:
                report.moved_by_velocity.append(name)
            positions = [held((t - frame_time) / fps) for t in times]
            normals = [at_frame.normals for _ in times]
        else:
            positions = [p.positions for p in poses]
            normals = [p.normals for p in poses]
        frame_positions = None
        if frames is not None:
            # Where the same corners are at each frame: moved by velocity (units per second) from
            # the frame, or standing still, where the topology changes.
            frame_positions = []
            for d, (poses_f, _) in zip((-1.0, 0.0, 1.0), frames):
                p = poses_f.get(key)
                frame_positions.append(p.positions if p is not None and p.signature == at_frame.signature else held(d / fps))
        if bake:
            positions = baked(cameras, positions)
            normals = [n @ c.rotation for c, n in zip(cameras, normals)]
            if frame_positions is not None:
                frame_positions = baked([c for _, c in frames], frame_positions)
        slots = at_frame.slots
        for slot in np.unique(at_frame.material_index):
            tris = np.nonzero(at_frame.material_index == slot)[0]
            corners = (tris[:, None] * 3 + np.arange(3)[None, :]).reshape(-1)
            material = slots[slot] if 0 <= slot < len(slots) else None
            indices = np.arange(len(corners), dtype=np.int64).reshape(-1, 3)
            if at_frame.mirrored:
                indices = indices[:, ::-1]
            mesh = {"keys": np.stack([p[corners] for p in positions]).astype(np.float32),
                    "indices": indices,
                    "normals": np.stack([n[corners] for n in normals]).astype(np.float32),
                    "material": materials.index(material),
                    "name": name}
            if at_frame.uvs is not None:
                mesh["uvs"] = at_frame.uvs[corners]
            if frame_positions is not None:
                mesh["frame_positions"] = np.stack([p[corners] for p in frame_positions]).astype(np.float32)
            meshes.append(mesh)
            report.triangles += len(tris)
        report.objects += 1
    if not meshes:
        raise ValueError("the scene has no mesh to render")
    if bake:
        camera = {"position": [0.0, 0.0, 0.0], "target": [0.0, 0.0, -1.0], "up": [0.0, 1.0, 0.0]}
    else:
        camera = cameras[0].pose()
        end = cameras[-1].pose()
        camera["position_end"], camera["target_end"], camera["up_end"] = end["position"], end["target"], end["up"]
    camera["fov"] = math.degrees(cameras[0].fov)
    camera["znear"] = max(1e-6, float(scene.camera.data.clip_start))
    frame_cameras = None
    if frames is not None:
        if bake:
            frame_cameras = [{k: camera[k] for k in ("position", "target", "up", "fov", "znear")} for _ in frames]
        else:
            frame_cameras = [dict(c.pose(), fov=math.degrees(c.fov), znear=camera["znear"]) for _, c in frames]
    if scene.camera.data.shift_x != 0.0 or scene.camera.data.shift_y != 0.0:
        report.unsupported.append("the camera's shift is ignored")
    if scene.render.pixel_aspect_x != scene.render.pixel_aspect_y:
        report.unsupported.append("pixels are rendered square: the pixel aspect only shapes the field of view")
    if bake and depsgraph.view_layer.use_pass_normal:
        report.unsupported.append("the camera's path is carried by the geometry, so the Normal pass is in the camera's space")
    return meshes, materials.materials, materials.textures, camera, frame_cameras, report


def world_colour(scene):
    """The world's background colour (a Background node's Color times Strength, else its colour)."""
    world = scene.world
    if world is None:
        return [0.0, 0.0, 0.0]
    if world.use_nodes and world.node_tree is not None:
        for node in world.node_tree.nodes:
            if node.type == "BACKGROUND":
                strength = node.inputs["Strength"].default_value
                return [c * strength for c in node.inputs["Color"].default_value[:3]]
    return list(world.color[:3])
