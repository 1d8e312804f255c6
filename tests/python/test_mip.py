"""svbrdf.Material, build_mip and Mip against svbrdf-bake: a pyramid built from numpy arrays equals the one
the program builds from the same values written as PNG files; eval and compare answer as svbrdf-bake
eval and compare do; bad arguments raise the program's line."""
import json
import os
import tempfile
import unittest

import numpy as np

import svbrdf
from helpers import program, refusal, run, write_png


def textures(seed, size):
    rng = np.random.default_rng(seed)
    base = rng.integers(0, 256, size=(size, size, 3), dtype=np.uint8)
    mr = rng.integers(0, 256, size=(size, size, 3), dtype=np.uint8)
    # Normals tilted at most ~35°: a map's usual range.
    n = np.concatenate([rng.integers(70, 186, size=(size, size, 2)), rng.integers(220, 256, size=(size, size, 1))], axis=2)
    return base, mr, n.astype(np.uint8)


class MipAgainstProgram(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        cls.base, cls.mr, cls.n = textures(5, 8)
        cls.files = {k: os.path.join(d, k + '.png') for k in ('base', 'mr', 'n')}
        write_png(cls.files['base'], cls.base)
        write_png(cls.files['mr'], cls.mr)
        write_png(cls.files['n'], cls.n)
        cls.mip_file = os.path.join(d, 'm.exr')
        status, _, err = run([program('svbrdf-bake'), 'mip', '--base-color', cls.files['base'], '--metallic-roughness',
                              cls.files['mr'], '--normal', cls.files['n'], '--out', cls.mip_file])
        assert status == 0, err
        cls.material = svbrdf.Material(base_color=cls.base, metallic_roughness=cls.mr, normal=cls.n)
        cls.mip = svbrdf.build_mip(cls.material)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_material_from_arrays_equals_the_one_from_files(self):
        from_files = svbrdf.Material(base_color=self.files['base'], metallic_roughness=self.files['mr'],
                                     normal=self.files['n'])
        for name in ('base_color', 'metallic', 'roughness', 'normal'):
            np.testing.assert_array_equal(getattr(self.material, name), getattr(from_files, name), err_msg=name)
        # glTF's channels: roughness is G / 255, metallic B / 255.
        np.testing.assert_allclose(self.material.roughness, self.mr[:, :, 1] / 255, rtol=1e-6)
        np.testing.assert_allclose(self.material.metallic, self.mr[:, :, 2] / 255, rtol=1e-6)

    def test_pyramid_from_arrays_equals_the_programs_from_pngs(self):
        from_program = svbrdf.read_mip(self.mip_file)
        self.assertEqual(self.mip.levels, 4)
        self.assertEqual(from_program.levels, 4)
        for level in range(self.mip.levels):
            w, h = self.mip.extent(level)
            for mode in ('param', 'brdf'):
                for i in range(w):
                    for j in range(h):
                        np.testing.assert_array_equal(self.mip.table(mode, level, (i, j)),
                                                      from_program.table(mode, level, (i, j)),
                                                      err_msg=f'{mode} level {level} texel {i} {j}')

    def test_eval_answers_as_svbrdf_bake_eval(self):
        rng = np.random.default_rng(9)
        v = rng.normal(size=(40, 3))
        v[:, 2] = np.abs(v[:, 2])
        d = (v / np.linalg.norm(v, axis=1, keepdims=True)).astype(np.float32)
        wi, wo = d[:20], d[20:]
        lines = ''.join('%.9g %.9g %.9g %.9g %.9g %.9g\n' % (*a, *b) for a, b in zip(wi, wo))
        for mode in ('exact', 'param', 'vmf', 'brdf'):
            with self.subTest(mode=mode):
                status, out, err = run([program('svbrdf-bake'), 'eval', self.mip_file, '--level', '2', '--texel', '1', '0',
                                        '--mode', mode], lines)
                self.assertEqual(status, 0, err)
                expected = np.array([[float(x) for x in line.split()] for line in out.splitlines()])
                np.testing.assert_allclose(self.mip.eval(mode, 2, (1, 0), wi, wo), expected, rtol=2e-8, atol=1e-12)

    def test_compare_reports_what_svbrdf_bake_compare_reports(self):
        status, out, err = run([program('svbrdf-bake'), 'compare', self.mip_file, '--json'])
        self.assertEqual(status, 0, err)
        expected = json.loads(out)['levels']
        rows = self.mip.compare()
        self.assertEqual([r['level'] for r in rows], [r['level'] for r in expected])
        for row, want in zip(rows, expected):
            for mode, stats in want['modes'].items():
                for key, value in stats.items():
                    self.assertAlmostEqual(row['modes'][mode][key], value, delta=abs(value) * 1e-5 + 1e-9,
                                           msg=f'level {row["level"]} {mode} {key}')
        # The metric itself: a table against itself is no error, and e_rel of exact's and brdf's tables
        # at the last level is what compare reports for its one texel.
        exact = self.mip.table('exact', 3, (0, 0))
        self.assertEqual(svbrdf.e_rel(exact, exact), 0.0)
        self.assertAlmostEqual(svbrdf.e_rel(self.mip.table('brdf', 3, (0, 0)), exact), rows[-1]['modes']['brdf']['e_rel_max'])


class MipRefusals(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.mip_file = os.path.join(cls.tmp.name, 'm.exr')
        status, _, err = run([program('svbrdf-bake'), 'mip', '--base-color-factor', '0.5,0.5,0.5', '--out', cls.mip_file])
        assert status == 0, err
        cls.mip = svbrdf.read_mip(cls.mip_file)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_a_texel_outside_the_pyramid_raises_the_programs_line(self):
        line = refusal([program('svbrdf-bake'), 'eval', self.mip_file, '--level', '0', '--texel', '3', '0', '--mode', 'brdf'],
                       'svbrdf-bake', '0 0 1 0 0 1\n')
        with self.assertRaises(svbrdf.InputError) as caught:
            self.mip.eval('brdf', 0, (3, 0), (0, 0, 1), (0, 0, 1))
        self.assertEqual(str(caught.exception), line)

    def test_a_missing_or_corrupt_file_raises_the_programs_line(self):
        bad = os.path.join(self.tmp.name, 'bad.png')
        with open(bad, 'wb') as f:
            f.write(b'\x89PNG\r\n\x1a\nnot a png')
        for path in (bad, os.path.join(self.tmp.name, 'missing.png')):
            with self.subTest(path=path):
                line = refusal([program('svbrdf-bake'), 'mip', '--base-color', path, '--out',
                                os.path.join(self.tmp.name, 'o.exr')], 'svbrdf-bake')
                with self.assertRaises(svbrdf.InputError) as caught:
                    svbrdf.Material(base_color=path)
                self.assertEqual(str(caught.exception), line)

    def test_bad_arguments_are_refused(self):
        with self.assertRaisesRegex(svbrdf.InputError, r"^mode: unknown mode 'level0' \(exact, param, toksvig, vmf, brdf\)$"):
            self.mip.table('level0', 0, (0, 0))
        with self.assertRaisesRegex(svbrdf.InputError, r'^lobes: 0 is out of range \(1\.\.\d+\)$'):
            svbrdf.build_mip(svbrdf.Material(), lobes=0)
        with self.assertRaisesRegex(svbrdf.InputError, '^base_color: expected uint8, uint16 or float values$'):
            svbrdf.Material(base_color=np.zeros((2, 2, 3), dtype=np.int64))
        with self.assertRaisesRegex(svbrdf.InputError, r'^approx: expected a table of shape \(4225, 3\)$'):
            svbrdf.e_rel(np.zeros((3, 3)), self.mip.table('exact', 0, (0, 0)))


if __name__ == '__main__':
    unittest.main()
