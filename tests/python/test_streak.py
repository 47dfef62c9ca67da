"""The Python module as a user calls it: a built-in scene against the CLI's EXR, a scene from
numpy arrays against its closed form, and bad arrays raising one clear streak.Error."""
import json
import os
import struct
import subprocess
import tempfile
import unittest

import numpy as np

import streak

CLI = os.environ.get("STREAK_CLI", "build/streak")
CESIUM_MAN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "scenes", "CesiumMan", "glTF-Binary",
                          "CesiumMan.glb")


def sweeping_quad():
    """A white quad at depth 3 (90-degree camera, 16x4 image) whose right edge sweeps raster x
    from 2 to 14 over the shutter: pixel centre xc is covered for (14 - xc) / 12 of it."""
    depth, aspect = 3.0, 4.0

    def at(rx, ry):
        return [(2 * rx / 16 - 1) * depth * aspect, (1 - 2 * ry / 4) * depth, -depth]

    keys = np.array([[at(-20 + dx, -1), at(-20 + dx, 5), at(2 + dx, 5), at(2 + dx, -1)] for dx in (0, 12)], dtype=np.float32)
    indices = np.array([[0, 1, 2], [0, 2, 3]])
    camera = {"position": [0, 0, 0], "target": [0, 0, -1], "fov": 90}
    return keys, indices, camera


