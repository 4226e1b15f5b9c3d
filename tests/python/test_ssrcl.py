"""The Python module against independent truth: the CLI's output on a bundled sample (bit for bit),
an analytic plane mirror, the library's typed errors and the CLI's settings record.

Run by ctest (python_module) with PYTHONPATH=build/python, SSRCL_CLI and SSRCL_SOURCE_DIR set.
"""
import copy
import filecmp
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

import ssrcl

SOURCE_DIR = os.environ["SSRCL_SOURCE_DIR"]
CLI = os.environ["SSRCL_CLI"]
sys.path.insert(0, os.path.join(SOURCE_DIR, "samples", "blender"))
import minexr  # noqa: E402  (the samples' pure-Python EXR reader)

GLOSSY = os.path.join(SOURCE_DIR, "samples", "blender", "glossy", "glossy.exr")
TINTED = os.path.join(SOURCE_DIR, "samples", "blender", "tinted_glossy", "tinted_glossy.exr")
ENV_DIR = os.path.join(SOURCE_DIR, "samples", "corpus", "environment")


def bits(array):
    return np.ascontiguousarray(array, dtype=np.float32).view(np.uint32)


def exr_channels(exr, names):
    """Channels of a minexr file as an HxWxC float32 array."""
    planes = [np.array(exr.channel(n), dtype=np.float32).reshape(exr.height, exr.width) for n in names]
    return np.stack(planes, axis=-1)


def string_attributes(exr, prefix):
    return {k: v[1].decode() for k, v in exr.attributes.items() if k.startswith(prefix) and v[0] == "string"}


def perspective(fovy_degrees, aspect, near, far):
    f = 1.0 / math.tan(math.radians(fovy_degrees) / 2)
    return np.array([[f / aspect, 0, 0, 0], [0, f, 0, 0],
                     [0, 0, (far + near) / (near - far), 2 * far * near / (near - far)], [0, 0, -1, 0]])


class PlaneMirror:
    """A mirror floor (y = 0) facing a wall (z = -WALL) whose colour is linear in its height, seen
    by a camera at (0, 1, 0) looking down -Z. Each floor pixel's reflected ray is traced here in
    double precision: the wall colour where it lands, and how far it travels."""
    W, H, WALL = 96, 64, 8.0

    @staticmethod
    def wall_color(y):
        return np.stack([0.2 + 0.1 * y, np.full_like(y, 0.5), 0.8 - 0.05 * y], axis=-1)

    def __init__(self, fovy=50.0, shift=0.0):
        """`shift` moves the frame up (> 0) or down in NDC units: an off-axis projection."""
        W, H = self.W, self.H
        self.projection = perspective(fovy, W / H, 0.1, 100.0)
        self.projection[1, 2] = shift
        view = np.eye(4)
        view[1, 3] = -1.0  # world -> camera: the camera sits at y = 1
        self.camera = ssrcl.Camera(view=view, projection=self.projection, width=W, height=H)
        xs, ys = np.meshgrid(np.arange(W) + 0.5, np.arange(H) + 0.5)
        # Camera-space (= world, up to the offset) direction through each pixel centre, z = -1.
        d = np.stack([(2 * xs / W - 1) / self.projection[0, 0], (1 - 2 * ys / H + shift) / self.projection[1, 1],
                      -np.ones_like(xs)], axis=-1)
        t_floor = np.where(d[..., 1] < 0, -1.0 / np.minimum(d[..., 1], -1e-12), np.inf)
        self.floor = t_floor < self.WALL
        depth = np.where(self.floor, t_floor, self.WALL)  # planar depth: d.z = -1
        wall_y = 1.0 + self.WALL * d[..., 1]
        self.color = np.where(self.floor[..., None], 0.05, self.wall_color(wall_y))
        self.depth = depth[..., None]
        self.normal = np.where(self.floor[..., None], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0])
        self.roughness = np.where(self.floor, 0.0, 1.0)[..., None]

        # The floor's mirror ray (d.x, -d.y, -1) from its hit point reaches the wall after
        # s = WALL - t_floor along z, at height -s * d.y.
        s = self.WALL - np.where(self.floor, t_floor, 0.0)
        hit_y = -s * d[..., 1]
        self.expected_color = self.wall_color(hit_y)
        self.expected_distance = s * np.linalg.norm(d, axis=-1)
        # Where the hit lands on screen (pixels), to keep clear of the screen-edge fade.
        self.hit_x, self.hit_y = s * d[..., 0], hit_y
        self.hit_px, self.hit_py = self.on_screen(self.projection)
        # A pixel of wall spans this much height: the colour's change across one pixel.
        self.wall_height_per_pixel = 2 * self.WALL / (self.projection[1, 1] * H)

    def on_screen(self, projection):
        """Pixel coordinates of the hits in a camera at this one's place with this projection."""
        return ((self.hit_x / self.WALL * projection[0, 0] + 1) * self.W / 2,
                (1 - (self.hit_y - 1.0) / self.WALL * projection[1, 1] + projection[1, 2]) * self.H / 2)

    def pipeline(self, settings):
        p = ssrcl.Pipeline(ssrcl.Device())
        # float64 arrays on purpose: converted on the way in.
        p.setImage("color", self.color)
        p.setImage("depth", self.depth)
        p.setImage("normal", self.normal)
        p.setImage("roughness", self.roughness)
        p.setCamera(self.camera)
        p.settings = settings
        return p

    def traced(self):
        """A pipeline that has traced the scene; only the floor gets rays (the wall's roughness 1 is
        above maxRoughness)."""
        p = self.pipeline(ssrcl.TraceSettings(maxRoughness=0.5))
        p.commit()
        p.execute()
        return p


