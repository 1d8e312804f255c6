"""svbrdf.Bsdf against svbrdf-brdf: the same model from the same name and parameters evaluates the same
float32 values, bit for bit, on random direction pairs; bad arguments raise the program's line."""
import unittest

import numpy as np

import svbrdf
from helpers import program, refusal, run

# Models with parameters as svbrdf-brdf's --param takes them, and as keywords.
MODELS = [
    ('gltf', {'base_color': (0.8, 0.4, 0.2), 'roughness': 0.35, 'metallic': 0.25}),
    ('lambert', {}),
    ('blinn-phong', {}),
    ('oren-nayar', {}),
    ('cook-torrance', {}),
    ('gltf-surface', {'clearcoat': 1, 'roughness': 0.6}),
]


def random_directions(rng, n):
    """Unit vectors on the sphere, both hemispheres (eval's below-horizon cases included), as float32."""
    v = rng.normal(size=(n, 3))
    return (v / np.linalg.norm(v, axis=1, keepdims=True)).astype(np.float32)


def param_args(params):
    args = []
    for k, v in params.items():
        text = ','.join(repr(float(x)) for x in v) if isinstance(v, tuple) else repr(v)
        args += ['--param', f'{k}={text}']
    return args


class BsdfAgainstProgram(unittest.TestCase):
    def setUp(self):
        rng = np.random.default_rng(20)
        self.wi = random_directions(rng, 200)
        self.wo = random_directions(rng, 200)
        # %.9g writes every float32 so that it reads back exactly: the program sees the same pairs.
        self.lines = ''.join('%.9g %.9g %.9g %.9g %.9g %.9g\n' % (*a, *b) for a, b in zip(self.wi, self.wo))

    def program_values(self, command, model, params):
        status, out, err = run([program('svbrdf-brdf'), command, model] + param_args(params), self.lines)
        self.assertEqual(status, 0, err)
        return np.array([[float(x) for x in line.split()] for line in out.splitlines()], dtype=np.float32)

    def test_eval_equals_the_program_bit_for_bit(self):
        for model, params in MODELS:
            with self.subTest(model=model):
                f = svbrdf.Bsdf(model, **params).eval(self.wi, self.wo)
                self.assertEqual(f.shape, (200, 3))
                self.assertEqual(f.dtype, np.float32)
                expected = self.program_values('eval', model, params)
                self.assertTrue(np.any(expected > 0))
                np.testing.assert_array_equal(f, expected)

    def test_pdf_equals_the_program_bit_for_bit(self):
        for model, params in MODELS:
            with self.subTest(model=model):
                d = svbrdf.Bsdf(model, **params).pdf(self.wi, self.wo)
                np.testing.assert_array_equal(d, self.program_values('pdf', model, params)[:, 0])

    def test_one_direction_pairs_with_many(self):
        b = svbrdf.Bsdf('gltf', roughness=0.5)
        one = b.eval(self.wi, self.wo[0])
        np.testing.assert_array_equal(one, b.eval(self.wi, np.repeat(self.wo[:1], len(self.wi), axis=0)))
        self.assertEqual(b.eval(self.wi[0], self.wo[0]).shape, (3,))

    def test_sample_equals_the_program_bit_for_bit(self):
        # The program samples for the wo and at the u of each stdin line (sample --stdin). u, written with
        # %.9g, reaches it as the same float32 values; wo it renormalizes in double precision
        # (direction_text.cpp), which may move a float32 unit vector by an ulp: the module is given the
        # direction the program samples for, computed as the program computes it.
        rng = np.random.default_rng(11)
        wo = random_directions(rng, 200)
        wo[:, 2] = np.abs(wo[:, 2])
        u = rng.random((200, 3), dtype=np.float32)
        lines = ''.join('%.9g %.9g %.9g %.9g %.9g %.9g\n' % (*a, *b) for a, b in zip(wo, u))
        read = np.array([[float('%.9g' % x) for x in a] for a in wo])
        program_wo = (read / np.sqrt(read[:, 0] * read[:, 0] + read[:, 1] * read[:, 1] + read[:, 2] * read[:, 2])[:, None])
        program_wo = program_wo.astype(np.float32)
        for model, params in MODELS + [('lambert', {'albedo': 0.2, 'impulses': ['mirror:0.4']})]:
            with self.subTest(model=model, params=params):
                params = dict(params)
                impulses = params.pop('impulses', [])
                args = [program('svbrdf-brdf'), 'sample', model, '--stdin'] + param_args(params)
                status, out, err = run(args + [a for i in impulses for a in ('--impulse', i)], lines)
                self.assertEqual(status, 0, err)
                rows = [line.split() for line in out.splitlines()]
                expected = np.array([[float(x) for x in r[:7]] for r in rows], dtype=np.float32)
                wi, pdf, weight, kind = svbrdf.Bsdf(model, impulses=impulses, **params).sample(program_wo, u)
                self.assertEqual([svbrdf.SAMPLE_KINDS[k] for k in kind], [r[7] for r in rows])
                self.assertGreater(np.count_nonzero(kind == 0), 20)
                np.testing.assert_array_equal(wi, expected[:, 0:3])
                np.testing.assert_array_equal(pdf, expected[:, 3])
                np.testing.assert_array_equal(weight, expected[:, 4:7])

    def test_sample_agrees_with_eval_and_pdf(self):
        # A finite sample's pdf is pdf(wi, wo) and its weight f·cos/pdf (bsdf.h), computed through the
        # module's own eval and pdf on the directions it returns.
        rng = np.random.default_rng(3)
        wo = random_directions(rng, 1000)
        wo[:, 2] = np.abs(wo[:, 2])
        u = rng.random((1000, 3), dtype=np.float32)
        b = svbrdf.Bsdf('gltf', roughness=0.4, metallic=0.5)
        wi, pdf, weight, kind = b.sample(wo, u)
        finite = kind == svbrdf.SAMPLE_KINDS.index('finite')
        self.assertGreater(finite.sum(), 700)
        np.testing.assert_allclose(pdf[finite], b.pdf(wi, wo)[finite], rtol=1e-4)
        expected = b.eval(wi, wo)[finite] * np.abs(wi[finite, 2:3]) / pdf[finite, None]
        np.testing.assert_allclose(weight[finite], expected, rtol=1e-4, atol=1e-7)


