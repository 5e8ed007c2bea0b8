#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The iteration study of Park et al. 2013, section 5, on the project's scenes and camera.

  study.py [--quick] [--out DIR] [--size N] [--image-size N] [--scenes a,b,..] [--angles a,b,..]
           [--engine f64|f24] [--quiet]

For every scene x view angle, one ray per covered pixel of an image-size x image-size camera image
over a size x size map (``model.camera``), and:

* Table 2: the probability of a node crossing among the iterations (height reads) of ``oh``
  ([10]) and ``tevs`` ([12]), and the whole action breakdown (descent, crossing, level-up, hit,
  miss) of every exact method.  The paper's number is crossings / iterations (its Rocks row
  reproduces its own Table 4: 8 descents + 1 final read + crossings = iterations).
* Table 3: mean iterations of the multi-level descent with n = 1..4 levels before the first
  crossing (no start level, no level-up; n = 1 is ``oh``, n = 2 is ``multi-down``).
* Table 4: mean iterations per pixel of every exact method, the reduction of ``park`` and
  ``park-xor`` against ``oh`` and ``tevs``, with the paper's numbers beside ours.
* The approximate methods against the exact hit (``park``, f64): |t - t_exact|, pixels whose hit
  texel differs, hit-position MSE, PSNR of a texture-lookup image, iterations.
* f24 against f64: hit-texel agreement of every exact method.

Writes DIR/study.md (tables), DIR/study.json (every number), DIR/study.png (iterations per method
and angle) and prints a short summary.  Progress goes to stderr.