class CliEquivalenceTest(unittest.TestCase):
    def test_trace_matches_cli_bit_for_bit(self):
        with tempfile.TemporaryDirectory() as tmp:
            cli_out = os.path.join(tmp, "cli.exr")
            subprocess.run([CLI, "trace", GLOSSY, "-o", cli_out, "--seed", "7", "--spp", "2", "--compression", "none"],
                           check=True)

            frame = ssrcl.loadFrame(GLOSSY)
            p = ssrcl.Pipeline(ssrcl.Device())
            p.setFrame(frame)
            p.settings = ssrcl.TraceSettings(seed=7, samplesPerPixel=2)
            p.commit()
            p.execute()
            rgba, distance = p.output("reflection"), p.output("distance")

            cli = minexr.ExrFile(cli_out)
            self.assertEqual(rgba.shape, (cli.height, cli.width, 4))
            self.assertEqual(distance.shape, (cli.height, cli.width, 1))
            self.assertGreater(np.count_nonzero(rgba[..., 3]), 1000)  # the sample reflects something
            np.testing.assert_array_equal(bits(rgba), bits(exr_channels(cli, ["R", "G", "B", "A"])))
            np.testing.assert_array_equal(bits(distance), bits(exr_channels(cli, ["distance"])))

            # Written with the CLI's options and record, the file is the CLI's byte for byte.
            record = string_attributes(cli, "ssrcl/")
            self.assertEqual(record["ssrcl/settings"], p.settings.json())
            py_out = os.path.join(tmp, "py.exr")
            ssrcl.writeReflectionExr(py_out, rgba, distance, compression="none", headerFrom=GLOSSY,
                                     windows=frame.windows, camera=frame.displayCamera, attributes=record)
            self.assertTrue(filecmp.cmp(py_out, cli_out, shallow=False))


    def test_threaded_exr_write_is_the_same_bytes(self):
        # Smooth, so ZIP shrinks every 16-line chunk (a chunk it cannot shrink is stored raw).
        y, x = np.mgrid[0:67, 0:45].astype(np.float32)
        rgba = np.stack([x / 45, y / 67, (x + y) / 112, np.ones_like(x)], axis=-1)
        distance = rgba[..., :1] * 10
        with tempfile.TemporaryDirectory() as tmp:
            paths = []
            for threads in (4, 0):
                ssrcl.setExrThreads(threads)
                paths.append(os.path.join(tmp, f"t{threads}.exr"))
                ssrcl.writeReflectionExr(paths[-1], rgba, distance, compression="zip")
            self.assertTrue(filecmp.cmp(paths[0], paths[1], shallow=False))
            np.testing.assert_array_equal(exr_channels(minexr.ExrFile(paths[0]), ["R", "G", "B", "A"]), rgba)


