"""What the Python module's tests share: where the build and the shared data are, the programs' own
output to compare against, and a PNG writer that does not go through svbrdf (PNG 1.2, 8-bit)."""
import os
import struct
import subprocess
import zlib

BINARY_DIR = os.environ.get('SVBRDF_BINARY_DIR', '')
SHARED_DIR = os.environ.get('SVBRDF_SHARED_DIR', '')


def program(name):
    return os.path.join(BINARY_DIR, name)


def run(args, stdin=''):
    """Runs a program; returns (exit status, stdout, stderr)."""
    p = subprocess.run(args, input=stdin, capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


def refusal(args, program_name, stdin=''):
    """The one line a program refuses `args` with, less its 'PROGRAM: ' prefix (exit 2 asserted)."""
    status, _, err = run(args, stdin)
    assert status == 2, (args, status, err)
    line = err.strip()
    assert '\n' not in line, err
    prefix = program_name + ': '
    assert line.startswith(prefix), line
    return line[len(prefix):]


def write_png(path, pixels):
    """pixels: uint8 numpy array (H, W) or (H, W, C), C in 1..4."""
    if pixels.ndim == 2:
        pixels = pixels[:, :, None]
    h, w, c = pixels.shape
    color_type = {1: 0, 2: 4, 3: 2, 4: 6}[c]
    raw = b''.join(b'\x00' + pixels[y].tobytes() for y in range(h))

    def chunk(kind, data):
        body = kind + data
        return struct.pack('>I', len(data)) + body + struct.pack('>I', zlib.crc32(body) & 0xffffffff)

    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n')
        f.write(chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, color_type, 0, 0, 0)))
        f.write(chunk(b'IDAT', zlib.compress(raw)))
        f.write(chunk(b'IEND', b''))
