#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Where the one-ring pipeline's clocks go: bench frames through a pipeline harness with
tb/harness/probe/ring_probe.sv bound into dm_pipeline (a measurement-only build of its own,
build/harness/pipeline-probe[-<params>]/), every frame compared with the model's f24 render.

Per frame it prints the bench's figures (clocks, iterations, clk/iter) and the probe's counts
over the clocks with a pixel inside (the bench's clock span): what the slot entering the ring's
first stage carries each clock (a new ray, a ray going round again, a finished ray held back by
a full result FIFO, or nothing, with the reason no ray took it), the fragment input's eligible
clocks by outcome, and the result side's waits.  --param NAME=VALUE (repeatable) builds
dm_pipeline with other parameter values (SLOTS, F0_DEPTH, ...) for what-if runs.  Exit status 1
when a pixel differs from the model.
"""
from __future__ import annotations

import dataclasses
import json
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from model import camera, scenes, shade, traverse  # noqa: E402
from model.cli import Parser, fail  # noqa: E402
from tb.harness import build as hbuild  # noqa: E402
from tb.harness import dm_pipeline  # noqa: E402

PROG = "ring_probe.py"
PROBE_SV = ROOT / "tb" / "harness" / "probe" / "ring_probe.sv"
PROBE_FILE = "ring_probe.txt"
#: ring_probe.sv's WINDOW: clocks before an empty slot in which the input's hold-ups count.
WINDOW = 64


def probe_spec(params: dict[str, int]) -> hbuild.HarnessSpec:
    """The one-ring pipeline harness with the probe bound in and ``params`` overriding
    dm_pipeline's defaults, built into a directory of its own."""
    base = dm_pipeline.pipeline_spec(1)
    tag = "-".join(f"{k}{v}" for k, v in sorted(params.items()))
    name = "pipeline-probe" + (f"-{tag}" if tag else "")
    return dataclasses.replace(base, name=name, params={**base.params, **params},
                               build_dir=hbuild.BUILD / name,
                               rtl_files=(*base.rtl_files, PROBE_SV))


def parse_params(items: list[str]) -> dict[str, int]:
    out: dict[str, int] = {}
    for it in items:
        name, sep, val = it.partition("=")
        if not sep or not name.isidentifier():
            fail(PROG, f"--param wants NAME=VALUE, got {it!r}")
        try:
            out[name] = int(val, 0)
        except ValueError:
            fail(PROG, f"--param {name}: not an integer: {val!r}")
    return out


def run_case(scene: str, view: str, a: Any, binary: Path) -> dict[str, Any]:
    frame, cam = dm_pipeline.scene_frame(scene, a.map, view, a.image, a.method, True)
    dm_pipeline.check_limits(frame)
    ref = shade.render(frame, cam, jobs=a.jobs)
    cwd = os.getcwd()
    with tempfile.TemporaryDirectory(prefix="ring_probe_") as tmp:
        os.chdir(tmp)
        try:
            img, st = dm_pipeline.render_rtl(frame, cam, frags=ref.frags, latency=a.latency,
                                             binary=binary)
        finally:
            os.chdir(cwd)
        counts = {}
        for line in (Path(tmp) / PROBE_FILE).read_text().splitlines():
            k, v = line.split()
            counts[k] = int(v)
    bad = dm_pipeline.compare(img.out, ref.out)
    return {"scene": scene, "view": view, "pixels": st["pixels"], "cycles": st["cycles"],
            "iterations": st["iterations"], "mismatches": int(len(bad)),
            "cycles_per_iteration": st["cycles"] / max(st["iterations"], 1),
            "height_lookup_misses": st["height_cache_misses"],
            "height_lookup_hits": st["height_cache_hits"], "probe": counts}


def report(r: dict[str, Any]) -> str:
    p = r["probe"]
    busy = max(p["busy"], 1)
    it = max(r["iterations"], 1)

    def per_iter(x: int) -> str:
        return f"{x:>9,} ({x / it:.4f}/iter)"

    empty = sum(p[k] for k in ("ring_empty_sf_bypass", "ring_empty_sf_busy",
                               "ring_empty_f0_wait", "ring_empty_vc", "ring_empty_front"))
    lines = [
        f"{r['scene']} {r['view']}: {r['pixels']:,} pixels, {r['cycles']:,} clocks, "
        f"{r['iterations']:,} iterations, clk/iter {r['cycles_per_iteration']:.4f}, "
        f"{r['mismatches']} pixels differ",
        f"  probe span (clocks with a pixel inside) {p['busy']:,}",
        f"  slot entering the ring: new {p['ring_new']:,}, round again {p['ring_recirc']:,}, "
        f"finished but held (result FIFO full) {per_iter(p['ring_blocked'])}, "
        f"empty {per_iter(empty)}",
        f"    empty because: setup FIFO head bypasses {p['ring_empty_sf_bypass']:,}; setup FIFO "
        f"empty and rays in setup {p['ring_empty_sf_busy']:,}; setup empty, rays in FIFO #0 "
        f"{p['ring_empty_f0_wait']:,}; rays only in view_calc {p['ring_empty_vc']:,}; "
        f"front end empty {p['ring_empty_front']:,}",
        f"    empty, the fragment input in the {WINDOW} clocks before held back by: free slot ids "
        f"{p['ring_empty_by_slots']:,}, FIFO #0 credits {p['ring_empty_by_credit']:,}, no "
        f"fragment {p['ring_empty_by_nofrag']:,}; by none (input at 1 per 4 clocks) "
        f"{p['ring_empty_by_rate']:,}",
        f"  height lookups that missed (a pass without an iteration) "
        f"{per_iter(r['height_lookup_misses'])}",
        f"  fragment input, eligible clocks {p['fe_elig']:,}: taken {p['fe_taken']:,}, no slot id "
        f"{p['fe_no_slot']:,}, no FIFO #0 credit {p['fe_no_credit']:,}, no fragment "
        f"{p['fe_no_frag']:,}",
        f"  result FIFO full {p['res_full']:,} clocks; a result waiting: hit spacing "
        f"{p['res_wait_spacing']:,}, request credit {p['res_wait_req']:,}, out credit "
        f"{p['res_wait_out']:,}, miss FIFO {p['res_wait_miss']:,}",
        f"  setup credit stalls {p['setup_credit_stall']:,}, FIFO #0 waiting for setup's phase "
        f"{p['f0_wait_phase']:,}",
        f"  mean occupancy: ring {p['sum_ring'] / busy:.2f}, slots in use "
        f"{p['sum_live'] / busy:.1f}, FIFO #0 {p['sum_f0'] / busy:.2f}, setup "
        f"{p['sum_su'] / busy:.2f}, setup FIFO {p['sum_sf'] / busy:.2f}",
    ]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--frames", default="bump:oblique,bump:grazing,rocks:oblique",
                    help="comma-separated scene:view pairs (default "
                         "bump:oblique,bump:grazing,rocks:oblique)")
    ap.add_argument("--method", default="park", help="exact method (default park)")
    ap.add_argument("--map", type=int, default=256, help="height map side (default 256)")
    ap.add_argument("--image", type=int, default=512, help="image side (default 512)")
    ap.add_argument("--latency", type=int, default=20, help="AXI read latency (default 20)")
    ap.add_argument("--jobs", type=int, default=1, help="model render processes (default 1)")
    ap.add_argument("--param", action="append", default=[],
                    help="NAME=VALUE: a dm_pipeline parameter for the probe build (repeatable)")
    ap.add_argument("--out", type=Path, default=None, help="JSON of the results")
    a = ap.parse_args(argv)
    frames = []
    for f in a.frames.split(","):
        s, sep, v = f.strip().partition(":")
        if not sep or s not in scenes.SCENES or v not in camera.VIEWS:
            fail(PROG, f"--frames: {f!r} is not scene:view")
        frames.append((s, v))
    if a.method not in traverse.EXACT_METHODS:
        fail(PROG, f"unknown exact method {a.method!r}")
    params = parse_params(a.param)
    t0 = time.time()
    binary = hbuild.build(probe_spec(params), "fast", quiet=False)
    rows = []
    for s, v in frames:
        r = run_case(s, v, a, binary)
        print(report(r), flush=True)
        rows.append(r)
    if a.out is not None:
        a.out.parent.mkdir(parents=True, exist_ok=True)
        a.out.write_text(json.dumps({"params": params, "image": a.image, "map": a.map,
                                     "rows": rows}, indent=1) + "\n")
    bad = sum(r["mismatches"] for r in rows)
    print(f"{PROG}: {len(rows)} frames, {bad} pixels differ from the f24 model, "
          f"{time.time() - t0:.0f} s")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
