#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""RTL traverse-unit performance (make bench): clocks per iteration, height-cache hit rate and
memory traffic per scene x view angle, through the Verilator harness (tb/harness/traverse_system.py).

For every scene and view: one ray per covered pixel of an --image x --image camera image over a
--size x --size map, in the order a tiled rasteriser emits fragments (--tile x --tile pixel
blocks; --tile 1 is raster order), traced by traverse_system (traverse unit + height cache + AXI
memory with --latency clocks of read latency).  Two runs per case:

  cold  the frame from an empty cache (the first frame of a view),
  warm  the same frame again with the cache as the first run left it (an animation's steady
        state; the harness checks that both runs return the same results).

--incoherent N replaces the camera images by N incoherent rays per scene (the view column reads
"incoherent"): start positions uniform over the map, azimuths uniform in [0, 2 pi), horizontal run
over the ray's whole depth (|du, dv|) uniform in [0, --size / 2] texels, in random order, like the
secondary rays of a ray tracer (no two neighbours in the stream share a tile or a direction);
--seed picks them.  --park measures the ring with its park queue (traverse_loop PARK = 1, a
harness build of its own; off by default); --park-depth, --park-wait and --park-max set its
knobs (traverse_loop PARK_DEPTH, PARK_WAIT, PARK_MAX), --mshrs the height cache's line fills in
flight (height_cache MSHRS; the AXI ID width grows to log2(MSHRS) + 2 where 4 is too narrow) and
--sets its sets (height_cache SETS; 4 ways of 32-byte lines, so 256 sets = 32 KiB): each setting
away from the defaults is a harness build of its own (build/traverse_<params>/).

Every RTL result is compared with the f24 engine (t, u, v, hit, invalid, iterations): a
difference fails the run (exit status 1).  Writes JSON (--out) and a markdown table (--md) and
prints the table; the README's performance table comes from it.

