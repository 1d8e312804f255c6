"""The module as `cmake --install` places it: installed into a scratch prefix, it imports with only
prefix/lib/pythonX.Y/site-packages on the path (not the build's python/), finds the project's shared
libraries from there (its RPATH), and evaluates: Lambert's f is albedo / pi."""
import glob
import os
import subprocess
import sys
import tempfile
import unittest

from helpers import BINARY_DIR

CMAKE = os.environ.get('SVBRDF_CMAKE', 'cmake')
SITE = os.path.join('lib', f'python{sys.version_info.major}.{sys.version_info.minor}', 'site-packages')

# Run by the installed module's interpreter with a clean environment: prints where svbrdf came from
# and f for one pair of directions.
CHILD = '''
import numpy as np, svbrdf
print(svbrdf.__file__)
f = svbrdf.Bsdf('lambert', albedo=(0.25, 0.5, 0.75)).eval(np.array([0.0, 0.6, 0.8]), np.array([0.0, 0.0, 1.0]))
print(' '.join(repr(float(x)) for x in f))
'''


class InstalledModule(unittest.TestCase):
    def test_the_installed_module_imports_from_the_prefix_alone(self):
        if not glob.glob(os.path.join(BINARY_DIR, 'python', 'svbrdf*.so')):
            self.skipTest(f'{BINARY_DIR} has no Python module to install (configured with SVBRDF_BUILD_PYTHON off)')
        with tempfile.TemporaryDirectory() as prefix:
            p = subprocess.run([CMAKE, '--install', BINARY_DIR, '--prefix', prefix], capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            site = os.path.join(prefix, SITE)
            self.assertTrue(glob.glob(os.path.join(site, 'svbrdf*.so')), f'no svbrdf module installed in {site}')
            env = {k: v for k, v in os.environ.items() if not k.startswith('PYTHON')}
            env['PYTHONPATH'] = site
            p = subprocess.run([sys.executable, '-s', '-c', CHILD], env=env, cwd=prefix, capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)
            where, values = p.stdout.splitlines()
            self.assertEqual(os.path.dirname(where), site)
            f = [float(x) for x in values.split()]
            # float32 arithmetic: albedo / pi within a float's rounding.
            for got, albedo in zip(f, (0.25, 0.5, 0.75)):
                self.assertAlmostEqual(got, albedo / 3.141592653589793, delta=albedo * 1e-6)


if __name__ == '__main__':
    unittest.main()