Action counts come from ``traverse.trace(..., stats=...)``; the descent depth of Table 3 is
``Method.descent_levels``.
"""
from __future__ import annotations

import dataclasses
import inspect
import json
import math
import sys
import time
from pathlib import Path
from typing import Any, Callable

import numpy as np

from model import camera, heightmap, scenes, traverse
from model.cli import Parser, Progress, fail
from model.rays import Rays, TraceResult

PROG = "study.py"
ANGLES = ("front", "oblique", "grazing")
ANGLE_ABBR = {"front": "F", "oblique": "O", "grazing": "G"}
TABLE2_METHODS = ("oh", "tevs")
DESCENT_LEVELS = (1, 2, 3, 4)
REFERENCE = "park"  # the exact method (f64) the approximate methods are measured against
ACTIONS = ("down", "cross", "hit", "miss")  # every iteration is exactly one of these
QUICK = {"size": 64, "image_size": 64, "scenes": ("rocks", "stones", "bump"), "angles": ANGLES}
FULL = {"size": 256, "image_size": 256, "scenes": scenes.SCENES, "angles": ANGLES}

# ---- the paper's numbers (Park et al. 2013, section 5; seed text 000) ------------------------
# Table 2: probability of node crossing (%), [10] = oh, [12] = tevs, per scene: F, O, G.
PAPER_T2: dict[str, dict[str, tuple[float, ...]]] = {
    "oh": {"rocks": (22.4, 54.5, 76.4), "stones": (3.8, 17.9, 51.5),
           "four-shapes": (8.5, 39.7, 58.1), "saints": (5.9, 27.5, 62.1),
           "wall": (5.1, 21.0, 52.1), "bump": (7.6, 38.2, 72.5), "dent": (5.1, 23.5, 38.5)},
    "tevs": {"rocks": (19.2, 36.9, 47.9), "stones": (3.7, 15.0, 36.1),
             "four-shapes": (8.1, 28.3, 37.9), "saints": (5.5, 21.6, 39.8),
             "wall": (4.9, 16.6, 35.9), "bump": (7.3, 27.5, 47.3), "dent": (4.9, 18.3, 26.9)},
}
# Table 3: iterations for descent depth n, Rocks only: F, O, G.
PAPER_T3 = {1: (11.5, 19.7, 37.9), 2: (8.9, 18.2, 37.8), 3: (8.4, 18.2, 38.0), 4: (9.6, 19.1, 42.7)}
# Table 4: iterations per pixel, F, O, G.  The seed's text of this table is garbled; it was read
# row by row (seven values per scene column group).  None: a cell the text does not give (five
# "mixed use" cells, presumably bold values lost).  Doubtful reads are listed in PAPER_T4_NOTES.
_N = None
PAPER_T4: dict[str, dict[str, tuple[float | None, ...]]] = {
    "oh": {"rocks": (11.6, 19.7, 37.9), "stones": (9.3, 10.9, 18.4),
           "four-shapes": (9.8, 14.9, 21.3), "saints": (9.5, 12.4, 23.6),
           "wall": (9.4, 11.3, 18.7), "bump": (8.6, 12.9, 28.9), "dent": (8.4, 10.4, 12.7)},
    "tevs": {"rocks": (12.6, 19.6, 30.2), "stones": (9.5, 11.5, 19.2),
             "four-shapes": (10.2, 15.0, 20.0), "saints": (9.8, 13.2, 20.7),
             "wall": (9.7, 11.8, 19.2), "bump": (8.9, 13.4, 25.3), "dent": (8.6, 19.8, 12.7)},
    "start-level": {"rocks": (9.5, 19.3, 37.9), "stones": (4.4, 8.4, 18.0),
                    "four-shapes": (7.4, 14.3, 21.3), "saints": (6.6, 11.4, 23.3),
                    "wall": (5.2, 9.4, 18.3), "bump": (8.5, 12.9, 28.9), "dent": (8.3, 10.4, 12.7)},
    "multi-down": {"rocks": (8.9, 18.3, 37.8), "stones": (5.6, 7.8, 16.4),
                   "four-shapes": (6.9, 13.8, 21.6), "saints": (6.1, 10.1, 23.2),
                   "wall": (4.1, 8.0, 23.0), "bump": (6.2, 12.9, 36.6), "dent": (5.5, 8.0, 11.0)},
    "selective": {"rocks": (11.6, 18.4, 29.2), "stones": (9.3, 11.0, 18.2),
                  "four-shapes": (9.8, 14.4, 19.7), "saints": (9.5, 12.3, 20.0),
                  "wall": (9.4, 11.3, 18.5), "bump": (8.6, 12.3, 24.7), "dent": (8.4, 10.3, 12.4)},
    "coherent": {"rocks": (12.1, 19.8, 31.6), "stones": (9.3, 11.3, 19.3),
                 "four-shapes": (10.0, 15.4, 20.6), "saints": (9.6, 12.9, 21.4),
                 "wall": (9.5, 11.7, 19.3), "bump": (8.7, 13.2, 26.1), "dent": (8.4, 10.7, 13.0)},
    "park": {"rocks": (8.0, 16.4, 28.3), "stones": (3.2, 6.6, _N), "four-shapes": (5.6, 12.6, _N),
             "saints": (4.7, 9.5, 18.8), "wall": (3.9, 6.6, _N), "bump": (6.1, _N, 24.1),
             "dent": (5.5, 7.8, _N)},
}
PAPER_T4_NOTES = [
    "Table 4 of the seed text is garbled; values were read row by row. Blank paper cells: the text "
    "does not give them (five a+b+c1 cells).",
    "tevs rocks oblique: the text gives 19.6 in the table body and 19.0 in its header line.",
    "tevs dent oblique: the text reads 19.8 (oh 10.4, coherent 10.7: probably 10.8).",
]
PAPER_CLAIM = {"park_vs_oh": (16.0, 65.0), "park_vs_tevs": (5.0, 66.0)}


class StudyError(RuntimeError):
    """An internal inconsistency (action counts that do not add up to the iterations)."""


# ---- counted traversal (stats + descent depth) ----------------------------------------------

class Counted:
    """trace() with its action counts (``stats``) and an optional descent depth."""

    def __call__(self, pyr: heightmap.Pyramid, rays: Rays, method: traverse.Method, engine: str,
                 descent_levels: int | None = None) -> tuple[TraceResult, dict[str, int]]:
        stats: dict[str, int] = {}
        if descent_levels is not None:
            method = dataclasses.replace(method, descent_levels=descent_levels)
        res = traverse.trace(pyr, rays, method, engine, stats=stats)
        out = {k: int(stats.get(k, 0)) for k in ("down", "cross", "up", "hit", "miss")}
        total = sum(out[a] for a in ACTIONS)
        if total != int(res.iterations.sum()):
            raise StudyError(f"{method.name}: action counts sum to {total}, "
                             f"iterations to {int(res.iterations.sum())}")
        return res, out


def same_result(a: TraceResult, b: TraceResult) -> bool:
    """Iterations, hit and t identical (NaN equal to NaN)."""
    return (np.array_equal(a.iterations, b.iterations) and np.array_equal(a.hit, b.hit)
            and np.array_equal(a.t, b.t, equal_nan=True))


# ---- measurements ---------------------------------------------------------------------------

def hit_texels(pyr: heightmap.Pyramid, rays: Rays, res: TraceResult,
               engine: str = "f64") -> tuple[np.ndarray, np.ndarray]:
    """The level-0 cell (column, row) holding each ray at its hit time, by the traversal's
    crossing-time rule in the engine's arithmetic (traverse.locate); -1 where there is no hit.

    (floor(u) would pick the neighbour of a wall hit exactly on a texel edge.)
    """
    ar = traverse.ENGINES[engine]
    invalid, S = traverse.setup(pyr, rays, ar)
    ok = ~invalid
    t = np.nan_to_num(res.t[ok])
    zero = np.zeros(t.shape, dtype=np.int64)
    cx = traverse.locate(ar, S.u0, S.du, S.inv_du, S.sx, t, zero, zero, zero + pyr.width - 1)
    cy = traverse.locate(ar, S.v0, S.dv, S.inv_dv, S.sy, t, zero, zero, zero + pyr.height - 1)
    tx = np.full(len(rays), -1, dtype=np.int64)
    ty = tx.copy()
    tx[ok], ty[ok] = cx, cy
    miss = ~res.hit
    tx[miss] = ty[miss] = -1
    return tx, ty


def compare(pyr: heightmap.Pyramid, rays: Rays, ref: TraceResult, res: TraceResult,
            texture: np.ndarray | None, ref_engine: str = "f64",
            res_engine: str = "f64") -> dict[str, Any]:
    """Per-pixel agreement of ``res`` with ``ref`` (both over the same rays)."""
    n = max(len(rays), 1)
    rx, ry = hit_texels(pyr, rays, ref, ref_engine)
    qx, qy = hit_texels(pyr, rays, res, res_engine)
    both = ref.hit & res.hit
    dt = np.abs(res.t - ref.t)[both]
    d2 = ((res.u - ref.u) ** 2 + (res.v - ref.v) ** 2)[both]
    same_texel = (rx == qx) & (ry == qy)  # both misses count as agreeing
    out: dict[str, Any] = {
        "pixels": len(rays),
        "hit_mismatch_pct": 100.0 * float(np.count_nonzero(ref.hit != res.hit)) / n,
        "texel_differs_pct": 100.0 * float(np.count_nonzero(~same_texel)) / n,
        "mean_abs_dt": float(dt.mean()) if dt.size else 0.0,
        "max_abs_dt": float(dt.max()) if dt.size else 0.0,
        "mse_uv": float(d2.mean()) if d2.size else 0.0,
        "iterations": float(res.iterations.mean()) if len(rays) else 0.0,
        "iterations_equal_pct": 100.0 * float(np.count_nonzero(res.iterations == ref.iterations)) / n,
    }
    if texture is not None:
        def image(tx: np.ndarray, ty: np.ndarray) -> np.ndarray:
            img = np.zeros((len(tx), 3))
            h = tx >= 0
            img[h] = texture[ty[h], tx[h]]
            return img
        mse = float(np.mean((image(qx, qy) - image(rx, ry)) ** 2)) if len(rays) else 0.0
        out["mse_texture"] = mse
        out["psnr_texture_db"] = None if mse == 0 else 10.0 * math.log10(1.0 / mse)
    return out


def fractions(counts: dict[str, int]) -> dict[str, float]:
    total = max(sum(counts[a] for a in ACTIONS), 1)
    out = {a: counts[a] / total for a in ACTIONS}
    out["p_cross"] = out["cross"]  # the paper's number: crossings / iterations
    out["p_down"] = out["down"]
    out["p_end"] = out["hit"] + out["miss"]
    out["level_up_per_cross"] = counts["up"] / counts["cross"] if counts["cross"] else 0.0
    return out


def approx_registry() -> tuple[dict[str, Callable[..., TraceResult]], str | None]:
    try:
        from model import approx
        return dict(approx.APPROX_METHODS), None
    except Exception as e:  # being finished concurrently: report, don't die
        return {}, f"{type(e).__name__}: {e}"


def run_approx(fn: Callable[..., TraceResult], pyr: heightmap.Pyramid, rays: Rays,
               depth_scale: float) -> TraceResult:
    kw = {}
    if "depth_scale" in inspect.signature(fn).parameters:
        kw["depth_scale"] = depth_scale
    return fn(pyr, rays, **kw)


def study_view(pyr: heightmap.Pyramid, scene: scenes.Scene, rays: Rays, engine: str,
               counted: Counted, approx: dict[str, Callable[..., TraceResult]],
               tick: Callable[[], None] = lambda: None) -> dict[str, Any]:
    """Every measurement of one scene x angle; ``tick`` after each method (for progress)."""
    other = "f24" if engine == "f64" else "f64"
    out: dict[str, Any] = {"rays": len(rays), "methods": {}, "descent": {}, "approx": {},
                           "engine": {}}
    results: dict[str, dict[str, TraceResult]] = {"f64": {}, "f24": {}}
    for name, m in traverse.METHODS.items():
        res, counts = counted(pyr, rays, m, engine)
        official = traverse.trace(pyr, rays, name, engine)
        if not same_result(res, official):
            raise StudyError(f"counted trace of {name} ({engine}) differs from traverse.trace")
        results[engine][name] = official
        results[other][name] = traverse.trace(pyr, rays, name, other)
        cap = traverse.iteration_cap(pyr)
        out["methods"][name] = {
            "iterations": float(res.iterations.mean()) if len(rays) else 0.0,
            "iterations_max": int(res.iterations.max(initial=0)),
            "hit_pct": 100.0 * float(res.hit.mean()) if len(rays) else 0.0,
            "capped": int(np.count_nonzero(res.iterations >= cap)),
            "counts": counts, "fractions": fractions(counts)}
        out["engine"][name] = compare(pyr, rays, results["f64"][name], results["f24"][name],
                                      None, "f64", "f24")
        tick()
    base = traverse.Method("multi-n", descent="multi", doc="oh + multi descent of n levels")
    for n in DESCENT_LEVELS:
        res, counts = counted(pyr, rays, base, engine, descent_levels=n)
        check = {1: "oh", 2: "multi-down"}.get(n)
        if check and not same_result(res, results[engine][check]):
            raise StudyError(f"descent n = {n} differs from {check} ({engine})")
        out["descent"][str(n)] = {"iterations": float(res.iterations.mean()) if len(rays) else 0.0,
                                  "fractions": fractions(counts)}
        tick()
    ref = results["f64"][REFERENCE]
    for name, fn in approx.items():
        tick()
        try:
            res = run_approx(fn, pyr, rays, scene.depth_scale)
        except Exception as e:  # an unfinished approximate method must not stop the study
            out["approx"][name] = {"error": f"{type(e).__name__}: {e}".splitlines()[0]}
            continue
        out["approx"][name] = compare(pyr, rays, ref, res, scene.texture)
    return out


# ---- aggregation ----------------------------------------------------------------------------

def mean(xs: list[float | None]) -> float | None:
    v = [x for x in xs if x is not None]
    return float(np.mean(v)) if v else None


def paper_t4(method: str, scene: str, angle: str) -> float | None:
    if angle not in ANGLES:
        return None
    return PAPER_T4.get(method, {}).get(scene, (None, None, None))[ANGLES.index(angle)]


def paper_t2(method: str, scene: str, angle: str) -> float | None:
    if angle not in ANGLES:
        return None
    return PAPER_T2.get(method, {}).get(scene, (None, None, None))[ANGLES.index(angle)]


def reduction(a: float | None, b: float | None) -> float | None:
    """Percent fewer iterations of a than of b."""
    if a is None or b is None or b == 0:
        return None
    return 100.0 * (1.0 - a / b)


def aggregate(views: dict[str, dict[str, dict[str, Any]]], cfg: dict[str, Any]) -> dict[str, Any]:
    sc, an = cfg["scenes"], cfg["angles"]
    methods = list(traverse.METHODS)
    t2 = {s: {a: {m: {**views[s][a]["methods"][m]["fractions"],
                      "counts": views[s][a]["methods"][m]["counts"],
                      "paper_p_cross_pct": paper_t2(m, s, a)}
                  for m in methods} for a in an} for s in sc}
    t3 = {s: {a: {n: views[s][a]["descent"][n]["iterations"] for n in views[s][a]["descent"]}
              for a in an} for s in sc}
    t4 = {s: {a: {m: views[s][a]["methods"][m]["iterations"] for m in methods} for a in an}
          for s in sc}
    t4_mean = {a: {m: mean([t4[s][a][m] for s in sc]) for m in methods} for a in an}
    pairs = [("park", "oh"), ("park", "tevs"), ("park-xor", "oh"), ("park-xor", "tevs")]
    red = {s: {a: {f"{x}_vs_{y}": reduction(t4[s][a][x], t4[s][a][y]) for x, y in pairs}
               | {f"paper_park_vs_{y}": reduction(paper_t4("park", s, a), paper_t4(y, s, a))
                  for y in ("oh", "tevs")}
               for a in an} for s in sc}
    keys = [f"{x}_vs_{y}" for x, y in pairs] + ["paper_park_vs_oh", "paper_park_vs_tevs"]
    red_range = {}
    for k in keys:
        vals = [red[s][a][k] for s in sc for a in an if red[s][a][k] is not None]
        red_range[k] = [min(vals), max(vals)] if vals else None
    red_mean = {a: {f"{x}_vs_{y}": reduction(t4_mean[a][x], t4_mean[a][y]) for x, y in pairs}
                for a in an}
    p_cross_mean = {a: {m: mean([t2[s][a][m]["p_cross"] for s in sc]) for m in methods}
                    for a in an}
    approx_names = sorted({n for s in sc for a in an for n in views[s][a]["approx"]},
                          key=lambda n: list(views[sc[0]][an[0]]["approx"]).index(n)
                          if n in views[sc[0]][an[0]]["approx"] else 99)
    approx = {s: {a: views[s][a]["approx"] for a in an} for s in sc}
    approx_mean: dict[str, dict[str, Any]] = {}
    for a in an:
        approx_mean[a] = {}
        for n in approx_names:
            rows = [approx[s][a][n] for s in sc if "error" not in approx[s][a].get(n, {"error": 1})]
            if not rows:
                approx_mean[a][n] = {"error": "failed on every scene"}
                continue
            approx_mean[a][n] = {
                "mean_abs_dt": mean([r["mean_abs_dt"] for r in rows]),
                "max_abs_dt": max(r["max_abs_dt"] for r in rows),
                "texel_differs_pct": mean([r["texel_differs_pct"] for r in rows]),
                "hit_mismatch_pct": mean([r["hit_mismatch_pct"] for r in rows]),
                "mse_uv": mean([r["mse_uv"] for r in rows]),
                "mse_texture": mean([r["mse_texture"] for r in rows]),
                "iterations": mean([r["iterations"] for r in rows]),
                "scenes": len(rows)}
            m = approx_mean[a][n]["mse_texture"]
            approx_mean[a][n]["psnr_texture_db"] = (None if not m else 10 * math.log10(1 / m))
    eng = {s: {a: views[s][a]["engine"] for a in an} for s in sc}
    eng_summary = {m: {"min_texel_agree_pct": min(100 - eng[s][a][m]["texel_differs_pct"]
                                                  for s in sc for a in an),
                       "min_iterations_equal_pct": min(eng[s][a][m]["iterations_equal_pct"]
                                                       for s in sc for a in an),
                       "max_abs_dt": max(eng[s][a][m]["max_abs_dt"] for s in sc for a in an)}
                   for m in methods}
    return {
        "rays": {s: {a: views[s][a]["rays"] for a in an} for s in sc},
        "table2": t2, "table2_mean_p_cross": p_cross_mean,
        "table3": t3,
        "table4": t4, "table4_mean": t4_mean,
        "hits_pct": {s: {a: {m: views[s][a]["methods"][m]["hit_pct"] for m in methods}
                         for a in an} for s in sc},
        "capped_rays": sum(views[s][a]["methods"][m]["capped"] for s in sc for a in an
                           for m in methods),
        "reduction": red, "reduction_range": red_range, "reduction_of_means": red_mean,
        "approx": approx, "approx_mean": approx_mean, "approx_reference": f"{REFERENCE} (f64)",
        "engine": eng, "engine_summary": eng_summary,
    }


# ---- output ---------------------------------------------------------------------------------

def fmt(x: float | None, nd: int = 1) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    return f"{x:.{nd}f}"


def md_table(header: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines) + "\n"


def view_arg(a: str) -> str | float:
    """A view name as given, or an elevation in degrees."""
    return a if a in camera.VIEWS else float(a)


def elev(a: str) -> float:
    return camera.elevation(view_arg(a))


def ab(a: str) -> str:
    return ANGLE_ABBR.get(a, a)


def write_md(path: Path, cfg: dict[str, Any], R: dict[str, Any]) -> None:
    sc, an = cfg["scenes"], cfg["angles"]
    methods = list(traverse.METHODS)
    eng = cfg["engine"]
    o: list[str] = []
    o.append("# Iteration study (Park et al. 2013, section 5)\n")
    o.append(f"Map {cfg['size']}x{cfg['size']} (unorm8, depth scale {cfg['depth_scale']:.2f} "
             f"texels), one ray per covered pixel of a {cfg['image_size']}x{cfg['image_size']} "
             f"image, views {', '.join(f'{a} ({elev(a):g} deg)' for a in an)}, "
             f"engine {eng}; {cfg['rays_total']:,} rays per method; {cfg['seconds']:.1f} s. "
             "An iteration is one height read (CONVENTIONS); means are per covered pixel "
             "(hits and misses). The paper used 1024x768 images of 256x256 maps in its own "
             "scenes and camera, so only trends compare, not values.\n")
    rays_row = [[s] + [f"{R['rays'][s][a]:,}" for a in an] for s in sc]
    o.append("Rays per view:\n\n" + md_table(["scene"] + list(an), rays_row))

    o.append("\n## Table 2: probability of node crossing (%)\n")
    o.append("Crossings / iterations (the paper's measure: its Rocks row reproduces its own "
             "Table 4 as 8 descents + 1 final read + crossings). Ours / paper.\n\n")
    hdr = ["scene"] + [f"{ab(a)} {m}" for a in an for m in ("oh [10]", "tevs [12]")]
    rows = [[s] + [f"{fmt(100 * R['table2'][s][a][m]['p_cross'])} / "
                   f"{fmt(R['table2'][s][a][m]['paper_p_cross_pct'])}"
                   for a in an for m in TABLE2_METHODS] for s in sc]
    rows.append(["mean"] + [f"{fmt(100 * R['table2_mean_p_cross'][a][m])} / "
                            f"{fmt(mean([paper_t2(m, s, a) for s in sc]))}"
                            for a in an for m in TABLE2_METHODS])
    o.append(md_table(hdr, rows))
    o.append("\nAction breakdown of every method (% of iterations, mean over scenes): "
             "descent / crossing / final (hit or miss); level-ups per crossing.\n\n")
    rows = []
    for m in methods:
        cells = []
        for a in an:
            f = {k: mean([R["table2"][s][a][m][k] for s in sc])
                 for k in ("p_down", "p_cross", "p_end", "level_up_per_cross")}
            cells.append(f"{fmt(100 * f['p_down'])} / {fmt(100 * f['p_cross'])} / "
                         f"{fmt(100 * f['p_end'])}; {fmt(f['level_up_per_cross'], 2)}")
        rows.append([m] + cells)
    o.append(md_table(["method"] + list(an), rows))

    o.append("\n## Table 3: iterations of the multi-level descent, n levels\n")
    o.append("n levels down per descent until the first node crossing (clamped at level 0); no "
             "start level, no level-up. n = 1 is `oh`, n = 2 `multi-down`. Paper: Rocks only.\n\n")
    hdr = ["scene", "n"] + list(an) + [f"paper {ab(a)}" for a in an]
    rows = []
    for s in sc:
        best = {a: min(DESCENT_LEVELS, key=lambda n: R["table3"][s][a][str(n)]) for a in an}
        for n in DESCENT_LEVELS:
            cells = []
            for a in an:
                v = fmt(R["table3"][s][a][str(n)], 2)
                cells.append(f"**{v}**" if best[a] == n else v)
            paper = [fmt(PAPER_T3[n][ANGLES.index(a)]) if s == "rocks" and a in ANGLES else ""
                     for a in an]
            rows.append([s if n == 1 else "", str(n)] + cells + paper)
    o.append(md_table(hdr, rows))

    o.append("\n## Table 4: iterations per pixel\n")
    o.append("Ours / paper (paper: [10] = oh, [12] = tevs, (a) start-level, (b) multi-down, "
             "(c1) selective, (c2) coherent, a+b+c1 = park; drobot, park-gpu and park-xor have "
             "no paper column). Lowest of ours in bold.\n\n")
    for a in an:
        o.append(f"### {a}\n\n")
        rows = []
        low = {s: min(R["table4"][s][a].values()) for s in sc}
        for m in methods:
            cells = []
            for s in sc:
                v = R["table4"][s][a][m]
                txt = fmt(v, 2)
                if v == low[s]:
                    txt = f"**{txt}**"
                p = paper_t4(m, s, a)
                cells.append(txt + (f" / {fmt(p)}" if m in PAPER_T4 else ""))
            pm = [paper_t4(m, s, a) for s in sc]
            pmean = mean(pm) if m in PAPER_T4 and None not in pm else None
            cells.append(fmt(R["table4_mean"][a][m], 2) + (f" / {fmt(pmean)}" if pmean else ""))
            rows.append([m] + cells)
        o.append(md_table(["method"] + list(sc) + ["mean"], rows) + "\n")
    o.append("Notes on the paper column: " + " ".join(PAPER_T4_NOTES) + "\n")

    o.append("\n## Reduction of iterations (%)\n")
    o.append("100 (1 - a / b) per scene and view. The paper claims 16-65 % (park vs oh) and "
             "5-66 % (park vs tevs).\n\n")
    keys = ["park_vs_oh", "park_vs_tevs", "park-xor_vs_oh", "park-xor_vs_tevs",
            "paper_park_vs_oh", "paper_park_vs_tevs"]
    hdr = ["scene", "view"] + [k.replace("_vs_", " vs ").replace("_", " ") for k in keys]
    rows = [[s, a] + [fmt(R["reduction"][s][a][k]) for k in keys] for s in sc for a in an]
    rows.append(["range", ""] + [("–" if R["reduction_range"][k] is None else
                                  f"{fmt(R['reduction_range'][k][0])} to "
                                  f"{fmt(R['reduction_range'][k][1])}") for k in keys])
    o.append(md_table(hdr, rows))

    o.append(f"\n## Approximate methods against the exact hit ({R['approx_reference']})\n")
    if cfg.get("approx_error"):
        o.append(f"model.approx could not be imported: {cfg['approx_error']}\n")
    o.append("Means over scenes (max |dt|: max over scenes). |dt| and MSE (hit position, "
             "texel^2) over pixels where both hit; texel differs: % of pixels whose hit texel "
             "(or hit/miss) differs; PSNR of a nearest-texel texture lookup at the hit (misses "
             "black) against the exact image.\n\n")
    hdr = ["view", "method", "iterations", "mean abs dt", "max abs dt", "texel differs %",
           "hit/miss differs %", "MSE uv", "PSNR dB"]
    rows = []
    for a in an:
        for m in ("oh", REFERENCE):
            rows.append([a, f"{m} (exact)", fmt(R["table4_mean"][a][m], 2), "0", "0", "0", "0",
                         "0", "inf"])
        for n, r in R["approx_mean"][a].items():
            if "error" in r:
                rows.append([a, n, "error: " + r["error"]] + [""] * 6)
                continue
            rows.append([a, n, fmt(r["iterations"], 2), fmt(r["mean_abs_dt"], 4),
                         fmt(r["max_abs_dt"], 3), fmt(r["texel_differs_pct"], 2),
                         fmt(r["hit_mismatch_pct"], 2), fmt(r["mse_uv"], 3),
                         fmt(r["psnr_texture_db"], 1)])
    o.append(md_table(hdr, rows))
    errs = sorted({f"{n}: {v['error']}" for s in sc for a in an
                   for n, v in R["approx"][s][a].items() if "error" in v})
    if errs:
        o.append("\nErrors: " + "; ".join(errs) + "\n")

    o.append("\n## Engines: f24 against f64\n")
    o.append("% of pixels with the same hit texel (or both missing) and % with the same "
             "iteration count, for `park`:\n\n")
    hdr = ["scene"] + [f"{ab(a)} texel" for a in an] + [f"{ab(a)} iters" for a in an]
    rows = [[s] + [fmt(100 - R["engine"][s][a]["park"]["texel_differs_pct"], 3) for a in an]
            + [fmt(R["engine"][s][a]["park"]["iterations_equal_pct"], 3) for a in an]
            for s in sc]
    o.append(md_table(hdr, rows))
    o.append("\nEvery exact method, worst case over scenes and views:\n\n")
    rows = [[m, fmt(v["min_texel_agree_pct"], 3), fmt(v["min_iterations_equal_pct"], 3),
             f"{v['max_abs_dt']:.2e}"] for m, v in R["engine_summary"].items()]
    o.append(md_table(["method", "min texel agree %", "min iterations equal %", "max abs dt"],
                      rows))
    o.append("\n![iterations per method and view](study.png)\n")
    path.write_text("\n".join(block.strip("\n") + "\n" for block in o))


def write_png(path: Path, cfg: dict[str, Any], R: dict[str, Any]) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sc, an = cfg["scenes"], cfg["angles"]
    methods = list(traverse.METHODS)
    fig, axes = plt.subplots(1, len(an), figsize=(4.2 * len(an) + 1, 4.6), squeeze=False)
    x = np.arange(len(methods))
    for ax, a in zip(axes[0], an):
        per_scene = np.array([[R["table4"][s][a][m] for m in methods] for s in sc])
        ax.bar(x, per_scene.mean(axis=0), color="#4c78a8", label="ours (mean over scenes)")
        for row in per_scene:
            ax.plot(x, row, ".", color="#222222", ms=3, alpha=0.5)
        pm = [[paper_t4(m, s, a) for s in sc] for m in methods]
        px = [i for i, v in enumerate(pm) if methods[i] in PAPER_T4 and None not in v]
        if px:
            ax.plot(px, [float(np.mean(pm[i])) for i in px], "D", color="#e45756", ms=5,
                    label="paper (same scenes)")
        ax.set_xticks(x, methods, rotation=60, ha="right", fontsize=8)
        ax.set_title(f"{a} ({elev(a):g} deg)")
        ax.grid(axis="y", alpha=0.3)
    axes[0][0].set_ylabel("iterations per pixel")
    axes[0][-1].legend(fontsize=7, loc="upper right")
    fig.suptitle(f"Iterations per method and view: {len(sc)} scenes, map {cfg['size']}, "
                 f"image {cfg['image_size']}, engine {cfg['engine']}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def clean_json(x: Any) -> Any:
    if isinstance(x, dict):
        return {str(k): clean_json(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [clean_json(v) for v in x]
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    return x


def summary(cfg: dict[str, Any], R: dict[str, Any], out: Path) -> str:
    an = cfg["angles"]
    w = max(9, *(len(a) + 2 for a in an))
    lines = [f"study: {len(cfg['scenes'])} scenes x {len(an)} views, map {cfg['size']}, "
             f"image {cfg['image_size']}, engine {cfg['engine']}, {cfg['rays_total']:,} rays "
             f"per method, {cfg['seconds']:.1f} s"]
    lines.append("mean iterations per pixel".ljust(28) + "".join(a.rjust(w) for a in an))
    for m in ("oh", "tevs", "multi-down", "selective", "park", "park-gpu", "park-xor"):
        lines.append(f"  {m}".ljust(28) + "".join(fmt(R['table4_mean'][a][m], 2).rjust(w)
                                                 for a in an))
    for k in ("park_vs_oh", "park_vs_tevs", "park-xor_vs_oh", "park-xor_vs_tevs"):
        lines.append(f"  {k.replace('_vs_', ' vs ')} %".ljust(28) +
                     "".join(fmt(R['reduction_of_means'][a][k]).rjust(w) for a in an))
    for m in TABLE2_METHODS:
        lines.append(f"  P(crossing) {m} %".ljust(28) +
                     "".join(fmt(100 * R['table2_mean_p_cross'][a][m]).rjust(w) for a in an))
    for k, claim in PAPER_CLAIM.items():
        r = R["reduction_range"][k]
        if r:
            lines.append(f"{k.replace('_vs_', ' vs ')}: {r[0]:.0f} to {r[1]:.0f} % per scene/view "
                         f"(paper: {claim[0]:.0f} to {claim[1]:.0f} %)")
    best = {a: min(DESCENT_LEVELS, key=lambda n: mean([R["table3"][s][a][str(n)]
                                                       for s in cfg["scenes"]]) or 0)
            for a in an}
    lines.append("best descent depth n (mean over scenes): " +
                 ", ".join(f"{a} {best[a]}" for a in an))
    agree = min(v["min_texel_agree_pct"] for v in R["engine_summary"].values())
    lines.append(f"f24 vs f64: hit texel agreement >= {agree:.3f} % (every exact method)")
    lines.append(f"wrote {out / 'study.md'}, {out / 'study.json'}, {out / 'study.png'}")
    return "\n".join(lines)


# ---- command line ---------------------------------------------------------------------------

def parse_list(ap: Parser, what: str, text: str | None, valid: tuple[str, ...] | None,
               default: tuple[str, ...]) -> list[str]:
    if text is None:
        return list(default)
    items = [t.strip() for t in text.split(",") if t.strip()]
    if not items:
        ap.error(f"--{what}: empty list")
    if what == "scenes" and items == ["all"]:
        return list(scenes.SCENES)
    out = []
    for it in items:
        if what == "scenes":
            if it not in (valid or ()):
                ap.error(f"unknown scene {it!r} (valid: {', '.join(valid or ())}, or all)")
        else:
            try:
                camera.elevation(it if it in camera.VIEWS else float(it))
            except ValueError:
                ap.error(f"bad angle {it!r} (valid: {', '.join(camera.VIEWS)} or an elevation "
                         "in (0, 90] degrees)")
        if it in out:
            ap.error(f"--{what}: {it!r} given twice")
        out.append(it)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help=f"small fast run (map {QUICK['size']}, image {QUICK['image_size']}, "
                         f"scenes {','.join(QUICK['scenes'])}); explicit options still apply")
    ap.add_argument("--out", type=Path, default=Path("out/study"), help="output directory")
    ap.add_argument("--size", type=int, help=f"map size N (N x N), default {FULL['size']}")
    ap.add_argument("--image-size", type=int,
                    help=f"camera image size (square), default {FULL['image_size']}")
    ap.add_argument("--scenes", help="comma-separated scenes, or all (default all): "
                    + ", ".join(scenes.SCENES))
    ap.add_argument("--angles", help="comma-separated views (default front,oblique,grazing) or "
                    "elevations in degrees")
    ap.add_argument("--engine", default="f64", choices=("f64", "f24"),
                    help="engine of tables 2-4 (default f64)")
    ap.add_argument("--quiet", action="store_true", help="no progress on stderr")
    args = ap.parse_args(argv)

    d = QUICK if args.quick else FULL
    size = d["size"] if args.size is None else args.size
    image = d["image_size"] if args.image_size is None else args.image_size
    if not 2 <= size <= 4096:
        ap.error(f"--size must be in [2, 4096], got {size}")
    if not 4 <= image <= 4096:
        ap.error(f"--image-size must be in [4, 4096], got {image}")
    sc = parse_list(ap, "scenes", args.scenes, scenes.SCENES, d["scenes"])
    an = parse_list(ap, "angles", args.angles, None, d["angles"])
    out: Path = args.out
    if out.exists() and not out.is_dir():
        fail(PROG, f"--out is not a directory: {out}")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        fail(PROG, f"cannot create {out}: {e.strerror or e}")

    t0 = time.time()
    counted = Counted()
    approx, approx_error = approx_registry()
    views: dict[str, dict[str, dict[str, Any]]] = {}
    per_view = len(traverse.METHODS) + len(DESCENT_LEVELS) + len(approx)
    prog = Progress("study (methods traced)", len(sc) * len(an) * per_view,
                    enabled=not args.quiet)
    done = 0

    def tick() -> None:
        nonlocal done
        done += 1
        prog.update(done)
    rays_total = 0
    depth = camera.depth_scale(size, size)
    for s in sc:
        scene = scenes.load_scene(s, size)
        pyr = heightmap.build(scene.heights)
        views[s] = {}
        for a in an:
            rays = camera.Camera.for_view(view_arg(a), size, size, image, image).rays().rays
            rays_total += len(rays)
            views[s][a] = study_view(pyr, scene, rays, args.engine, counted, approx, tick)
    cfg = {"size": size, "image_size": image, "scenes": sc, "angles": an, "engine": args.engine,
           "quick": bool(args.quick), "depth_scale": depth, "rays_total": rays_total,
           "approx_error": approx_error,
           "methods": list(traverse.METHODS), "descent_levels": list(DESCENT_LEVELS),
           "approx_methods": list(approx), "seconds": 0.0}
    R = aggregate(views, cfg)
    cfg["seconds"] = time.time() - t0
    paper = {"table2_p_cross_pct": PAPER_T2, "table3_rocks": {str(k): v for k, v in PAPER_T3.items()},
             "table4": PAPER_T4, "table4_notes": PAPER_T4_NOTES, "claims_pct": PAPER_CLAIM,
             "angles": list(ANGLES)}
    doc = clean_json({"config": cfg, "paper": paper, **R})
    (out / "study.json").write_text(json.dumps(doc, indent=1, allow_nan=False) + "\n")
    write_md(out / "study.md", cfg, R)
    write_png(out / "study.png", cfg, R)
    print(summary(cfg, R, out))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except StudyError as e:
        sys.stderr.write(f"{PROG}: internal error: {e}\n")
        sys.exit(1)
