#!/usr/bin/env python3
"""stamp.py T0 < LOG > STAMPED: prefixes each line read with the seconds since T0 (epoch seconds,
as `date +%s.%N` gives them) at which it arrived, so that bench/cycles/run can time the phases that
svbrdf-render and Blender announce on their output. A carriage return ends a line too."""
import sys
import time

t0 = float(sys.argv[1])
out = sys.stdout
buf = b""
while True:
    chunk = sys.stdin.buffer.raw.read(65536)
    if not chunk:
        break
    now = time.time() - t0
    buf += chunk.replace(b"\r", b"\n")
    *lines, buf = buf.split(b"\n")
    for line in lines:
        out.write(f"{now:.3f} {line.decode('utf-8', 'replace')}\n")
    out.flush()
if buf:
    out.write(f"{time.time() - t0:.3f} {buf.decode('utf-8', 'replace')}\n")