def cli_pass(tmp, args):
    """RGBA of `ssrcl trace` run with `args` (input and options)."""
    out = os.path.join(tmp, "cli.exr")
    subprocess.run([CLI, "trace", *args, "-o", out, "--compression", "none"], check=True)
    return exr_channels(minexr.ExrFile(out), ["R", "G", "B", "A"])


def python_pass(frame, settings, environment=None):
    p = ssrcl.Pipeline(ssrcl.Device())
    p.setFrame(frame)
    p.setEnvironment(environment)
    p.settings = settings
    p.commit()
    p.execute()
    return p.output("reflection")


class CliEquivalenceOfOptionsTest(unittest.TestCase):
    def test_back_face_pass_matches_cli_and_a_reused_pipeline_forgets_it(self):
        scene = os.path.join(SOURCE_DIR, "samples", "corpus", "thin_objects")
        with tempfile.TemporaryDirectory() as tmp:
            cli = cli_pass(tmp, [scene + ".exr", "--back-depth-file", scene + ".back.exr"])
        settings = ssrcl.TraceSettings()
        with_back = ssrcl.loadFrame(scene + ".exr", backDepthFile=scene + ".back.exr")
        without = ssrcl.loadFrame(scene + ".exr")
        np.testing.assert_array_equal(bits(python_pass(with_back, settings)), bits(cli))
        p = ssrcl.Pipeline(ssrcl.Device())
        p.settings = settings
        for frame in (with_back, without):  # a frame without the pass after one with it
            p.setFrame(frame)
            p.commit()
            p.execute()
        alone = python_pass(without, settings)
        np.testing.assert_array_equal(bits(p.output("reflection")), bits(alone))
        self.assertFalse(np.array_equal(bits(alone), bits(cli)))

    def test_environment_fill_matches_cli(self):
        shot, sky = os.path.join(ENV_DIR, "env_plaza.exr"), os.path.join(ENV_DIR, "sky.exr")
        with tempfile.TemporaryDirectory() as tmp:
            cli = cli_pass(tmp, [shot, "--seed", "3", "--spp", "1", "--environment", sky,
                                 "--environment-rotation", "30", "--environment-intensity", "0.5"])
        env = ssrcl.loadEnvironmentMap(sky)
        self.assertEqual(env.source, sky)
        self.assertEqual(env.level(0).shape[1], 2 * env.level(0).shape[0])
        settings = ssrcl.TraceSettings(seed=3, samplesPerPixel=1, environmentRotation=30, environmentIntensity=0.5)
        frame = ssrcl.loadFrame(shot)
        filled = python_pass(frame, settings, env)
        np.testing.assert_array_equal(bits(filled), bits(cli))
        # The fill adds the environment where the screen misses (A < 1) and leaves A alone.
        premultiplied = python_pass(frame, settings)
        np.testing.assert_array_equal(bits(filled[..., 3]), bits(premultiplied[..., 3]))
        misses = premultiplied[..., 3] < 0.5
        self.assertGreater(np.count_nonzero(misses), 1000)
        self.assertGreater(filled[misses, :3].mean(), premultiplied[misses, :3].mean() + 0.01)

    def test_glossy_pass_form_matches_cli(self):
        with tempfile.TemporaryDirectory() as tmp:
            cli = cli_pass(tmp, [TINTED, "--seed", "5", "--spp", "1", "--output-form", "glossy-pass"])
        frame = ssrcl.loadFrame(TINTED, outputForm="glossy-pass")
        incident = python_pass(frame, ssrcl.TraceSettings(seed=5, samplesPerPixel=1))
        glossy = ssrcl.applyGlossyPassForm(incident, frame)
        np.testing.assert_array_equal(bits(glossy), bits(cli))
        # Copper's F0 is below 1 and red-heavy: the form darkens, blue most.
        lit = incident[..., 3] > 0.5
        ratio = glossy[lit, :3].sum(axis=0) / incident[lit, :3].sum(axis=0)
        self.assertTrue(np.all(ratio < 1.0) and ratio[0] > ratio[2], ratio)

    def test_default_output_form_is_the_cli_default(self):
        # TINTED holds the base_color / metallic AOVs: `ssrcl trace` with no --output-form writes
        # the glossy-pass form, and loadFrame reads the passes it needs by default.
        self.assertEqual(ssrcl.defaultOutputForm(TINTED), "glossy-pass")
        self.assertEqual(ssrcl.defaultOutputForm(GLOSSY), "incident")
        self.assertEqual(ssrcl.defaultOutputForm(TINTED, renderer="arnold"), "incident")
        with tempfile.TemporaryDirectory() as tmp:
            cli = cli_pass(tmp, [TINTED, "--seed", "5", "--spp", "1"])
        frame = ssrcl.loadFrame(TINTED)
        self.assertEqual(frame.outputForm, "glossy-pass")  # the choice loadFrame made while reading
        self.assertEqual(ssrcl.loadFrame(GLOSSY).outputForm, "incident")
        self.assertEqual(ssrcl.loadFrame(TINTED, outputForm="incident").outputForm, "incident")
        glossy = ssrcl.applyGlossyPassForm(python_pass(frame, ssrcl.TraceSettings(seed=5, samplesPerPixel=1)), frame)
        np.testing.assert_array_equal(bits(glossy), bits(cli))

    def test_glossy_pass_form_needs_material_passes(self):
        frame = ssrcl.loadFrame(GLOSSY)  # read without the glossy-pass form: no material passes
        with self.assertRaises(ssrcl.InvalidArgumentError):
            ssrcl.applyGlossyPassForm(np.zeros((frame.color.shape[0], frame.color.shape[1], 4), np.float32), frame)


