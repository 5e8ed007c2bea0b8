#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""One ray, step by step: the golden model's traversal of a single ray (level, cell, the height read
and its byte address, t, plane, t_exit, t_new, action per iteration), to line up with the RTL's
waveform; optionally the same ray through the RTL (Verilator harness), with its FST.

  ray_steps.py (--scene NAME [--map-size N] | --heightmap FILE)
               (--ray U0 V0 DU DV | --rays RAYS.npy --index I | --pixel X Y [--angle A] [--image N])
               [--method park] [--engine f24|f64] [--rtl] [--waves OUT.fst] [--json OUT.json]

The steps come from model.traverse.trace's `record` hook (the traversal itself is not repeated
here).  With the f24 engine every float is also shown as its 24-bit pattern (hex), the form the
waves show.  Iteration i of the model is the i-th height lookup of the ray that the cache answered
with a hit (rs_hit_i = 1): lookups answered with a miss go round again and are not iterations.
After a descent whose locate moved its estimate one cell on (the model's row has "estimate"), the
ring's next lookup reads the estimate (its exit check's redo pass, not an iteration, whether the
cache answers it with a hit or a miss): expected_reads lists that read too, and match_reads pairs
each expected read with its lookup.
--pixel takes the ray the pipeline traces for that pixel of a scene view (the view unit's du, dv
in the engine's arithmetic, model.view.view_calc).  Bad input: one line, exit status 2.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

from model import f24, heightmap, traverse
from model.arith import ENGINES
from model.cli import Parser, fail
from model.rays import Rays
from tb.harness import traverse_words

PROG = "ray_steps.py"
#: The harness's byte address of the pyramid (tb.harness.traverse_system.DEFAULT_BASE).
DEFAULT_BASE = 0x4000_0000
#: Clocks from a height lookup to its answer (traverse_pkg::LOOKUP_LAT).
LOOKUP_LAT = traverse_words.LOOKUP_LAT
#: The ring's stage that writes the next state (one before the tail, traverse_pkg::LOOP_DEPTH).
NEXT_STAGE = traverse_words.LOOP_DEPTH - 2


def hx(x: float) -> str:
    """The f24 pattern of a value the f24 engine produced (exactly representable)."""
    return f"{int(f24.from_float(np.array([x]))[0]):06x}"


def texel_address(pyr: heightmap.Pyramid, base: int, k: int, cx: int, cy: int) -> int:
    """traverse_addr's byte address: base + level_off[k] + (cy * (N >> k) + cx) * bytes."""
    return base + pyr.level_offsets()[k] + (cy * (pyr.size >> k) + cx) * (pyr.bits // 8)


def load_map(args) -> tuple[np.ndarray, str, Any]:
    """Heights, a name, and the scene (None for a height-map file)."""
    if args.heightmap is not None:
        if args.scene is not None:
            fail(PROG, "give --scene or --heightmap, not both")
        try:
            return heightmap.load(args.heightmap), str(args.heightmap), None
        except Exception as e:  # HeightMapError, OpenImageIO's errors
            fail(PROG, f"cannot read height map {args.heightmap}: {e}".splitlines()[0])
    from model import scenes
    name = args.scene or "rocks"
    if name not in scenes.SCENES:
        fail(PROG, f"unknown scene {name!r} (valid scenes: {', '.join(scenes.SCENES)})")
    if args.map_size < 1 or args.map_size > 4096:
        fail(PROG, f"--map-size must be 1 .. 4096, got {args.map_size}")
    sc = scenes.load_scene(name, args.map_size)
    return sc.heights, f"{name} {args.map_size}x{args.map_size}", sc


def pick_ray(args, pyr: heightmap.Pyramid, scene, engine: str) -> tuple[Rays, str]:
    given = [x for x in ("ray", "rays", "pixel") if getattr(args, x) is not None]
    if len(given) != 1:
        fail(PROG, "give exactly one of --ray, --rays (with --index), --pixel")
    if args.ray is not None:
        return Rays.from_array(np.array([args.ray], dtype=np.float64)), "given with --ray"
    if args.rays is not None:
        if args.index is None:
            fail(PROG, "--rays needs --index")
        try:
            a = np.load(args.rays, allow_pickle=False)
        except Exception as e:
            fail(PROG, f"cannot read rays file {args.rays}: {e}".splitlines()[0])
        if not isinstance(a, np.ndarray) or a.dtype != np.float64 or a.ndim != 2 \
                or a.shape[1] != 4:
            fail(PROG, f"rays must be a float64 (N, 4) array, {args.rays} holds "
                       f"{getattr(a, 'dtype', '?')} {getattr(a, 'shape', '?')}")
        if not 0 <= args.index < len(a):
            fail(PROG, f"--index {args.index} out of range: {args.rays} holds {len(a)} rays")
        return Rays.from_array(a[args.index:args.index + 1]), f"ray {args.index} of {args.rays}"
    # --pixel: the ray the pipeline traces for that pixel
    from model import camera, view
    from model.camera import VIEWS
    try:
        angle: str | float = args.angle if args.angle in VIEWS else float(args.angle)
    except ValueError:
        fail(PROG, f"--angle must be one of {', '.join(VIEWS)} or an elevation in degrees")
    depth = scene.depth_scale if scene is not None else camera.depth_scale(pyr.width, pyr.height)
    try:
        cam = camera.Camera.for_view(angle, pyr.width, pyr.height, args.image, args.image,
                                     depth_scale=depth)
    except ValueError as e:
        fail(PROG, str(e))
    x, y = args.pixel
    fr = cam.fragments()
    idx = np.nonzero((fr.row == y) & (fr.col == x))[0]
    if idx.size == 0:
        fail(PROG, f"pixel ({x}, {y}) of the {args.image}x{args.image} {args.angle} view is not "
                   "covered by the quad")
    i = int(idx[0])
    vo = view.view_calc(ENGINES[engine], fr.tbn[i:i + 1], fr.view[i:i + 1], depth)
    return (Rays(fr.u0[i:i + 1].copy(), fr.v0[i:i + 1].copy(), vo.du, vo.dv),
            f"pixel ({x}, {y}) of the {args.image}x{args.image} {args.angle} view "
            f"(view unit, {engine})")


def steps(pyr: heightmap.Pyramid, rays: Rays, method: str, engine: str, base: int
          ) -> tuple[list[dict[str, Any]], Any, dict[str, int]]:
    rec: list[dict[str, Any]] = []
    stats: dict[str, int] = {}
    res = traverse.trace(pyr, rays, method, engine, record=rec, stats=stats)
    for r in rec:
        for x in (r, r.get("estimate")):
            if x is not None:
                x["code"] = int(pyr.levels[x["level"]][x["cy"], x["cx"]])
                x["address"] = texel_address(pyr, base, x["level"], x["cx"], x["cy"])
    return rec, res, stats


def expected_reads(steps_: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The height reads the RTL makes for the model's rows, in order: one answered read per row
    (iteration), and before the row after a descent whose locate moved its estimate, the redo's
    read of that estimate (level, cell, address, code of the estimate; the next row's t and
    iteration; "redo": True): the lookup right after the descent's, answered or not."""
    out: list[dict[str, Any]] = []
    for i, s in enumerate(steps_):
        est = steps_[i - 1].get("estimate") if i else None
        if est is not None:
            out.append({**est, "t": s["t"], "iteration": s["iteration"], "redo": True})
        out.append(s)
    return out


def _what(s: dict[str, Any]) -> str:
    return (f"the redo before iteration {s['iteration']}" if s.get("redo")
            else f"iteration {s['iteration']}")


def _answered(lk: dict[str, Any]) -> bool:
    return bool(lk.get("hit") or lk.get("err"))


def match_reads(reads: list[dict[str, Any]], looks: list[dict[str, Any]]
                ) -> tuple[list[tuple[dict[str, Any], dict[str, Any]]], str | None]:
    """Pairs each expected read (expected_reads) with the RTL lookup that makes it: an
    iteration's is the next answered lookup (misses before it go round again), a redo's the next
    lookup of any answer.  Returns the pairs and None, or the pairs so far and what is missing or
    left over."""
    pairs: list[tuple[dict[str, Any], dict[str, Any]]] = []
    j = 0
    for r in reads:
        if not r.get("redo"):
            while j < len(looks) and not _answered(looks[j]):
                j += 1
        if j >= len(looks):
            n = sum(1 for _, lk in pairs if _answered(lk))
            return pairs, (f"{_what(r)}: the model reads 0x{r['address']:08x}; the RTL made only "
                           f"{n} answered lookups")
        pairs.append((r, looks[j]))
        j += 1
    rest = [lk for lk in looks[j:] if _answered(lk)]
    if rest:
        lk = rest[0]
        return pairs, (f"the RTL reads on after the model's {len(reads)} reads: 0x"
                       f"{lk['address']:08x} at clock {lk['clock']} (time {lk['time']})")
    return pairs, None


def rtl_lookups(fst: Path, scope: str = "TOP.traverse_system.u_unit.") -> list[dict[str, Any]]:
    """The height lookups of the traverse unit in an FST of the harness, in order: clock, byte
    address, and the cache's answer LOOKUP_LAT clocks later (hit / miss / error, code).  The
    harness dumps clock n's inputs at time 2n (clk_i low) and its edge at 2n + 1."""
    import pywellen

    w = pywellen.Waveform(str(fst))
    vs = {v.full_name: v for v in w.all_vars()}
    names = ("clk_i", "lk_valid_o", "lk_addr_o", "rs_valid_i", "rs_hit_i", "rs_err_i", "rs_data_i")
    missing = [n for n in names if scope + n not in vs]
    if missing:
        raise KeyError(f"{fst} lacks {scope}{missing[0]}")
    sig = {n: vs[scope + n].signal for n in names}
    steps: list[int] = []
    w.stream_time_steps(lambda idx, *_: steps.append(idx), [vs[scope + "clk_i"]])
    n_idx = (max(steps) + 1) if steps else 0

    def val(n: str, i: int) -> int:
        v = sig[n].value_at(i)
        return int(v) if isinstance(v, int) else 0

    looks: list[dict[str, Any]] = []
    for i in range(0, n_idx, 2):
        if val("clk_i", i) or not val("lk_valid_o", i):
            continue
        lk: dict[str, Any] = {"clock": i // 2, "time": i, "address": val("lk_addr_o", i)}
        j = i + 2 * LOOKUP_LAT   # the answer, LOOKUP_LAT clocks later
        if j < n_idx and val("rs_valid_i", j):
            lk.update(hit=bool(val("rs_hit_i", j)), err=bool(val("rs_err_i", j)),
                      code=val("rs_data_i", j))
        looks.append(lk)
    return looks


def ring_states(fst: Path, looks: list[dict[str, Any]],
                scope: str = "TOP.traverse_system.u_unit.u_loop.",
                answered_only: bool = True) -> list[dict[str, int]] | None:
    """The ray's state in stage S1's ring registers (node_q[1], t_q[1], stat_q[1].iters) at the
    clock of each answered lookup (of every lookup given, with answered_only False: the lookups
    match_reads paired; S1 presents the lookup); None when the FST lacks them."""
    import pywellen

    w = pywellen.Waveform(str(fst))
    vs = {v.full_name: v for v in w.all_vars()}
    names = {"level": "node_q.[1].k", "cx": "node_q.[1].cx", "cy": "node_q.[1].cy",
             "t": "t_q.[1]", "iters": "stat_q.[1].iters"}
    if any(scope + n not in vs for n in names.values()):
        return None
    out = []
    for lk in looks:
        if answered_only and not _answered(lk):
            continue
        row = {}
        for k, n in names.items():
            v = vs[scope + n].signal.value_at(lk["time"])
            row[k] = int(v) if isinstance(v, int) else -1
        out.append(row)
    return out


def compare_states(steps_: list[dict[str, Any]], states: list[dict[str, int]]) -> str | None:
    """None when S1's ring registers held each expected read's level, cell, t and iteration - 1
    at its lookup (steps_: expected_reads of the model's rows), else the first difference."""
    for s, st in zip(steps_, states):
        want = {"level": s["level"], "cx": s["cx"], "cy": s["cy"],
                "t": int(f24.from_float(np.array([s["t"]]))[0]), "iters": s["iteration"] - 1}
        if st != want:
            return f"{_what(s)}: model {_fmt_state(want)}; RTL {_fmt_state(st)}"
    return None


def _fmt_state(st: dict[str, int]) -> str:
    return ", ".join(f"{k} {v:#x}" if k == "t" else f"{k} {v}" for k, v in st.items())


def compare_lookups(steps_: list[dict[str, Any]], looks: list[dict[str, Any]]) -> str | None:
    """None when the RTL's lookups read the expected addresses in order (steps_: expected_reads
    of the model's rows; paired by match_reads), with the expected codes where answered (an
    iteration's always), else the first difference."""
    pairs, short = match_reads(steps_, looks)
    for s, lk in pairs:
        code_ok = (not _answered(lk)) or lk.get("code") == s["code"]
        if lk["address"] != s["address"] or not code_ok or lk.get("err"):
            ans = ("a miss" if not _answered(lk) else
                   f"code 0x{lk['code']:x}{', error' if lk.get('err') else ''}")
            return (f"{_what(s)}: the model reads 0x{s['address']:08x} (code "
                    f"0x{s['code']:x}), the RTL 0x{lk['address']:08x} ({ans}) at clock "
                    f"{lk['clock']} (time {lk['time']})")
    return short


def fmt_val(x: float, f24_engine: bool) -> str:
    if f24_engine:
        return f"{x:<11.6g} {hx(x)}" if np.isfinite(x) else f"{x:<11} {hx(x)}"
    return f"{x:<.9g}"


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    src = ap.add_argument_group("height map")
    src.add_argument("--scene", help="procedural scene (default rocks)")
    src.add_argument("--map-size", type=int, default=256, help="scene map side (default 256)")
    src.add_argument("--heightmap", type=Path, help="image (OpenImageIO) or .npy")
    src.add_argument("--bits", type=int, default=8, choices=(8, 16), help="height storage")
    ray = ap.add_argument_group("the ray")
    ray.add_argument("--ray", type=float, nargs=4, metavar=("U0", "V0", "DU", "DV"))
    ray.add_argument("--rays", type=Path, help="a RAYS.npy batch (trace.py's input) ...")
    ray.add_argument("--index", type=int, help="... and the ray's index in it")
    ray.add_argument("--pixel", type=int, nargs=2, metavar=("X", "Y"),
                     help="the pipeline's ray for pixel (column X, row Y) of a view")
    ray.add_argument("--angle", default="oblique", help="front | oblique | grazing | degrees")
    ray.add_argument("--image", type=int, default=256, help="image side for --pixel")
    ap.add_argument("--method", default="park", help=", ".join(traverse.EXACT_METHODS))
    ap.add_argument("--engine", default="f24", choices=("f24", "f64"))
    ap.add_argument("--base", type=lambda s: int(s, 0), default=DEFAULT_BASE,
                    help="byte address of the pyramid (default 0x40000000, the harness's)")
    ap.add_argument("--rtl", action="store_true", help="also trace the ray on the RTL")
    ap.add_argument("--waves", type=Path, help="with --rtl: write the RTL run's FST here")
    ap.add_argument("--latency", type=int, default=20, help="AXI read latency for --rtl")
    ap.add_argument("--json", type=Path, help="write the steps and results as JSON")
    args = ap.parse_args(argv)

    if args.method not in traverse.EXACT_METHODS:
        fail(PROG, f"unknown method {args.method!r} (exact methods: "
                   f"{', '.join(traverse.EXACT_METHODS)})")
    if args.waves is not None:
        args.rtl = True
        if args.waves.suffix != ".fst":
            fail(PROG, f"--waves writes an FST file (name it .fst): {args.waves}")
    if args.rtl and args.engine != "f24":
        fail(PROG, "--rtl compares with the f24 engine (the RTL's arithmetic)")
    if args.json is not None:
        try:
            args.json.parent.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            fail(PROG, f"cannot write --json {args.json}: {e.strerror or e}")
        if args.json.is_dir():
            fail(PROG, f"--json {args.json} is a directory")
    h, name, scene = load_map(args)
    pyr = heightmap.build(h, bits=args.bits)
    rays, origin = pick_ray(args, pyr, scene, args.engine)
    is24 = args.engine == "f24"
    rec, res, stats = steps(pyr, rays, args.method, args.engine, args.base)

    out = sys.stdout
    print(f"{PROG}: {name} (unorm{pyr.bits}, padded {pyr.size}, root level {pyr.n}), "
          f"method {args.method}, engine {args.engine}; pyramid at 0x{args.base:08x}", file=out)
    r = [float(getattr(rays, k)[0]) for k in ("u0", "v0", "du", "dv")]
    print(f"ray ({origin}): u0 {r[0]!r} v0 {r[1]!r} du {r[2]!r} dv {r[3]!r}", file=out)
    if is24:
        q = [float(f24.to_float(f24.from_float(np.array([x])))[0]) for x in r]
        print("  as f24 (ray_u0_i ray_v0_i ray_du_i ray_dv_i): "
              + " ".join(hx(x) for x in q), file=out)
    cols = ["t", "plane", "t_exit", "t_new"]
    w = 18 if is24 else 12
    print(f"{'iter':>4} {'lvl':>3} {'cell x':>7} {'cell y':>7} {'address':>10} {'code':>6} "
          + " ".join(f"{c:<{w}}" for c in cols) + " action", file=out)
    for s in rec:
        print(f"{s['iteration']:>4} {s['level']:>3} {s['cx']:>7} {s['cy']:>7} "
              f"{s['address']:>#10x} {s['code']:>#6x} "
              + " ".join(f"{fmt_val(s[c], is24):<{w}}" for c in cols) + f" {s['action']}",
              file=out)
    inv = bool(res.invalid[0])
    summary = {"hit": bool(res.hit[0]), "invalid": inv, "t": float(res.t[0]),
               "u": float(res.u[0]), "v": float(res.v[0]),
               "iterations": int(res.iterations[0])}
    if inv:
        print("model: the ray is invalid (a NaN / Inf field, or it starts outside the map): "
              "no iterations", file=out)
    else:
        print(f"model: {'hit' if summary['hit'] else 'no hit'}"
              + (f" t {summary['t']!r} u {summary['u']!r} v {summary['v']!r}"
                 + (f" (f24 {hx(summary['t'])} {hx(summary['u'])} {hx(summary['v'])})"
                    if is24 else "") if summary["hit"] else "")
              + f", {summary['iterations']} iterations; {stats}", file=out)
    result: dict[str, Any] = {"map": name, "method": args.method, "engine": args.engine,
                              "ray": r, "origin": origin, "base": args.base, "steps": rec,
                              "model": summary}
    rc = 0
    if args.rtl:
        from tb.harness import traverse_system
        print(f"{PROG}: running the ray on the RTL (Verilator harness"
              + (", traced build" if args.waves else "") + "; the first build takes minutes)",
              file=sys.stderr, flush=True)
        try:
            rr, st = traverse_system.trace_rtl(pyr, rays, args.method, latency=args.latency,
                                               waves=args.waves, base=args.base)
        except Exception as e:  # RtlEngineError, build failures
            print(f"{PROG}: the RTL run failed: {e}".splitlines()[0], file=sys.stderr)
            return 1
        got = {"hit": bool(rr.hit[0]), "invalid": bool(rr.invalid[0]), "t": float(rr.t[0]),
               "u": float(rr.u[0]), "v": float(rr.v[0]), "iterations": int(rr.iterations[0])}
        same = all((got[k] == summary[k]) or (isinstance(got[k], float) and np.isnan(got[k])
                                              and np.isnan(summary[k])) for k in got)
        print(f"rtl:   {'hit' if got['hit'] else 'no hit'}"
              + (f" t {got['t']!r} u {got['u']!r} v {got['v']!r}" if got["hit"] else "")
              + f", {got['iterations']} iterations, {st.get('cycles')} clocks: "
              + ("identical to the model" if same else "DIFFERENT from the model"), file=out)
        if args.waves:
            looks = rtl_lookups(args.waves)
            print(f"rtl lookups in the waves ({len(looks)}; clock n is at time 2n; iteration i = "
                  f"the i-th answered lookup; for a lookup at clock c: the ray's state in group "
                  f"S0 at c - 1, lk_* at c, the answer at c + {LOOKUP_LAT}, the action and next "
                  f"state in S{NEXT_STAGE} at c + {NEXT_STAGE - 1}):", file=out)
            print(f"{'clock':>6} {'time':>6} {'address':>10}  answer", file=out)
            reads = expected_reads(rec)
            pairs, _ = match_reads(reads, looks)
            made = {id(lk): r for r, lk in pairs}
            for lk in looks:
                ans = ("error" if lk.get("err") else f"hit {lk['code']:#06x}" if lk.get("hit")
                       else "miss" if "hit" in lk else "(no answer)")
                if id(lk) in made and made[id(lk)].get("redo"):
                    ans += "  = " + _what(made[id(lk)]) + " (locate's exit check)"
                elif id(lk) in made:
                    ans += "  = " + _what(made[id(lk)])
                elif "hit" in lk and not lk.get("hit"):
                    ans += " (goes round again)"
                print(f"{lk['clock']:>6} {lk['time']:>6} {lk['address']:>#10x}  {ans}", file=out)
            states = ring_states(args.waves, [lk for _, lk in pairs], answered_only=False)
            if states is not None:
                sdiff = compare_states(reads, states)
                print("state: at each answered lookup and each redo's (clock c), S1's ring "
                      "registers u_loop.node_q[1] (k, cx, cy), t_q[1] and stat_q[1].iters hold the row's level, "
                      "cell, t and iteration - 1 (the registers move one stage a clock: stage "
                      f"s at c + s - 1; S{NEXT_STAGE} loads stage {NEXT_STAGE + 1} with the next row's at "
                      f"c + {NEXT_STAGE - 1}): "
                      + ("yes" if sdiff is None else f"FIRST DIFFERENCE: {sdiff}"), file=out)
                result["state_difference"] = sdiff
                same = same and sdiff is None
            diff = compare_lookups(reads, looks)
            print("lookups: " + ("the RTL reads the model's addresses and codes in order"
                                 if diff is None else f"FIRST DIFFERENCE: {diff}"), file=out)
            print(f"waves: {args.waves} (gtkwave {args.waves} tb/waves/traverse_harness.gtkw)",
                  file=out)
            result["rtl_lookups"] = looks
            result["lookup_difference"] = diff
            same = same and diff is None
        result["rtl"] = got
        result["rtl_stats"] = st
        rc = 0 if same else 1
    if args.json:
        args.json.write_text(json.dumps(result, indent=1, default=float) + "\n")
    return rc


if __name__ == "__main__":
    sys.exit(main())