Definitions: clocks/iteration = clocks from the first ray in to the last result out / height reads
that returned data (the unit's iterations).  lookup hit rate = lookups that hit / all lookups
(a ray whose read missed retries on its next pass, so one miss costs several lookups; a redo of
locate's exit check, `relocations` in the JSON, reads once more too).  fills per
iteration = cache-line fills / iterations; 1 - that is the share of height reads served without
memory traffic (the figure comparable to the paper's "cache hit rate").
"""
from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
from model import camera, heightmap, scenes, traverse
from model.cli import Parser, Progress, fail
from tb.harness import sv_params, traverse_system
from model.rays import Rays

PROG = "bench_rtl.py"
#: Park et al. 2013, section 5.5 / Table 6: 4 units at 84 MHz, 7.5 Mpixels/s on Rocks (oblique).
PAPER_MHZ = 84.0
PAPER_UNITS = 4
PAPER_MPIX = 7.5
PAPER_CLOCKS_PER_PIXEL = PAPER_UNITS * PAPER_MHZ / PAPER_MPIX  # per unit: about 45


def compare(res: Any, ref: Any) -> int:
    """Rays whose RTL result differs from the f24 engine's (NaN == NaN)."""
    bad = np.zeros(len(ref.hit), dtype=bool)
    for f in ("t", "u", "v"):
        a, b = getattr(res, f), getattr(ref, f)
        bad |= ~((a == b) | (np.isnan(a) & np.isnan(b)))
    for f in ("hit", "invalid", "iterations"):
        bad |= getattr(res, f) != getattr(ref, f)
    return int(bad.sum())


def run_case(pyr: heightmap.Pyramid, rays: Any, method: str, latency: int,
             park: bool = False, params: dict[str, int] | None = None) -> dict[str, Any]:
    mst: dict[str, int] = {}
    ref = traverse.trace(pyr, rays, method, "f24", stats=mst)
    # (relocations: the ring's redos of locate's exit check, one height read more each)
    row: dict[str, Any] = {"rays": len(rays), "iterations": int(ref.iterations.sum()),
                           "relocations": mst.get("relocate", 0)}
    for warm in (False, True):
        res, st = traverse_system.trace_rtl(pyr, rays, method, latency=latency, warm=warm,
                                             park=park, params=params)
        key = "warm" if warm else "cold"
        row[key] = {k: st[k] for k in ("cycles", "iterations", "lookups", "height_cache_hits",
                                       "height_cache_misses", "mem_lines", "mem_bytes",
                                       "sim_clocks", "wall_seconds", "clocks_per_second")}
        row[key]["mismatches"] = compare(res, ref)
        row[key]["iterations_match"] = st["iterations"] == row["iterations"]
    return row


def incoherent_rays(rng: np.random.Generator, size: int, n: int) -> Any:
    """``n`` rays from uniform positions on a ``size`` x ``size`` map in uniform directions."""
    ang = rng.uniform(0.0, 2.0 * np.pi, n)
    run = rng.uniform(0.0, size / 2, n)
    return Rays(rng.uniform(0.0, size, n), rng.uniform(0.0, size, n),
                run * np.cos(ang), run * np.sin(ang))


def derived(row: dict[str, Any], key: str) -> dict[str, float]:
    r = row[key]
    it = max(r["iterations"], 1)
    return {"clk_per_iter": r["cycles"] / it,
            "clk_per_ray": r["cycles"] / max(row["rays"], 1),
            "lookup_hit": r["height_cache_hits"] / max(r["lookups"], 1),
            "served": 1.0 - r["mem_lines"] / it,
            "bytes_per_ray": r["mem_bytes"] / max(row["rays"], 1)}


def harness_params(a: Any) -> dict[str, int]:
    """The traverse_system parameters away from the harness's defaults that the options ask for
    (exits 2 on a value out of range or a park knob without --park)."""
    params: dict[str, int] = {}
    if a.mshrs is not None:
        if a.mshrs < 1 or a.mshrs > 64 or a.mshrs & (a.mshrs - 1):
            fail(PROG, f"--mshrs must be a power of two in 1 .. 64, got {a.mshrs}")
        params["MSHRS"] = a.mshrs
        params["AXI_ID_W"] = max(traverse_system.PARAMS["AXI_ID_W"],
                                 (a.mshrs - 1).bit_length() + 2)
    if a.sets is not None:
        if a.sets < 16 or a.sets > 4096 or a.sets & (a.sets - 1):
            fail(PROG, f"--sets must be a power of two in 16 .. 4096, got {a.sets}")
        params["SETS"] = a.sets
    # traverse_loop's ranges: ring + queue < 2^LOOP_BUSY_W (its busy_o), an 8-bit park age
    depth_max = ((1 << sv_params.value("traverse_pkg", "LOOP_BUSY_W")) - 1
                 - sv_params.value("traverse_pkg", "LOOP_DEPTH"))
    for opt, name, val, lo, hi in (("--park-depth", "PARK_DEPTH", a.park_depth, 1, depth_max),
                                   ("--park-wait", "PARK_WAIT", a.park_wait, 0, 255),
                                   ("--park-max", "PARK_MAX", a.park_max, 1, 1 << 16)):
        if val is None:
            continue
        if not a.park:
            fail(PROG, f"{opt} needs --park")
        if not lo <= val <= hi:
            fail(PROG, f"{opt} must be in {lo} .. {hi}, got {val}")
        params[name] = val
    return params


def main() -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default=",".join(scenes.SCENES))
    ap.add_argument("--angles", default=",".join(camera.VIEWS))
    ap.add_argument("--methods", default="park,park-xor")
    ap.add_argument("--size", type=int, default=256, help="map side in texels (default 256)")
    ap.add_argument("--image", type=int, default=256, help="camera image side (default 256)")
    ap.add_argument("--tile", type=int, default=8, help="fragment tile side (1: raster order)")
    ap.add_argument("--latency", type=int, default=20, help="AXI read latency in clocks")
    ap.add_argument("--incoherent", type=int, default=0, metavar="N",
                    help="N incoherent rays per scene instead of the camera views (see above)")
    ap.add_argument("--seed", type=int, default=1, help="random seed of --incoherent's rays")
    ap.add_argument("--park", action="store_true",
                    help="the ring with its park queue (traverse_loop PARK = 1; default off)")
    ap.add_argument("--mshrs", type=int, default=None, metavar="N",
                    help="height-cache MSHRs, line fills in flight (height_cache MSHRS; "
                         "default the harness's, 4)")
    ap.add_argument("--park-depth", type=int, default=None, metavar="N",
                    help="park queue entries (traverse_loop PARK_DEPTH, default 16; with --park)")
    ap.add_argument("--park-wait", type=int, default=None, metavar="N",
                    help="clocks a parked ray waits before it beats new rays to a free slot "
                         "(traverse_loop PARK_WAIT, default 16; with --park)")
    ap.add_argument("--park-max", type=int, default=None, metavar="N",
                    help="clocks the park queue's head waits before it takes any tail slot "
                         "(traverse_loop PARK_MAX, default 4 x the ring's stages; with --park)")
    ap.add_argument("--sets", type=int, default=None, metavar="N",
                    help="height-cache sets (height_cache SETS, 4 ways x 32 B each; default the "
                         "harness's, 256 = 32 KiB)")
    ap.add_argument("--out", type=Path, default=ROOT / "out" / "bench" / "rtl.json")
    ap.add_argument("--md", type=Path, default=ROOT / "out" / "bench" / "rtl.md")
    a = ap.parse_args()
    names = a.scenes.split(",")
    angles = ["incoherent"] if a.incoherent else a.angles.split(",")
    methods = a.methods.split(",")
    for what, got, valid in (("scene", names, scenes.SCENES),
                             ("angle", [] if a.incoherent else angles, camera.VIEWS),
                             ("method", methods, traverse.EXACT_METHODS)):
        bad = [x for x in got if x not in valid]
        if bad:
            fail(PROG, f"unknown {what} {bad[0]!r}; valid: {', '.join(valid)}")
    for what, val, lo in (("--size", a.size, 1), ("--image", a.image, 1), ("--tile", a.tile, 1),
                          ("--latency", a.latency, 1), ("--incoherent", a.incoherent, 0)):
        if val < lo:
            fail(PROG, f"{what} must be >= {lo}, got {val}")
    params = harness_params(a)
    try:
        # the variant trace_rtl runs: checked under RTL_ENGINE_CHECKED=1 (the test suite),
        # else fast (make bench)
        traverse_system.build(traverse_system.default_variant(), quiet=False, park=a.park,
                              params=params)
    except traverse_system.RtlEngineError as e:
        fail(PROG, str(e).splitlines()[0])
    rows: list[dict[str, Any]] = []
    total = len(names) * len(angles) * len(methods)
    prog = Progress(f"{PROG}: cases", total)
    rng = np.random.default_rng(a.seed)
    for name in names:
        sc = scenes.load_scene(name, a.size)
        pyr = heightmap.build(sc.heights)
        for angle in angles:
            if a.incoherent:
                rays = incoherent_rays(rng, a.size, a.incoherent)
            else:
                cam = camera.Camera.for_view(angle, a.size, a.size, a.image, a.image)
                rays = cam.tiled_rays(a.tile).rays
            for method in methods:
                row = {"scene": name, "angle": angle, "method": method,
                       **run_case(pyr, rays, method, a.latency, a.park, params)}
                row.update({f"{k}_{key}": v for key in ("cold", "warm")
                            for k, v in derived(row, key).items()})
                rows.append(row)
                prog.update(len(rows))
    mism = sum(r[k]["mismatches"] for r in rows for k in ("cold", "warm"))
    sim_clocks = sum(r[k]["sim_clocks"] for r in rows for k in ("cold", "warm"))
    sim_wall = sum(r[k]["wall_seconds"] for r in rows for k in ("cold", "warm"))

    def mean(k: str, sel: list[dict[str, Any]]) -> float:
        return float(np.mean([r[k] for r in sel])) if sel else float("nan")

    head = ("| scene | view | method | iter/ray | clk/iter cold | clk/iter warm | clk/ray warm "
            "| lookup hit cold | reads w/o fill cold | reads w/o fill warm | bytes/ray cold |")
    lines = [head, "|" + "---|" * 11]
    for r in rows:
        lines.append(f"| {r['scene']} | {r['angle']} | {r['method']} "
                     f"| {r['iterations'] / max(r['rays'], 1):.2f} "
                     f"| {r['clk_per_iter_cold']:.3f} | {r['clk_per_iter_warm']:.3f} "
                     f"| {r['clk_per_ray_warm']:.2f} | {100 * r['lookup_hit_cold']:.1f}% "
                     f"| {100 * r['served_cold']:.2f}% | {100 * r['served_warm']:.2f}% "
                     f"| {r['bytes_per_ray_cold']:.1f} |")
    summary = []
    for method in methods:
        for angle in angles:
            sel = [r for r in rows if r["method"] == method and r["angle"] == angle]
            cpr = mean("clk_per_ray_warm", sel)
            summary.append({
                "method": method, "angle": angle,
                "iter_per_ray": float(np.mean([r["iterations"] / max(r["rays"], 1) for r in sel])),
                "clk_per_iter_cold": mean("clk_per_iter_cold", sel),
                "clk_per_iter_warm": mean("clk_per_iter_warm", sel),
                "clk_per_ray_warm": cpr,
                "served_cold": mean("served_cold", sel),
                "mrays_per_s_at_84mhz": PAPER_MHZ / cpr if cpr > 0 else float("nan")})
    lines += ["", f"Mean over the {len(names)} scenes (per unit; the paper: about "
              f"{PAPER_CLOCKS_PER_PIXEL:.0f} clocks/pixel per unit, {PAPER_MPIX} Mpixels/s from "
              f"{PAPER_UNITS} units at {PAPER_MHZ:.0f} MHz on Rocks oblique):", "",
              "| method | view | iter/ray | clk/iter cold | clk/iter warm | clk/ray warm "
              "| reads w/o fill cold | Mrays/s per unit at 84 MHz |", "|" + "---|" * 8]
    for s in summary:
        lines.append(f"| {s['method']} | {s['angle']} | {s['iter_per_ray']:.2f} "
                     f"| {s['clk_per_iter_cold']:.3f} | {s['clk_per_iter_warm']:.3f} "
                     f"| {s['clk_per_ray_warm']:.2f} | {100 * s['served_cold']:.2f}% "
                     f"| {s['mrays_per_s_at_84mhz']:.2f} |")
    rays_what = (f"{a.incoherent} incoherent rays per scene (seed {a.seed})" if a.incoherent
                 else f"image {a.image}x{a.image}, {a.tile}x{a.tile} tiles")
    lines += ["", f"Map {a.size}x{a.size}, {rays_what}, "
              f"AXI latency {a.latency} clocks; RTL vs f24 engine: {mism} mismatching rays; "
              f"harness {sim_clocks:,} clocks in {sim_wall:.1f} s = "
              f"{sim_clocks / max(sim_wall, 1e-9) / 1e6:.2f} M clocks/s."]
    md = "\n".join(lines) + "\n"
    print(md)
    a.out.parent.mkdir(parents=True, exist_ok=True)
    a.md.parent.mkdir(parents=True, exist_ok=True)
    a.md.write_text(md)
    a.out.write_text(json.dumps({
        "settings": {"size": a.size, "image": a.image, "tile": a.tile, "latency": a.latency,
                     "incoherent": a.incoherent, "seed": a.seed,
                     "params": traverse_system.spec(a.park, params).params},
        "rows": rows, "summary": summary, "mismatches": mism, "sim_clocks": sim_clocks,
        "sim_wall_seconds": sim_wall,
        "paper": {"mhz": PAPER_MHZ, "units": PAPER_UNITS, "mpixels_per_s": PAPER_MPIX,
                  "clocks_per_pixel_per_unit": PAPER_CLOCKS_PER_PIXEL}}, indent=1))
    if mism:
        print(f"{PROG}: {mism} rays differ between the RTL and the f24 engine", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