class AnalyticMirrorTest(unittest.TestCase):
    def test_plane_mirror_reflects_the_wall(self):
        scene = PlaneMirror()
        p = scene.traced()
        rgba = p.output("reflection")
        distance = p.output("distance")[..., 0]

        # Pixels clear of the edge fade (5% of 64 pixels), where both they and their hits lie.
        margin = 6
        xs, ys = np.meshgrid(np.arange(scene.W) + 0.5, np.arange(scene.H) + 0.5)
        inside = lambda x, y: (x > margin) & (x < scene.W - margin) & (y > margin) & (y < scene.H - margin)
        checked = scene.floor & inside(xs, ys) & inside(scene.hit_px, scene.hit_py)
        self.assertGreater(np.count_nonzero(checked), 500)
        np.testing.assert_allclose(rgba[checked, 3], 1.0, atol=1e-6)
        # A hit reads the colour of the pixel it lands in: within half a pixel of the exact height.
        half_pixel = 0.5 * np.array([0.1, 0.0, 0.05]) * scene.wall_height_per_pixel
        error = np.abs(rgba[checked, :3] - scene.expected_color[checked])
        self.assertTrue(np.all(error <= half_pixel + 1e-6), "worst colour error %s" % error.max(axis=0))
        # The hit is the ray's crossing of the wall's plane: exact up to float32 rounding.
        np.testing.assert_allclose(distance[checked], scene.expected_distance[checked], rtol=1e-5)
        # Wall pixels (above max roughness) reflect nothing.
        self.assertTrue(np.all(rgba[~scene.floor] == 0.0))


class ViewTest(unittest.TestCase):
    """Auxiliary views: a frame looking down (off-axis) misses the wall above its top edge, which the
    floor's nearest pixels reflect; a wider view from the same place shows it."""

    def test_a_view_supplies_the_reflection_the_frame_misses(self):
        scene, wide = PlaneMirror(shift=-0.6), PlaneMirror(fovy=100.0)
        alone = np.array(scene.traced().output("reflection"))
        p = scene.pipeline(ssrcl.TraceSettings(maxRoughness=0.5))
        p.setView(0, wide.camera, wide.color, wide.depth, wide.normal, wide.roughness, label="wide")
        self.assertEqual(p.viewCount(), 1)
        p.commit()
        p.execute()
        rgba, source = p.output("reflection"), p.output("view")

        # Floor pixels whose hit is above the frame (missed there) and well inside the wide view.
        margin = 6
        px, py = scene.on_screen(wide.projection)
        missed = scene.floor & (scene.hit_py < 0) & (px > margin) & (px < scene.W - margin) & (py > margin)
        self.assertGreater(np.count_nonzero(missed), 100)
        self.assertTrue(np.all(alone[missed, 3] == 0.0))
        np.testing.assert_allclose(rgba[missed, 3], 1.0, atol=1e-6)
        np.testing.assert_array_equal(source[missed, 0], 1.0)  # the first view
        np.testing.assert_array_equal(source[missed, 1], 1.0)  # all of A from views
        # The wide view's pixel of wall: within half of one of its pixels of the exact height, and a
        # tenth for the float32 reprojection into it (a hit on a pixel's border may take either).
        tolerance = 0.6 * np.array([0.1, 0.0, 0.05]) * wide.wall_height_per_pixel
        error = np.abs(rgba[missed, :3] - scene.expected_color[missed])
        self.assertTrue(np.all(error <= tolerance + 1e-6), "worst colour error %s" % error.max(axis=0))

        # Without its views the pipeline gives the single-frame pass again, bit for bit.
        p.clearViews()
        p.commit()
        p.execute()
        np.testing.assert_array_equal(bits(p.output("reflection")), bits(alone))

    def test_bad_view_is_named(self):
        scene, wide = PlaneMirror(), PlaneMirror(fovy=100.0)
        p = scene.pipeline(ssrcl.TraceSettings(maxRoughness=0.5))
        p.setView(0, wide.camera, wide.color, wide.depth[:10], wide.normal, label="wide.exr")
        with self.assertRaisesRegex(ssrcl.InvalidInputError, "wide.exr"):
            p.commit()
        with self.assertRaisesRegex(ssrcl.InvalidArgumentError, "view index 2"):
            p.setView(2, wide.camera, wide.color, wide.depth, wide.normal)