class RenderTest(unittest.TestCase):
    def test_builtin_equals_the_cli_exr(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cli.exr")
            subprocess.run([CLI, "render", "builtin:spin", "-m", "analytic", "--width", "64", "--height", "48", "-o", path], check=True)
            image = streak.render("builtin:spin", method="analytic", width=64, height=48)
            self.assertEqual(image.shape, (48, 64, 3))
            self.assertEqual(image.dtype, np.float32)
            self.assertTrue(np.array_equal(image, streak.read_image(path)))

    def test_region_is_the_slice_of_the_whole_image(self):
        whole = streak.render("builtin:spin", method="motion-path", width=64, height=48, aa=2)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "region.exr")
            subprocess.run([CLI, "render", "builtin:spin", "--width", "64", "--height", "48", "--aa", "2", "--region", "10,5,50,31", "-o", path],
                           check=True)
            region = streak.render("builtin:spin", method="motion-path", width=64, height=48, aa=2, region=(10, 5, 50, 31))
            self.assertEqual(region.shape, (26, 40, 3))
            self.assertTrue(np.array_equal(region, whole[5:31, 10:50]))
            self.assertTrue(np.array_equal(region, streak.read_image(path)))
        with self.assertRaises(streak.Error):
            streak.render("builtin:spin", width=64, height=48, region=(0, 0, 65, 48))

    def test_adaptive_equals_the_cli_exr_and_is_refused_at_aa_1(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "adaptive.exr")
            subprocess.run([CLI, "render", "builtin:spin", "-m", "analytic", "--width", "64", "--height", "48", "--aa", "4", "--adaptive", "0.02",
                            "-o", path], check=True)
            image, stats = streak.render("builtin:spin", method="analytic", width=64, height=48, aa=4, adaptive=0.02, stats=True)
            self.assertTrue(np.array_equal(image, streak.read_image(path)))
            self.assertGreater(stats["counters"]["adaptive_pixels_refined"], 0)
            full = streak.render("builtin:spin", method="analytic", width=64, height=48, aa=4)
            self.assertFalse(np.array_equal(image, full))
            # adaptive_full is the command line's --adaptive-full: at the threshold, every refined
            # pixel takes aa x aa, none the coarse 2 x 2 the default gives the mild steps.
            subprocess.run([CLI, "render", "builtin:spin", "-m", "analytic", "--width", "64", "--height", "48", "--aa", "4", "--adaptive", "0.02",
                            "--adaptive-full", "0.02", "-o", path], check=True)
            every, every_stats = streak.render("builtin:spin", method="analytic", width=64, height=48, aa=4, adaptive=0.02, adaptive_full=0.02,
                                               stats=True)
            self.assertTrue(np.array_equal(every, streak.read_image(path)))
            self.assertGreater(stats["counters"]["adaptive_pixels_refined_coarse"], 0)
            self.assertEqual(every_stats["counters"]["adaptive_pixels_refined_coarse"], 0)
            self.assertEqual(every_stats["counters"]["adaptive_pixels_refined"], stats["counters"]["adaptive_pixels_refined"])
            self.assertFalse(np.array_equal(every, image))
        with self.assertRaises(streak.Error):
            streak.render("builtin:spin", width=64, height=48, adaptive=0.02)

    def test_transparent_gives_the_sweeping_quads_coverage_as_alpha(self):
        # Over a grey background, alpha is the closed-form coverage and the colour is the white
        # quad's premultiplied by it: the background is gone. The CLI's EXR and write_image agree.
        keys, indices, camera = sweeping_quad()
        scene = streak.Scene.from_arrays(keys, indices, camera=camera, background=[0.5, 0.5, 0.5])
        image = streak.render(scene, method="analytic", width=16, height=4, unlit=True, transparent=True)
        self.assertEqual(image.shape, (4, 16, 4))
        coverage = np.clip((14 - (np.arange(16) + 0.5)) / 12, 0, 1)
        for row in image:
            np.testing.assert_allclose(row[:, 3], coverage, atol=1e-5)
            for c in range(3):
                np.testing.assert_allclose(row[:, c], coverage, atol=1e-5)
        opaque = streak.render(scene, method="analytic", width=16, height=4, unlit=True)
        self.assertEqual(opaque.shape, (4, 16, 3))
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "t.exr")
            subprocess.run([CLI, "render", "builtin:spin", "--width", "64", "--height", "48", "--transparent", "-o", path], check=True)
            spin = streak.render("builtin:spin", width=64, height=48, transparent=True)
            self.assertTrue(np.array_equal(spin, streak.read_image(path)))
            streak.write_image(image, os.path.join(tmp, "q.exr"))
            self.assertTrue(np.array_equal(image, streak.read_image(os.path.join(tmp, "q.exr"))))

    def test_passes_come_back_as_a_dict_and_mattes_read_by_name(self):
        # The sweeping quad's Cryptomatte coverage is its closed form; the EXR the CLI writes
        # gives the same matte by the object's name through cryptomatte_matte.
        keys, indices, camera = sweeping_quad()
        scene = streak.Scene.from_arrays(keys, indices, camera=camera)
        layers = streak.render(scene, method="analytic", width=16, height=4, unlit=True, passes=["depth", "object_id", "normal"])
        coverage = np.clip((14 - (np.arange(16) + 0.5)) / 12, 0, 1)
        self.assertEqual(layers["image"].shape, (4, 16, 3))
        for row in layers["CryptoObject00.g"]:
            np.testing.assert_allclose(row, coverage, atol=1e-5)
        np.testing.assert_allclose(layers["Z"][:, :13], 3.0, rtol=1e-5)
        # The quad faces the camera (+z): its normal pass is (0, 0, coverage).
        for row in layers["normal.Z"]:
            np.testing.assert_allclose(row, coverage, atol=1e-5)
        np.testing.assert_allclose(layers["normal.X"], 0.0, atol=1e-5)
        np.testing.assert_allclose(layers["normal.Y"], 0.0, atol=1e-5)
        self.assertTrue(np.all(layers["Z"][:, 14:] == 1e10))
        self.assertTrue(any(k.endswith("/manifest") for k in layers["metadata"]))
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "passes.exr")
            subprocess.run([CLI, "render", "builtin:crossing", "-m", "motion-path", "--width", "64", "--height", "48", "--passes", "object_id",
                            "-o", path], check=True)
            read = streak.read_layers(path)
            names = [n for n in __import__("json").loads(read["metadata"][next(k for k in read["metadata"] if k.endswith("/manifest"))])]
            self.assertGreaterEqual(len(names), 2)
            total = sum(streak.cryptomatte_matte(path, "CryptoObject", n) for n in names)
            rendered = streak.render("builtin:crossing", method="motion-path", width=64, height=48, transparent=True)
            np.testing.assert_allclose(total, rendered[..., 3], atol=1e-5)
            with self.assertRaises(streak.Error):
                streak.cryptomatte_matte(path, "CryptoAsset", names[0])
            rows = {r["pass"]: r for r in streak.compare_passes(path, path)}
            self.assertTrue(all(r["rms"] == 0 for r in rows.values()))
            self.assertTrue(all(f"CryptoObject {n}" in rows for n in names))

    def test_openimageio_reads_the_passes_and_their_cryptomatte_header(self):
        # OpenImageIO, a compositor's reader, reads the multi-layer EXR: its channels are
        # streak's, and the Cryptomatte header is the specification's (each type keyed by the
        # first 7 hex digits of its name's MurmurHash3, a manifest mapping names to the hashes
        # whose float conversions are the IDs in the channels; hashes computed here anew).
        try:
            import OpenImageIO as oiio
        except ImportError:
            self.skipTest("OpenImageIO's Python (python3-openimageio) is not installed")

        def murmur3_32(data, seed=0):
            c1, c2, h = 0xcc9e2d51, 0x1b873593, seed
            rotl = lambda x, r: ((x << r) | (x >> (32 - r))) & 0xffffffff  # noqa: E731
            tail = len(data) & ~3
            for i in range(0, tail, 4):
                k = rotl((int.from_bytes(data[i:i + 4], "little") * c1) & 0xffffffff, 15) * c2 & 0xffffffff
                h = (rotl(h ^ k, 13) * 5 + 0xe6546b64) & 0xffffffff
            k = int.from_bytes(data[tail:] + b"\0" * (4 - len(data[tail:])), "little") if len(data) & 3 else 0
            if k:
                h ^= rotl((k * c1) & 0xffffffff, 15) * c2 & 0xffffffff
            h ^= len(data)
            for shift, mul in ((16, 0x85ebca6b), (13, 0xc2b2ae35)):
                h = ((h ^ (h >> shift)) * mul) & 0xffffffff
            return h ^ (h >> 16)

        def id_of(name):
            """The float ID and the manifest's hex (of that float's bits) of a name."""
            h = murmur3_32(name.encode())
            if (h >> 23) & 255 in (0, 255):  # the specification's conversion: no denormal, inf or NaN
                h ^= 1 << 23
            return struct.unpack("<f", struct.pack("<I", h))[0], f"{h:08x}"

        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "passes.exr")
            subprocess.run([CLI, "render", "builtin:crossing", "-m", "motion-path", "--width", "64", "--height", "48", "--transparent",
                            "--passes", "depth,object_id,material_id", "-o", path], check=True)
            buf = oiio.ImageBuf(path)
            spec = buf.spec()
            names = list(spec.channelnames)
            pixels = buf.get_pixels(oiio.FLOAT)
            layers = streak.read_layers(path)
            for channel in ("Z", "Z.min", "CryptoObject00.r", "CryptoObject00.g", "CryptoMaterial01.a"):
                np.testing.assert_array_equal(pixels[..., names.index(channel)], layers[channel])
            alpha = pixels[..., names.index("A")]
            attributes = {a.name: a.value for a in spec.extra_attribs if a.name.startswith("cryptomatte/")}
            for type_name in ("CryptoObject", "CryptoMaterial"):
                key = f"{murmur3_32(type_name.encode()):08x}"[:7]
                self.assertEqual(attributes[f"cryptomatte/{key}/name"], type_name)
                self.assertEqual(attributes[f"cryptomatte/{key}/hash"], "MurmurHash3_32")
                self.assertEqual(attributes[f"cryptomatte/{key}/conversion"], "uint32_to_float32")
                manifest = json.loads(attributes[f"cryptomatte/{key}/manifest"])
                self.assertEqual(len(manifest), 2)
                mattes = np.zeros_like(alpha)
                ranks = sorted({n.split(".")[0] for n in names if n.startswith(type_name)})
                for name, hexid in manifest.items():
                    float_id, hex_id = id_of(name)
                    self.assertEqual(hexid, hex_id)
                    for rank in ranks:
                        for id_channel, coverage_channel in (("r", "g"), ("b", "a")):
                            ids = pixels[..., names.index(f"{rank}.{id_channel}")]
                            mattes += np.where(ids == np.float32(float_id), pixels[..., names.index(f"{rank}.{coverage_channel}")], 0.0)
                np.testing.assert_allclose(mattes, alpha, atol=1e-5)  # every coverage belongs to a manifest name
                self.assertGreater(alpha.max(), 0.99)

    def test_deep_comes_back_as_arrays_and_openimageio_flattens_it_to_the_image(self):
        # The sweeping quad over a transparent background: one deep sample a covered pixel, at
        # depth 3, whose alpha is its closed-form coverage. Written as a deep EXR, OpenImageIO
        # reads it and its flatten gives the render's RGBA.
        keys, indices, camera = sweeping_quad()
        scene = streak.Scene.from_arrays(keys, indices, camera=camera)
        out = streak.render(scene, method="analytic", width=16, height=4, unlit=True, transparent=True, deep=True)
        deep = out["deep"]
        self.assertEqual(deep["counts"].shape, (4, 16))
        self.assertEqual(deep["samples"].shape, (int(deep["counts"].sum()), 6))
        coverage = np.clip((14 - (np.arange(16) + 0.5)) / 12, 0, 1)
        np.testing.assert_array_equal(deep["counts"][0], (coverage > 0).astype(np.uint32))
        first_row = deep["samples"][: int(deep["counts"][0].sum())]
        np.testing.assert_allclose(first_row[:, 0], 3.0, rtol=1e-5)  # Z
        np.testing.assert_allclose(first_row[:, 5], coverage[coverage > 0], atol=1e-5)  # A
        try:
            import OpenImageIO as oiio
        except ImportError:
            self.skipTest("OpenImageIO's Python (python3-openimageio) is not installed")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "deep.exr")
            streak.write_deep_image(deep, path)
            back = streak.read_deep_image(path)
            np.testing.assert_array_equal(back["counts"], deep["counts"])
            np.testing.assert_array_equal(back["samples"], deep["samples"])
            buf = oiio.ImageBuf(path)
            self.assertTrue(buf.deep)
            self.assertEqual(list(buf.spec().channelnames), ["R", "G", "B", "A", "Z", "ZBack"])
            flat = oiio.ImageBufAlgo.flatten(buf).get_pixels(oiio.FLOAT)
            np.testing.assert_allclose(flat[..., :4], out["image"], atol=1e-5)
            # The CLI's deep file of a lit render over an opaque background (its sample behind
            # all): builtin:translucent, whose panes lie over each other, flattens to its image.
            image, deep_path = os.path.join(tmp, "t.exr"), os.path.join(tmp, "t_deep.exr")
            subprocess.run([CLI, "render", "builtin:translucent", "-m", "motion-path", "--width", "64", "--height", "48", "--aa", "2",
                            "--deep", deep_path, "-o", image], check=True)
            flat = oiio.ImageBufAlgo.flatten(oiio.ImageBuf(deep_path)).get_pixels(oiio.FLOAT)
            np.testing.assert_allclose(flat[..., :3], streak.read_image(image), atol=1e-5)
            np.testing.assert_allclose(flat[..., 3], 1.0, atol=1e-5)
        with self.assertRaises(streak.Error):
            streak.render(scene, method="post-filter", width=16, height=4, deep=True)
        with self.assertRaises(streak.Error):
            streak.write_deep_image({"counts": np.ones((2, 2), np.int32), "samples": np.zeros((3, 6), np.float32)}, "x.exr")
        with self.assertRaises(streak.Error):  # counts are whole numbers
            streak.write_deep_image({"counts": np.full((1, 2), 1.5), "samples": np.zeros((3, 6), np.float32)}, "x.exr")

    @unittest.skipUnless(os.path.exists(CESIUM_MAN), "the shared scenes are not beside the checkout")
    def test_gltf_motion_keys_and_bezier_pieces_equal_the_cli(self):
        # Scene.load takes the CLI's motion flags: chosen Bezier pieces render as the CLI's do.
        flags = ["--frame", "12", "--shutter", "6", "--motion-curve", "bezier", "--motion-curve-order", "3"]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cli.exr")
            subprocess.run([CLI, "render", CESIUM_MAN, "-m", "higher-order", "--width", "64", "--height", "48", *flags, "-o", path],
                           check=True)
            scene = streak.Scene.load(CESIUM_MAN, frame=12, shutter=6, width=64, height=48, motion_curve="bezier", motion_curve_order=3)
            image, stats = streak.render(scene, method="higher-order", width=64, height=48, stats=True)
            self.assertTrue(np.array_equal(image, streak.read_image(path)))
            self.assertEqual(stats["counters"]["motion_bezier_order"], 3)
            linear = streak.Scene.load(CESIUM_MAN, frame=12, shutter=6, width=64, height=48, motion_keys=5)
            _, stats = streak.render(linear, method="analytic", width=64, height=48, stats=True)
            self.assertEqual(stats["counters"]["motion_keys"], 5)
        with self.assertRaises(streak.Error):
            streak.Scene.load(CESIUM_MAN, motion_curve_order=3)  # an order without Bezier pieces applies to nothing

    @unittest.skipUnless(os.path.exists(CESIUM_MAN), "the shared scenes are not beside the checkout")
    def test_point_cache_reaches_the_loader(self):
        # A PC2 of CesiumMan's vertex count moves the mesh; one of another count is refused.
        scene = streak.Scene.load(CESIUM_MAN, width=64, height=48)
        with tempfile.TemporaryDirectory() as tmp:
            still = os.path.join(tmp, "still.pc2")
            with open(still, "wb") as f:  # every point at the origin, at frames 0 and 1
                f.write(b"POINTCACHE2\0" + struct.pack("<iiffi", 1, 3273, 0.0, 1.0, 2) + bytes(2 * 3273 * 12))
            collapsed = streak.Scene.load(CESIUM_MAN, width=64, height=48, point_cache=still, point_cache_space="world")
            # Every triangle collapsed to a point: skipped and counted as degenerate.
            self.assertEqual(collapsed.skipped_triangles, scene.num_triangles)
            wrong = os.path.join(tmp, "wrong.pc2")
            with open(wrong, "wb") as f:
                f.write(b"POINTCACHE2\0" + struct.pack("<iiffi", 1, 3, 0.0, 1.0, 1) + bytes(3 * 12))
            with self.assertRaisesRegex(streak.Error, "3 points"):
                streak.Scene.load(CESIUM_MAN, point_cache=wrong)

    def test_a_ply_sequence_loads_with_its_velocities(self):
        # Two frames of a triangle whose vertex count changes: the first moves along its
        # velocities, per frame or per second, as the CLI renders it.
        with tempfile.TemporaryDirectory() as tmp:
            for k, extra in ((0, ""), (1, "0 1 -5 1 0 0\n")):
                with open(os.path.join(tmp, "tri_%04d.ply" % k), "w") as f:
                    f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                            "property float vx\nproperty float vy\nproperty float vz\nelement face 1\n"
                            "property list uchar int vertex_indices\nend_header\n" % (3 + len(extra.splitlines())))
                    f.write("-1 -1 -5 1 0 0\n1 -1 -5 1 0 0\n0 1 -5 1 0 0\n" + extra + "3 0 1 2\n")
            spec = os.path.join(tmp, "tri_%04d.ply")
            cli = os.path.join(tmp, "cli.exr")
            subprocess.run([CLI, "render", spec, "--width", "32", "--height", "24", "--shutter", "1", "--velocity-unit", "frame", "-o", cli], check=True)
            scene = streak.Scene.load(spec, shutter=1, width=32, height=24, velocity_unit="frame")
            image = streak.render(scene, width=32, height=24)
            self.assertTrue(np.array_equal(image, streak.read_image(cli)))
            slow = streak.render(streak.Scene.load(spec, shutter=1, width=32, height=24), width=32, height=24)
            self.assertFalse(np.array_equal(image, slow))

    def test_arrays_give_the_closed_form_coverage(self):
        keys, indices, camera = sweeping_quad()
        scene = streak.Scene.from_arrays(keys=keys, indices=indices, camera=camera)
        self.assertEqual(scene.num_triangles, 2)
        image, stats = streak.render(scene, method="analytic", width=16, height=4, unlit=True, stats=True)
        expected = np.clip((14.0 - (np.arange(16) + 0.5)) / 12.0, 0.0, 1.0)
        np.testing.assert_allclose(image[:, :, 0], np.tile(expected, (4, 1)), atol=2e-4)
        self.assertEqual(stats["counters"]["triangles"], 2)
        self.assertEqual(stats["counters"]["memory_budget_mb"], 8192)
        # The memory budget reaches the method, and halving tiles leaves the image as it was.
        tight, tight_stats = streak.render(scene, method="analytic", width=16, height=4, unlit=True, stats=True, memory_budget_mb=1)
        self.assertEqual(tight_stats["counters"]["memory_budget_mb"], 1)
        self.assertTrue(np.array_equal(tight, image))
        # Textured with a uniform grey: the same ramp times the grey (linear light).
        grey = np.full((2, 2, 4), 0.5, dtype=np.float32)
        uvs = np.array([[0, 0], [0, 1], [1, 1], [1, 0]], dtype=np.float32)
        textured = streak.Scene.from_arrays(keys=keys, indices=indices, uvs=uvs, texture=grey, camera=camera)
        np.testing.assert_allclose(streak.render(textured, method="analytic", width=16, height=4, unlit=True)[1, :, 0], 0.5 * expected, atol=2e-4)
        # Under a triangle shutter curve: 1 - C((xc - 2) / 12), C(x) = 2 x^2 up to 1/2.
        curved = streak.render(scene.with_shutter("triangle"), method="analytic", width=16, height=4, unlit=True)
        self.assertAlmostEqual(float(curved[0, 3, 0]), 1 - 2 * (1.5 / 12) ** 2, delta=2e-4)

    def test_meshes_with_their_materials_names_and_textures(self):
        keys, indices, camera = sweeping_quad()
        # Two quads: the sweeping one in front, textured grey and named; a still red one behind,
        # filling the frame. Unlit: the ramp of grey over red.
        back = np.array([[[-99, -99, -5], [99, -99, -5], [99, 99, -5], [-99, 99, -5]]] * 2, dtype=np.float32)
        uvs = np.array([[0, 0], [0, 1], [1, 1], [1, 0]], dtype=np.float32)
        grey = np.full((2, 2, 4), 0.5, dtype=np.float32)
        scene = streak.Scene.from_meshes(
            [dict(keys=keys, indices=indices, uvs=uvs, material=1, name="Sweeper"), dict(keys=back, indices=indices, name="Wall")],
            materials=[dict(base_color=[1, 0, 0], double_sided=True, name="Red"), dict(texture=0, double_sided=True, name="Grey")],
            textures=[grey], camera=camera)
        self.assertEqual(scene.num_triangles, 4)
        out = streak.render(scene, method="analytic", width=16, height=4, unlit=True, passes=["object_id", "material_id"])
        expected = np.clip((14.0 - (np.arange(16) + 0.5)) / 12.0, 0.0, 1.0)
        np.testing.assert_allclose(out["image"][1, :, 0], 0.5 * expected + (1 - expected), atol=2e-4)
        np.testing.assert_allclose(out["image"][1, :, 1], 0.5 * expected, atol=2e-4)
        manifests = " ".join(v for k, v in out["metadata"].items() if k.endswith("manifest"))
        self.assertEqual(out["metadata"][f"cryptomatte/{streak.cryptomatte_key('CryptoObject')}/name"], "CryptoObject")
        for name in ("Sweeper", "Wall", "Red", "Grey"):
            self.assertIn(f'"{name}"', manifests)
        with self.assertRaisesRegex(streak.Error, r"meshes\[0\]: unknown key 'colour'"):
            streak.Scene.from_meshes([dict(keys=keys, indices=indices, colour=1)])
        with self.assertRaisesRegex(streak.Error, r"materials\[0\]: texture 3 does not exist|material 0: texture 3 does not exist"):
            streak.Scene.from_meshes([dict(keys=keys, indices=indices)], materials=[dict(texture=3)])
        with self.assertRaisesRegex(streak.Error, r"meshes\[1\]: indices: index 7 is out of range"):
            streak.Scene.from_meshes([dict(keys=keys, indices=indices), dict(keys=keys, indices=[[0, 1, 7]])])

    def test_progress_and_cancel(self):
        fractions = []
        image = streak.render("builtin:cubes?n=20", method="analytic", width=64, height=48, threads=1, progress=fractions.append)
        self.assertEqual(fractions[-1], 1.0)
        self.assertEqual(fractions, sorted(fractions))
        asked = []
        with self.assertRaises(streak.Cancelled):
            streak.render("builtin:cubes?n=20", method="analytic", width=64, height=48, threads=1, cancel=lambda: asked.append(1) or len(asked) > 2)
        self.assertEqual(len(asked), 3)
        self.assertTrue(issubclass(streak.Cancelled, streak.Error))
        # An exception in a callback stops the render and is raised as itself.
        with self.assertRaises(ZeroDivisionError):
            streak.render("builtin:cubes?n=20", width=64, height=48, progress=lambda f: 1 / 0)
        never = streak.render("builtin:cubes?n=20", method="analytic", width=64, height=48, cancel=lambda: False)
        self.assertTrue(np.array_equal(never, image))

    def test_bad_arrays_raise_one_clear_error(self):
        keys, indices, camera = sweeping_quad()
        nan = keys.copy()
        nan[1, 2, 0] = np.nan
        cases = {
            "keys must be a float array of shape (K, V, 3)": dict(keys=keys[:, :, :2], indices=indices),
            "finite": dict(keys=nan, indices=indices),
            "index 9 is out of range": dict(keys=keys, indices=np.array([[0, 1, 9]])),
            "index -1 is out of range": dict(keys=keys, indices=np.array([[0, -1, 2]])),
            "indices must be an integer array of shape (T, 3)": dict(keys=keys, indices=np.array([0, 1, 2])),
            "needs at least 2 key poses": dict(keys=keys[:1], indices=indices),
            "uvs must have one row per vertex": dict(keys=keys, indices=indices, uvs=np.zeros((3, 2))),
            "texture must be an array of shape": dict(keys=keys, indices=indices, texture=np.zeros((2, 2))),
        }
        for message, kwargs in cases.items():
            with self.subTest(message):
                with self.assertRaises(streak.Error) as caught:
                    streak.Scene.from_arrays(camera=camera, **kwargs)
                self.assertIn(message, str(caught.exception))
                self.assertNotIn("\n", str(caught.exception))
        with self.assertRaises(streak.Error):
            streak.render("builtin:nosuch")
        with self.assertRaises(streak.Error):
            streak.render("builtin:spin", method="nosuch")

    def test_methods_and_compare(self):
        names = [name for name, _ in streak.methods()]
        self.assertIn("analytic", names)
        self.assertIn("accumulation", names)
        a = streak.render("builtin:crossing", method="analytic", width=32, height=24)
        b = streak.render("builtin:crossing", method="accumulation", width=32, height=24, options={"samples": "256"})
        self.assertEqual(streak.compare(a, a)["psnr"], float("inf"))
        self.assertGreater(streak.compare(a, b)["psnr"], 40.0)
        # One of two pixels off by a whole level: 3.01 dB over the image, 0 dB over the foreground.
        black = np.zeros((1, 2, 3), dtype=np.float32)
        lit = black.copy()
        lit[0, 0] = 1.0
        c = streak.compare(black, lit)
        self.assertAlmostEqual(c["psnr"], 10.0 * np.log10(2.0), places=5)
        self.assertEqual(c["foreground_pixels"], 1)
        self.assertAlmostEqual(c["foreground_psnr"], 0.0, places=5)


if __name__ == "__main__":
    unittest.main()
