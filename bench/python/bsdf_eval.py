#!/usr/bin/env python3
"""ns per eval through the Python module against the C++ benchmark, in one run.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/bsdf_eval.py --cpp build/bench/appearance/bench_appearance

For each model the C++ benchmark (bench/appearance/bsdf_bench.cpp) builds through the registry, it
times svbrdf.Bsdf(...).eval(wi, wo) over --pairs random direction pairs in one call (--repetitions
calls, the median), the arrays made before the clock starts, and first runs the C++ program as the
anchor (its medians of as many repetitions): eval/<label>, one call at a time cycling through 4096
pairs, and eval-batch/<label>, a C++ loop over 10^6 pairs into an array, as the module's eval loops.
The batch pays what any loop over a large batch pays and the 4096-pair cycle does not (36 bytes a
pair to and from memory; branches that cannot learn a repeating sequence): Python against the batch
is the binding's own cost. Both sides draw their directions alike (z uniform in [0.02, 1], the
azimuth uniform: both above the horizon), use the same parameters and one thread: the module's eval
runs its loop on the calling thread. Times are CPU times of the thread (Google Benchmark's cpu_time;
time.thread_time here), so other work on a shared machine weighs less; wall times are printed too.
"""
import argparse
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import time

import numpy as np

import svbrdf

# (the C++ benchmark's label, model, keyword parameters, impulses): its registry cases, as keywords.
# lafortune/2lobes is left out: its two `lobe` parameters cannot both be keywords of one call.
MODELS = [
    ('lambert', 'lambert', {}, ()),
    ('phong', 'phong', {}, ()),
    ('blinn-phong', 'blinn-phong', {}, ()),
    ('microfacet/ggx', 'microfacet', {}, ()),
    ('microfacet/beckmann', 'microfacet', {'distribution': 'beckmann'}, ()),
    ('microfacet/ggx-conductor', 'microfacet', {'fresnel': 'conductor'}, ()),
    ('cook-torrance', 'cook-torrance', {}, ()),
    ('oren-nayar', 'oren-nayar', {}, ()),
    ('sheen', 'sheen', {'color': '0.9,0.6,0.3', 'roughness': 0.5}, ()),
    ('gltf', 'gltf', {}, ()),
    ('mirror', 'mirror', {}, ()),
    ('dielectric', 'dielectric', {}, ()),
    ('conductor-mirror', 'conductor-mirror', {}, ()),
    ('lambert+mirror:0.4', 'lambert', {'albedo': 0.2}, ('mirror:0.4',)),
]


def directions(rng, n):
    z = 0.02 + 0.98 * rng.random(n)
    phi = 2 * math.pi * rng.random(n)
    r = np.sqrt(1 - z * z)
    return np.ascontiguousarray(np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1), dtype=np.float32)


def cpp_medians(program, labels, repetitions):
    """{(kind, label): (cpu ns, real ns) per pair}: the medians of the C++ benchmarks eval/<label> (one
    call, cycling through 4096 pairs) and eval-batch/<label> (a loop over 10^6 pairs into an array)."""
    pattern = '^eval(-batch)?/(' + '|'.join(l.replace('+', r'\+') for l in labels) + ')$'
    out = subprocess.run([program, '--benchmark_filter=' + pattern, '--benchmark_format=json',
                          f'--benchmark_repetitions={repetitions}', '--benchmark_report_aggregates_only=true'],
                         check=True, capture_output=True, text=True).stdout
    medians = {}
    for b in json.loads(out)['benchmarks']:
        if b.get('aggregate_name') == 'median':
            kind, label = b['run_name'].split('/', 1)
            per = {'ns': 1, 'us': 1e3, 'ms': 1e6, 's': 1e9}[b['time_unit']] / b.get('pairs', 1)
            medians[kind, label] = (b['cpu_time'] * per, b['real_time'] * per)
    missing = [f'{k}/{l}' for l in labels for k in ('eval', 'eval-batch') if (k, l) not in medians]
    if missing:
        sys.exit(f'bsdf_eval.py: {program} has no benchmark {", ".join(missing)}')
    return medians


def python_medians(bsdf, wi, wo, repetitions, calls=1):
    """(cpu ns, real ns) per pair: the medians over `repetitions` of `calls` calls of eval on every pair."""
    bsdf.eval(wi[:1000], wo[:1000])  # the first call's one-time costs (page faults of the code) out of the timing
    cpu, real = [], []
    for _ in range(repetitions):
        t0, c0 = time.perf_counter_ns(), time.thread_time_ns()
        for _ in range(calls):
            f = bsdf.eval(wi, wo)
        c1, t1 = time.thread_time_ns(), time.perf_counter_ns()
        cpu.append((c1 - c0) / (calls * len(wi)))
        real.append((t1 - t0) / (calls * len(wi)))
        del f
    return statistics.median(cpu), statistics.median(real)


def cpu_model():
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                if line.startswith('model name'):
                    return line.split(':', 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or 'unknown'


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--cpp', required=True, help='the C++ benchmark program (build/bench/appearance/bench_appearance)')
    parser.add_argument('--pairs', type=int, default=1_000_000, help='direction pairs per eval call (default 10^6)')
    parser.add_argument('--repetitions', type=int, default=5, help='calls per model; the median is reported (default 5)')
    args = parser.parse_args()

    labels = [m[0] for m in MODELS]
    cpp = cpp_medians(args.cpp, labels, args.repetitions)
    rng = np.random.default_rng(42)
    wi, wo = directions(rng, args.pairs), directions(rng, args.pairs)
    print(f'# {cpu_model()}, {len(os.sched_getaffinity(0))} CPUs available; '
          f'{args.pairs} pairs per call, median of {args.repetitions}')
    print(f'{"model":26} {"C++ eval":>9} {"C++ batch":>10} {"Python":>8} {"/ batch":>8} {"/ eval":>7}'
          '   (wall: C++ batch, Python, ratio)')
    batch_ratios, eval_ratios = [], []
    for label, model, params, impulses in MODELS:
        bsdf = svbrdf.Bsdf(model, impulses=impulses, **params)
        py_cpu, py_real = python_medians(bsdf, wi, wo, args.repetitions)
        cpp_eval, _ = cpp['eval', label]
        cpp_batch, cpp_batch_real = cpp['eval-batch', label]
        batch_ratios.append(py_cpu / cpp_batch)
        eval_ratios.append(py_cpu / cpp_eval)
        print(f'{label:26} {cpp_eval:9.2f} {cpp_batch:10.2f} {py_cpu:8.2f} {py_cpu / cpp_batch:8.2f} '
              f'{py_cpu / cpp_eval:7.2f}   ({cpp_batch_real:.2f}, {py_real:.2f}, {py_real / cpp_batch_real:.2f})')
    print(f'Python / C++ batch: median {statistics.median(batch_ratios):.2f}, largest {max(batch_ratios):.2f}; '
          f'Python / C++ eval: median {statistics.median(eval_ratios):.2f}, largest {max(eval_ratios):.2f} '
          '(target <= 1.5)')


if __name__ == '__main__':
    main()