class TemporalBlendTest(unittest.TestCase):
    def test_two_takes_of_one_frame_average(self):
        """The same frame twice, its pass with different noise: every neighbour pixel reprojects
        onto itself and is accepted, so where the rays hit the blend is the takes' mean weighted
        1 : 1/2 (a frame one away in a window whose longer side is 1 weighs 1 - 1/2); a miss
        (distance 0) keeps its own take."""
        scene = PlaneMirror()
        rng = np.random.default_rng(7)
        takes = [rng.uniform(0.0, 1.0, (scene.H, scene.W, 4)).astype(np.float32) for _ in range(2)]
        distance = np.where(scene.floor, scene.expected_distance, 0.0).astype(np.float32)
        frames = [dict(reflection=t, distance=distance, depth=scene.depth[..., 0], normal=scene.normal,
                       roughness=np.full((scene.H, scene.W), 0.3), camera=scene.camera) for t in takes]
        blended = ssrcl.temporalBlend(frames, 0)
        hit = (distance > 0.0)[..., None]
        self.assertTrue(hit.any() and not hit.all())
        np.testing.assert_allclose(blended, np.where(hit, (takes[0] + 0.5 * takes[1]) / 1.5, takes[0]), atol=1e-6)
        for f in frames:  # mirror pixels keep their own pass
            f["roughness"] = np.zeros((scene.H, scene.W))
        np.testing.assert_array_equal(ssrcl.temporalBlend(frames, 1), takes[1])


class InputArrayTest(unittest.TestCase):
    """Inputs are read where they lie: float16, strided and float32 layouts give the same pass."""

    def trace(self, scene, **images):
        p = scene.pipeline(ssrcl.TraceSettings(maxRoughness=0.5))
        for name, image in images.items():
            p.setImage(name, image)
        p.commit()
        p.execute()
        return np.array(p.output("reflection"))

    def test_half_and_strided_inputs_equal_packed_float32(self):
        scene = PlaneMirror()
        color16 = scene.color.astype(np.float16)
        packed = self.trace(scene, color=np.ascontiguousarray(color16, dtype=np.float32))
        np.testing.assert_array_equal(bits(self.trace(scene, color=color16)), bits(packed))
        rgba = np.zeros(scene.color.shape[:2] + (4,), np.float32)  # colour as the RGB of an RGBA array
        rgba[..., :3] = color16
        np.testing.assert_array_equal(bits(self.trace(scene, color=rgba[..., :3])), bits(packed))
        flipped = np.ascontiguousarray(color16[::-1], dtype=np.float32)[::-1]  # negative row stride: copied
        np.testing.assert_array_equal(bits(self.trace(scene, color=flipped)), bits(packed))

    def test_inputs_are_read_at_execute_not_copied(self):
        scene = PlaneMirror()
        color = np.ascontiguousarray(scene.color, dtype=np.float32)
        p = scene.pipeline(ssrcl.TraceSettings(maxRoughness=0.5))
        p.setImage("color", color)
        p.commit()
        color *= 2.0  # after setImage, before execute: the pipeline reads these very pixels
        p.execute()
        doubled = self.trace(scene, color=np.ascontiguousarray(scene.color * 2.0, dtype=np.float32))
        np.testing.assert_array_equal(bits(p.output("reflection")), bits(doubled))


