"""svbrdf.render against svbrdf-render: a small render of a sample model with the same options and seed is
the program's float EXR bit for bit; bad options raise the program's line."""
import os
import signal
import tempfile
import threading
import time
import unittest

import numpy as np

import svbrdf
from helpers import SHARED_DIR, program, refusal, run

SCENE = os.path.join(SHARED_DIR, 'data', 'gltf-samples', 'BoxTextured', 'glTF', 'BoxTextured.gltf')
OPTIONS = ['--spp', '4', '--res', '24x16', '--seed', '7', '--max-depth', '3']


@unittest.skipUnless(os.path.exists(SCENE), f'{SCENE} is not here (../shared/data)')
class RenderAgainstProgram(unittest.TestCase):
    def test_render_equals_the_programs_exr(self):
        for filter_name in ('brdf', 'param'):
            with self.subTest(filter=filter_name), tempfile.TemporaryDirectory() as d:
                exr = os.path.join(d, 'box.exr')
                status, _, err = run([program('svbrdf-render'), SCENE, '--float', '--quiet', '--filter', filter_name,
                                      '--out', exr] + OPTIONS)
                self.assertEqual(status, 0, err)
                expected = svbrdf.read_image(exr)
                image = svbrdf.render(SCENE, spp=4, res='24x16', seed=7, max_depth=3, filter=filter_name)
                self.assertEqual(image.shape, (16, 24, 4))
                self.assertEqual(image.dtype, np.float32)
                self.assertGreater(image[:, :, :3].max(), 0)
                np.testing.assert_array_equal(image, expected)
                # Another seed is another image: the comparison can see a difference.
                self.assertFalse(np.array_equal(svbrdf.render(SCENE, spp=4, res='24x16', seed=8, max_depth=3,
                                                              filter=filter_name), expected))

    def test_aovs_come_back_as_layers(self):
        layers = svbrdf.render(SCENE, spp=1, res='8x8', aov=True, filter='param')
        self.assertEqual(sorted(layers), ['albedo', 'depth', 'mip_level', 'normal', 'rgba'])
        self.assertEqual(layers['normal'].shape, (8, 8, 3))
        self.assertEqual(layers['depth'].shape, (8, 8, 1))

    def test_ctrl_c_stops_the_render_and_raises_keyboard_interrupt(self):
        # A render of more samples than it can take within its time limit, 20 s, unless the SIGINT sent
        # 0.5 s in stops it. A KeyboardInterrupt within 10 s is one render() raised itself, not one
        # Python raised once the render had returned at its limit; 10 s is 20 times the expected delay,
        # for a loaded machine.
        small = {'spp': 1, 'res': '8x8', 'seed': 3, 'filter': 'param'}
        before = svbrdf.render(SCENE, **small)
        previous = signal.signal(signal.SIGINT, signal.default_int_handler)
        timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
        try:
            start = time.monotonic()
            timer.start()
            with self.assertRaises(KeyboardInterrupt):
                svbrdf.render(SCENE, spp=1 << 30, res='16x16', time_limit=20, threads=1, filter='param')
            self.assertLess(time.monotonic() - start, 10)
        finally:
            timer.cancel()
            signal.signal(signal.SIGINT, previous)
        # The module is as before: the same render gives the same image.
        np.testing.assert_array_equal(svbrdf.render(SCENE, **small), before)

    def test_bad_options_raise_the_programs_line(self):
        cases = [({'spp': 0}, ['--spp', '0']), ({'res': '10'}, ['--res', '10']),
                 ({'filter': 'box'}, ['--filter', 'box']), ({'bogus': 1}, ['--bogus', '1'])]
        for kwargs, args in cases:
            with self.subTest(kwargs=kwargs), tempfile.TemporaryDirectory() as d:
                line = refusal([program('svbrdf-render'), SCENE, '--quiet', '--out', os.path.join(d, 'x.exr')] + args,
                               'svbrdf-render')
                with self.assertRaises(svbrdf.InputError) as caught:
                    svbrdf.render(SCENE, **kwargs)
                self.assertEqual(line, str(caught.exception) + ('; see --help' if line.endswith('; see --help') else ''))

    def test_a_range_of_frames_is_refused_one_call_returns_one_image(self):
        with self.assertRaises(svbrdf.InputError) as caught:
            svbrdf.render(SCENE, frames='0-2')
        self.assertIn('frames=0-2: svbrdf.render returns one frame', str(caught.exception))
        # One frame is a render: this camera is still, which the program refuses too, with its line.
        with tempfile.TemporaryDirectory() as d:
            line = refusal([program('svbrdf-render'), SCENE, '--quiet', '--frames', '3', '--out', os.path.join(d, 'x.exr')],
                           'svbrdf-render')
        with self.assertRaises(svbrdf.InputError) as caught:
            svbrdf.render(SCENE, frames='3')
        self.assertEqual(str(caught.exception), line)

    def test_a_missing_scene_raises_the_programs_line(self):
        missing = os.path.join(tempfile.gettempdir(), 'svbrdf-no-such-scene.gltf')
        with tempfile.TemporaryDirectory() as d:
            line = refusal([program('svbrdf-render'), missing, '--quiet', '--out', os.path.join(d, 'x.exr')], 'svbrdf-render')
        with self.assertRaises(svbrdf.InputError) as caught:
            svbrdf.render(missing)
        self.assertEqual(str(caught.exception), line)


if __name__ == '__main__':
    unittest.main()