class BsdfRefusals(unittest.TestCase):
    def test_bad_model_and_parameters_raise_the_programs_line(self):
        cases = [('nope', {}, []), ('gltf', {'roughness': 2}, ['--param', 'roughness=2']),
                 ('gltf', {'shininess': 1}, ['--param', 'shininess=1']),
                 ('gltf', {'base_color': 'red'}, ['--param', 'base_color=red'])]
        for model, params, args in cases:
            with self.subTest(model=model, params=params):
                line = refusal([program('svbrdf-brdf'), 'eval', model] + args, 'svbrdf-brdf', '0 0 1 0 0 1\n')
                with self.assertRaises(svbrdf.InputError) as caught:
                    svbrdf.Bsdf(model, **params)
                self.assertEqual(str(caught.exception), line)
                self.assertIsInstance(caught.exception, ValueError)

    def test_arrays_of_the_wrong_shape_are_refused(self):
        b = svbrdf.Bsdf('lambert')
        with self.assertRaisesRegex(svbrdf.InputError, r'^wi: expected an array of shape \(N, 3\), got \(4, 2\)$'):
            b.eval(np.zeros((4, 2)), np.zeros((4, 3)))
        with self.assertRaisesRegex(svbrdf.InputError, '^eval: wi and wo must have the same shape'):
            b.eval(np.zeros((4, 3)), np.zeros((5, 3)))
        with self.assertRaisesRegex(svbrdf.InputError, '^u: expected an array of numbers'):
            b.sample(np.zeros((4, 3)), 'abc')


if __name__ == '__main__':
    unittest.main()