class OutputArrayTest(unittest.TestCase):
    def test_outputs_are_views_that_later_executes_leave_alone(self):
        scene = PlaneMirror()
        p = scene.traced()
        first = p.output("reflection")
        self.assertFalse(first.flags.owndata)  # views the pipeline's buffer
        self.assertFalse(first.flags.writeable)
        self.assertEqual(first.dtype, np.float32)
        kept = first.copy()

        p.setImage("color", scene.color * 2.0)
        p.commit()
        p.execute()
        second = p.output("reflection")
        np.testing.assert_array_equal(first, kept)  # the earlier result is still there, unchanged
        checked = scene.floor & (first[..., 3] == 1.0)
        np.testing.assert_allclose(second[checked, :3], 2.0 * first[checked, :3], rtol=1e-6)

        # execute() again without commit (same inputs): same output, the earlier view unchanged.
        p.execute()
        np.testing.assert_array_equal(p.output("reflection"), second)
        np.testing.assert_array_equal(first, kept)

    def test_new_images_of_the_committed_shape_need_no_commit(self):
        scene = PlaneMirror()
        p = scene.traced()
        first = p.output("reflection")  # a view held: execute() moves to a fresh pipeline
        kept = first.copy()
        p.setImage("color", scene.color * 2.0)
        p.execute()
        second = p.output("reflection")
        np.testing.assert_array_equal(first, kept)
        checked = scene.floor & (first[..., 3] == 1.0)
        self.assertGreater(np.count_nonzero(checked), 1000)
        np.testing.assert_allclose(second[checked, :3], 2.0 * first[checked, :3], rtol=1e-6)

        p.setImage("depth", scene.depth[:-1])  # another size: commit() first
        with self.assertRaisesRegex(ssrcl.InvalidOperationError, "'depth' changed from 96x64 with 1 channel to 96x63"):
            p.execute()

    def test_constant_roughness_is_optional(self):
        self.assertIsNone(ssrcl.TraceSettings().constantRoughness)
        scene = PlaneMirror()
        p = scene.pipeline(ssrcl.TraceSettings(constantRoughness=1.5))
        with self.assertRaisesRegex(ssrcl.InvalidArgumentError, "parameter roughness must be in"):
            p.commit()


class ErrorTest(unittest.TestCase):
    def test_unknown_preset(self):
        with self.assertRaises(ssrcl.InvalidArgumentError) as caught:
            ssrcl.qualityPreset("bogus")
        self.assertIn("bogus", str(caught.exception))
        self.assertIsInstance(caught.exception, ValueError)
        self.assertIsInstance(caught.exception, ssrcl.Error)
        self.assertEqual(caught.exception.code, "InvalidArgument")

    def test_bad_setting_names_the_parameter(self):
        p = PlaneMirror().pipeline(ssrcl.TraceSettings(samplesPerPixel=0))
        with self.assertRaisesRegex(ssrcl.InvalidArgumentError, "parameter spp"):
            p.commit()
        p.settings = ssrcl.TraceSettings(edgeFade=0.9)
        with self.assertRaisesRegex(ssrcl.InvalidArgumentError, "parameter edge-fade"):
            p.commit()

    def test_unknown_setting_is_a_type_error(self):
        with self.assertRaisesRegex(TypeError, "'samplesPerPixels'"):
            ssrcl.TraceSettings(samplesPerPixels=4)

    def test_missing_and_mismatched_images_name_the_image(self):
        scene = PlaneMirror()
        p = ssrcl.Pipeline(ssrcl.Device())
        p.setImage("color", scene.color)
        p.setImage("normal", scene.normal)
        p.setImage("roughness", scene.roughness)
        p.setCamera(scene.camera)
        with self.assertRaisesRegex(ssrcl.InvalidArgumentError, "'depth' not set"):
            p.commit()
        p.setImage("depth", scene.depth[:-1])
        with self.assertRaisesRegex(ssrcl.InvalidInputError, "'depth' is 96x63"):
            p.commit()
        with self.assertRaisesRegex(ssrcl.InvalidArgumentError, "'colour'"):
            p.setImage("colour", scene.color)
        with self.assertRaisesRegex(ssrcl.InvalidArgumentError, "'normal' must be an HxWxC"):
            p.setImage("normal", scene.normal[None])
        with self.assertRaisesRegex(ssrcl.InvalidOperationError, "before commit"):
            p.execute()

    def test_files(self):
        with tempfile.TemporaryDirectory() as tmp:
            missing = os.path.join(tmp, "missing.exr")
            with self.assertRaises(ssrcl.IoError) as caught:
                ssrcl.loadFrame(missing)
            self.assertIn(missing, str(caught.exception))
            self.assertIsInstance(caught.exception, OSError)

            camera = os.path.join(tmp, "small.camera.json")
            scene = PlaneMirror()
            ssrcl.saveCameraJson(camera, scene.camera)  # 96x64, the sample is not
            with self.assertRaisesRegex(ssrcl.InvalidInputError, "small.camera.json: camera is 96x64"):
                ssrcl.loadFrame(GLOSSY, camera=camera)
        with self.assertRaisesRegex(ssrcl.InvalidArgumentError, "camera view must be a 4x4"):
            ssrcl.Camera(view=np.eye(3), projection=scene.projection, width=96, height=64)

    def test_device_out_of_range(self):
        with self.assertRaises(ssrcl.NoDeviceError):
            ssrcl.Device(len(ssrcl.devices()) + 100)


