#!/usr/bin/env python3
"""Reads what bench/cycles/run leaves in its work folder and prints its figures.

    summarize.py sampling WORK NAME    the seconds run NAME spent sampling
    summarize.py table WORK            the markdown tables

For each run NAME, WORK holds NAME.meta ("renderer|scene|frame|spp|seed"), NAME.load (/proc/loadavg
at its start), NAME.time (/usr/bin/time's "%e %U %S": wall, user and system seconds) and NAME.log
(its output, each line prefixed by the seconds since the process started, from stamp.py).

svbrdf-render: sampling is the time its "N samples, M rays in X s" line gives; the first pixel is
that line's timestamp less X (everything before: reading the glTF, decoding images, building MIP
maps, the BVH, the emitters), with the stages it reports ("..., done in X s") as the breakdown.
Cycles: the first pixel is the timestamp of its "Sample 0/N" status line (Blender's start, the
import or the scene's construction, Cycles' synchronisation: images, shaders, BVH), sampling runs
from there to its "Finished" line; the breakdown is Blender's start-up (to "cycles_bench: started"
or, for scenes.py, to its first render status line), the import, and Cycles' synchronisation."""
import re
import sys
from pathlib import Path


def read_log(work, name):
    lines = []
    for raw in (work / f"{name}.log").read_text().splitlines():
        t, _, text = raw.partition(" ")
        lines.append((float(t), text))
    return lines


def first(lines, pattern):
    rx = re.compile(pattern)
    for t, text in lines:
        m = rx.search(text)
        if m:
            return t, m
    return None, None


def run_info(work, name):
    renderer, scene, frame, spp, seed = (work / f"{name}.meta").read_text().strip().split("|")
    wall, user, system = map(float, (work / f"{name}.time").read_text().split()[-3:])
    load = (work / f"{name}.load").read_text().split()[0]
    lines = read_log(work, name)
    info = {"renderer": renderer, "scene": scene, "frame": frame, "spp": int(spp), "seed": seed,
            "wall": wall, "cpu": user + system, "load": load}
    if renderer.startswith("svbrdf"):
        t, m = first(lines, r"svbrdf-render: (\d+) samples, (\d+) rays in ([\d.]+) s")
        sampling = float(m.group(3))
        info["sampling"] = sampling
        info["first_pixel"] = t - sampling
        stages = []
        for _, text in lines:
            s = re.search(r"svbrdf-render: (.*?)(?:, \d+/\d+)?, done in ([\d.]+) s", text)
            if s:
                what = s.group(1)
                what = "read + decode" if what.startswith("reading") else what.replace("building the ", "").replace(
                    " of the materials", "")
                stages.append(f"{what} {float(s.group(2)):.1f}")
        rest = info["first_pixel"] - sum(float(x.rsplit(" ", 1)[1]) for x in stages)
        info["breakdown"] = ", ".join(stages + [f"{'other' if stages else 'all'} {rest:.2f}"])
    else:
        t_sample0, _ = first(lines, r"\| Sample 0/\d+")
        t_done, _ = first(lines, r"\| Finished")
        t_started, _ = first(lines, r"^cycles_bench: started")
        t_loaded, _ = first(lines, r"^cycles_bench: loaded")
        t_status, _ = first(lines, r"^Fra:\d+ ")
        info["first_pixel"] = t_sample0
        info["sampling"] = t_done - t_sample0
        if t_started is not None:
            info["breakdown"] = (f"Blender start {t_started:.2f}, import {t_loaded - t_started:.2f}, "
                                 f"Cycles sync {t_sample0 - t_loaded:.2f}")
        else:
            info["breakdown"] = (f"Blender start + build + export {t_status:.2f}, "
                                 f"Cycles sync {t_sample0 - t_status:.2f}")
    return info


def relmse(work):
    out = {}
    for line in (work / "relmse.txt").read_text().splitlines():
        if line.startswith("relmse "):
            _, name, value = line.split()
            out[name] = float(value)
    return out


def table(work):
    rows = ["| run | renderer | scene | frame, spp | time to first pixel (s) | of which | sampling (s) | total wall (s) | CPU user+sys (s) | load at start |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for name in ("sv_helmet", "cy_helmet", "sv_panel", "cy_panel"):
        i = run_info(work, name)
        rows.append(f"| {name} | {i['renderer']} | {i['scene']} | {i['frame']}, {i['spp']} | {i['first_pixel']:.2f} | "
                    f"{i['breakdown']} | {i['sampling']:.2f} | {i['wall']:.2f} | {i['cpu']:.1f} | {i['load']} |")
    print("\n".join(rows))
    print()
    err = relmse(work)
    rows = ["| run | what | renderer | frame, spp (seed) | sampling (s) | total wall (s) | relMSE against its own reference | relMSE against the other's reference |",
            "|---|---|---|---|---|---|---|---|"]
    for name, what, own, other in (
            ("sv_ref", "reference", None, "sv_ref_vs_cy_ref"), ("cy_ref", "reference", None, "cy_ref_vs_sv_ref"),
            ("sv_64", "the time budget; equal spp, equal time", "sv_64_vs_sv_ref", "sv_64_vs_cy_ref"),
            ("cy_64", "equal spp", "cy_64_vs_cy_ref", "cy_64_vs_sv_ref"),
            ("cy_eq", "equal time", "cy_eq_vs_cy_ref", "cy_eq_vs_sv_ref")):
        i = run_info(work, name)
        own_text = "—" if own is None else f"{err[own]:.4g}"
        rows.append(f"| {name} | {what} | {i['renderer']} | {i['frame']}, {i['spp']} ({i['seed']}) | {i['sampling']:.2f} | "
                    f"{i['wall']:.2f} | {own_text} | {err[other]:.4g} |")
    print("\n".join(rows))


def main():
    work = Path(sys.argv[2])
    if sys.argv[1] == "sampling":
        print(f"{run_info(work, sys.argv[3])['sampling']:.4f}")
    elif sys.argv[1] == "table":
        table(work)
    else:
        sys.exit("usage: summarize.py sampling WORK NAME | table WORK")


main()