class SettingsTest(unittest.TestCase):
    def test_defaults_are_the_library_and_cli_defaults(self):
        self.assertEqual(ssrcl.TraceSettings(), ssrcl.qualityPreset("medium"))
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "out.exr")
            subprocess.run([CLI, "trace", GLOSSY, "-o", out, "--quality", "high", "--spp", "1", "--compression",
                            "none", "--reuse-radius", "0"], check=True)
            recorded = string_attributes(minexr.ExrFile(out), "ssrcl/")["ssrcl/settings"]
        expected = ssrcl.qualityPreset("high")
        expected.samplesPerPixel = 1
        expected.reuseRadius = 0
        self.assertEqual(expected.json(), recorded)

    def test_every_setting_round_trips(self):
        import json
        defaults = json.loads(ssrcl.TraceSettings().json())
        # Every field the CLI records is an attribute; change each to a value float32 holds exactly.
        changed = {}
        for name, value in defaults.items():
            current = getattr(ssrcl.TraceSettings(), name)
            if isinstance(current, bool):
                changed[name] = not current
            elif isinstance(current, int):
                changed[name] = current + 1
            elif isinstance(current, float) or current is None:  # None: an unset optional number
                changed[name] = 0.375 if current != 0.375 else 0.25
            else:
                changed[name] = [v for v in type(current).__members__.values() if v != current][0]
        s = ssrcl.TraceSettings(**changed)
        for name, value in changed.items():
            self.assertEqual(getattr(s, name), value, name)
        self.assertNotEqual(s, ssrcl.TraceSettings())
        self.assertEqual(copy.copy(s), s)

        p = ssrcl.Pipeline(ssrcl.Device())
        p.settings = s
        self.assertEqual(p.settings, s)
        p.settings.seed = 12345  # in place, as settings() is in C++
        self.assertEqual(p.settings.seed, 12345)

    def test_presets(self):
        self.assertEqual(ssrcl.qualityPreset("reference").tracer, ssrcl.Tracer.Linear)
        self.assertTrue(ssrcl.qualityPreset("high").denoise)
        self.assertEqual(ssrcl.qualityPreset("draft").traceStride, 2)


class DeviceTest(unittest.TestCase):
    def test_devices_match_the_cli_listing(self):
        devices = ssrcl.devices()
        self.assertGreater(len(devices), 0)
        listing = subprocess.run([CLI, "devices"], check=True, capture_output=True, text=True).stdout
        for d in devices:
            self.assertIn(d.name, listing)
            self.assertEqual(ssrcl.Device(d.index).info.name, d.name)
        self.assertEqual(ssrcl.Device("cpu").info.isGpu, False)


if __name__ == "__main__":
    unittest.main()
