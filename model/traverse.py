# SPDX-License-Identifier: Apache-2.0
"""The pyramidal traversals (Park et al. 2013, sections 2-4), written once for every engine.

One vectorised loop (all rays in lock-step, finished rays dropped each pass) runs every exact
method; the methods differ only in small pluggable policies (start level, descent, level-up), and
the arithmetic is injected (:mod:`model.arith`): the same code is the ``f64`` reference engine and
the ``f24`` engine, the bit-accurate specification of the traverse unit (``rtl/traverse/``).

Geometry (CONVENTIONS): the ray is at (u0 + du t, v0 + dv t) at depth t in [0, 1]; texel (i, j)
covers u in [j, j+1), v in [i, i+1) and is solid from depth 1 - h[i, j] down.  A node (k, cx, cy)
of level k covers u in [cx 2^k, (cx+1) 2^k) and likewise in v; its value H is the maximum height
below it, so nothing in it is above depth 1 - H (its "plane").

Boundaries, precisely.  The ray crosses the grid line u = b (an integer) at the time
``T(b) = (b - u0) * (1 / du)``, computed in the engine's arithmetic with the reciprocal taken once
per ray.  T depends only on b, never on the level, and is monotone in b; a ray on a boundary belongs
to the cell it is entering (cells are half-open in t: [T(entry), T(exit))).  Every decision below
is a comparison of t with such crossing times, so the traversal, at any level and in any order,
sees the same cell sequence as the texel-by-texel walk (``tests/reference_walk.py``), and returns
exactly its hit.  An axis with du = 0 (or 1/du not finite) never crosses; the cell is floor(u0).

One iteration = one height read.  At node (k, c) with the ray at time t:
  plane = 1 - H;  t_exit = min over axes of T(exit boundary);  t_new = max(t, plane)
  - t_new < min(t_exit, t_map): the ray meets the node's box inside the node:
      level 0: hit at t_new;  else descend (policy) into the child that holds the ray at t_new.
  - else if t_map <= t_exit: the ray leaves the map first: miss.
  - else node crossing: t = max(t, t_exit), step to the neighbour (both axes at a corner), then
    maybe level up (policy).
``t_map`` is the time the ray leaves the map's own extent [0, W) x [0, H) (a convex box, so it never
comes back); the padding of the power-of-two pyramid is never entered.

Termination.  t never decreases and every crossing passes at least one grid line not passed before,
so a ray makes at most W + H + 2 crossings, at most as many level-ups, and at most n + that many
descents: :func:`iteration_cap` bounds the iterations and the loop enforces it.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from .arith import ENGINES, Arith
from .heightmap import Pyramid
from .rays import Rays, TraceResult

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]
B = npt.NDArray[np.bool_]

LEVEL_UP_POLICIES = ("none", "tevs", "drobot", "selective", "coherent")
DESCENT_POLICIES = ("one", "multi", "xor")


@dataclass(frozen=True)
class Method:
    """An exact pyramidal method: which start, descent and level-up policies it combines."""

    name: str
    start_level: bool = False  # (a) start at the lowest level where P and A share a node
    descent: str = "one"  # "one" | "multi" (b: two levels until the first crossing) | "xor"
    level_up: str = "none"  # "none" | "tevs" | "drobot" | "selective" (c1) | "coherent" (c2)
    clip: bool = False  # start below the root's plane (1 - H_root) before the start decision
    descent_levels: int = 2  # (b): levels per descent before the first crossing ("multi", "xor")
    doc: str = ""


METHODS: dict[str, Method] = {m.name: m for m in (
    Method("oh", doc="Oh 2006: root start, one-level descent, no level-up"),
    Method("tevs", level_up="tevs", doc="Tevs 2008: level-up when the parent changes"),
    Method("drobot", level_up="drobot", doc="Drobot 2010: level-up on every crossing"),
    Method("start-level", start_level=True, doc="oh + (a) start-level by XOR / leading zeros"),
    Method("multi-down", descent="multi", doc="oh + (b) two-level descent until the first crossing"),
    Method("selective", level_up="selective", doc="oh + (c1) selective level-up"),
    Method("coherent", level_up="coherent", doc="oh + (c2) coherent level-up"),
    Method("park", start_level=True, descent="multi", level_up="selective",
           doc="a + b + c1: the hardware default"),
    Method("park-gpu", start_level=True, descent="multi", level_up="coherent",
           doc="a + b + c2: the GPU variant"),
    Method("park-xor", start_level=True, descent="xor", level_up="selective", clip=True,
           descent_levels=3,
           doc="beyond the paper: every descent goes straight to the lowest level whose node "
               "holds the rest of the ray inside the current node (XOR of its two ends), at least "
               "three levels until the first crossing, and the start is clipped to the root's "
               "plane"),
)}

#: Method names of CONVENTIONS plus ours; the hardware implements all of them.
EXACT_METHODS: tuple[str, ...] = tuple(METHODS)
#: Method codes the RTL's configuration register uses (index in EXACT_METHODS).
METHOD_CODES: dict[str, int] = {m: i for i, m in enumerate(EXACT_METHODS)}


def iteration_cap(pyr: Pyramid) -> int:
    """An upper bound on the iterations of any ray (see the module docstring)."""
    return 2 * (pyr.width + pyr.height + 2) + 2 * pyr.n + 8


@dataclass
class RaySetup:
    """Per-ray quantities of the first mode (engine values), for the valid rays."""

    u0: F64
    v0: F64
    du: F64
    dv: F64
    inv_du: F64
    inv_dv: F64
    sx: I64  # direction of motion along u: +1, -1, or 0 (no crossing along u)
    sy: I64
    t_map: F64  # time of leaving the map's extent (inf if never)


def crossing_time(ar: Arith, b: npt.ArrayLike, p0: F64, inv: F64, s: I64) -> F64:
    """T(b) = (b - p0) * inv for moving axes; +inf where the axis does not move."""
    t = ar.mul(ar.sub(ar.from_int(b), p0), inv)
    return np.where(s != 0, t, np.inf)


def setup(pyr: Pyramid, rays: Rays, ar: Arith) -> tuple[B, RaySetup]:
    """Quantise the rays to the engine, flag invalid ones, and compute the per-ray constants."""
    u0, v0, du, dv = (ar.r(np.asarray(x, dtype=np.float64)) for x in (rays.u0, rays.v0, rays.du,
                                                                     rays.dv))
    invalid = Rays(u0, v0, du, dv).invalid(pyr.width, pyr.height)
    ok = ~invalid
    u0, v0, du, dv = u0[ok], v0[ok], du[ok], dv[ok]
    one = np.ones_like(u0)
    inv_du, inv_dv = ar.div(one, du), ar.div(one, dv)
    sx = np.where((du != 0) & np.isfinite(inv_du), np.sign(du), 0).astype(np.int64)
    sy = np.where((dv != 0) & np.isfinite(inv_dv), np.sign(dv), 0).astype(np.int64)
    tmx = crossing_time(ar, np.where(sx > 0, pyr.width, 0), u0, inv_du, sx)
    tmy = crossing_time(ar, np.where(sy > 0, pyr.height, 0), v0, inv_dv, sy)
    return invalid, RaySetup(u0, v0, du, dv, inv_du, inv_dv, sx, sy, np.minimum(tmx, tmy))


def position(ar: Arith, p0: F64, d: F64, t: F64) -> F64:
    """p0 + d t (the hit-position calculation)."""
    return ar.add(p0, ar.mul(d, t))


def locate(ar: Arith, p0: F64, d: F64, inv: F64, s: I64, t: F64, level: I64, lo: I64,
           hi: I64) -> I64:
    """The cell of ``level`` that holds the ray at time t along one axis, within [lo, hi].

    An estimate from the position (floor(p0 + d t) >> level) is corrected by one cell with the
    crossing times of the estimated cell's two edges, so the answer is the exact one of the
    crossing-time rule whenever the estimate is within one cell (always, in both engines, for
    positions inside the map).  Axes that do not move use floor(p0).
    """
    return locate_parts(ar, p0, d, inv, s, t, level, lo, hi)[0]


def locate_parts(ar: Arith, p0: F64, d: F64, inv: F64, s: I64, t: F64, level: I64, lo: I64,
                 hi: I64) -> tuple[I64, B, I64]:
    """:func:`locate`'s cell, whether its exit check moved it (t at or after the estimate's exit
    crossing time, the cell one on), and the estimate that check started from.

    The ring makes the exit check of a descent on the ray's next pass (traverse_loop.sv,
    "Locate's exit check"): where it moves the cell, the ring reads the estimate's height once
    more than the iterations count (a "relocate").
    """
    p = np.where(s != 0, position(ar, p0, d, t), p0)
    c = np.clip(ar.to_index(p) >> level, lo, hi)
    entry = (c + (s < 0)) << level
    exit_ = (c + (s > 0)) << level
    t_entry = crossing_time(ar, entry, p0, inv, s)
    t_exit = crossing_time(ar, exit_, p0, inv, s)
    back = t_entry > t
    fwd = ~back & (t_exit <= t) & (np.clip(c + s, lo, hi) != c)
    est = np.where(back, np.clip(c - s, lo, hi), c)
    return np.where(fwd, c + s, est), fwd, est


def _bitlen(x: I64) -> I64:
    """Number of significant bits of non-negative integers (0 -> 0): 'levels minus leading zeros'."""
    out = np.zeros_like(x)
    v = x.copy()
    while np.any(v > 0):
        nz = v > 0
        out += nz
        v >>= 1
    return out


def start_node(c0x: I64, c0y: I64, ex: I64 | None, ey: I64 | None, width: int, height: int,
               n: int, xor: bool) -> tuple[B, I64, I64, I64]:
    """The first mode's start decision (the traverse unit's ``traverse_start_level``).

    (c0x, c0y) is the located level-0 start cell (one outside the padded map, -1 or N, where the
    ray starts off it), (ex, ey) the unclipped level-0 cell (floor) of the end point A, used only
    with the start-level policy (a) (``xor``).  Returns whether the start cell lies outside the
    map's own extent, the start level k (n, or with (a) the lowest level where the start and end
    cells, clipped to the padded map, share a node: the bit length of their XOR, at most n) and
    the start node (c0x >> k, c0y >> k) of the clipped start cell.
    """
    last = (1 << n) - 1
    outside = (c0x < 0) | (c0x >= width) | (c0y < 0) | (c0y >= height)
    c0x, c0y = np.clip(c0x, 0, last), np.clip(c0y, 0, last)
    if xor:
        assert ex is not None and ey is not None
        ax, ay = np.clip(ex, 0, last), np.clip(ey, 0, last)
        k = np.minimum(_bitlen(np.maximum(c0x ^ ax, c0y ^ ay)), n)
    else:
        k = np.zeros_like(c0x) + n
    return outside, k, c0x >> k, c0y >> k


def descent_level(descent: str, levels: int, k: I64, crossed: B, cx: I64 | None = None,
                  cy: I64 | None = None, ax: I64 | None = None, ay: I64 | None = None,
                  bx: I64 | None = None, by: I64 | None = None) -> I64:
    """The descent policy: the new level of rays descending from node (k, cx, cy), k >= 1.

    "one": k - 1.  "multi" (b): ``levels`` levels while the ray has not ``crossed`` a node yet,
    then one.  "xor": as multi, or lower: the lowest level whose node holds the rest of the ray
    inside this node, from the level-0 cells (floor, unclipped) of the ray at t_new (ax, ay) and at
    the node's exit (bx, by), both clipped to the node: the bit length of their XOR.  Never below 0.
    """
    if descent == "one":
        nk = k - 1
    else:
        nk = k - np.where(crossed, 1, np.minimum(levels, k))
        if descent == "xor":
            assert cx is not None and cy is not None and ax is not None and ay is not None
            assert bx is not None and by is not None
            lo, hi = cx << k, ((cx + 1) << k) - 1
            a_x, b_x = np.clip(ax, lo, hi), np.clip(bx, lo, hi)
            lo, hi = cy << k, ((cy + 1) << k) - 1
            a_y, b_y = np.clip(ay, lo, hi), np.clip(by, lo, hi)
            nk = np.minimum(_bitlen(np.maximum(a_x ^ b_x, a_y ^ b_y)), nk)
    return np.maximum(nk, 0)


def crossing_step(level_up: str, n: int, k: I64, cx: I64, cy: I64, stepx: I64, stepy: I64,
                  prev_cross: B, p1x: I64 | None = None,
                  p1y: I64 | None = None) -> tuple[I64, I64, I64, B]:
    """A node crossing: the neighbour, then the level-up policy.

    (stepx, stepy) is the move along each axis (s where that axis's exit is the node's exit, else
    0).  ``prev_cross``: the ray's last iteration was a crossing without level-up (coherent);
    (p1x, p1y): the level-0 cell (floor) where the ray meets this node's plane (selective only).
    Returns the new level, the new cell and whether the ray went up a level (never above n).
    """
    nx, ny = cx + stepx, cy + stepy
    if level_up == "none":
        cup = np.zeros(np.shape(k), dtype=bool)
    else:
        parent_changed = ((nx >> 1) != (cx >> 1)) | ((ny >> 1) != (cy >> 1))
        if level_up == "drobot":
            cup = np.ones(np.shape(k), dtype=bool)
        elif level_up == "tevs":
            cup = parent_changed
        elif level_up == "coherent":
            cup = parent_changed & prev_cross
        elif level_up == "selective":  # stay when the plane is met in the very next node
            assert p1x is not None and p1y is not None
            diff = np.maximum(np.abs((p1x >> k) - cx), np.abs((p1y >> k) - cy))
            cup = parent_changed & (diff != 1)
        else:
            raise ValueError(f"bad level-up policy {level_up!r}")
        cup &= k < n
    return k + cup, np.where(cup, nx >> 1, nx), np.where(cup, ny >> 1, ny), cup


def texel_offset(level_off: npt.ArrayLike, n: int, k: I64, cx: I64, cy: I64,
                 texel_size: int = 1) -> I64:
    """Where texel (cy, cx) of level k sits in the pyramid's storage.

    Level k starts at ``level_off[k]`` and is row-major with a row pitch of N >> k texels.  With
    :func:`_flat_levels`' offsets and size 1 this indexes the flat array the trace reads; with
    :meth:`Pyramid.level_offsets` (bytes) and the texel's byte size it is the byte offset from the
    base address that the traverse unit reads (``traverse_addr``; model/heightmap.py's layout).
    """
    return np.asarray(level_off, dtype=np.int64)[k] + (cy * ((1 << n) >> k) + cx) * texel_size


def _level_starts(pyr: Pyramid) -> I64:
    """Each level's first index in the flat array of all levels, and (last) the total size."""
    return np.cumsum([0] + [lv.size for lv in pyr.levels]).astype(np.int64)


def _flat_levels(pyr: Pyramid) -> tuple[npt.NDArray[np.int64], I64]:
    """All levels in one array (the memory layout's order) and each level's start index."""
    flat = np.concatenate([lv.ravel() for lv in pyr.levels]).astype(np.int64)
    return flat, _level_starts(pyr)[:-1]


def pyramid_texels(pyr: Pyramid) -> int:
    """Texels in all levels of the pyramid (the length of :func:`trace`'s ``touched``)."""
    return int(_level_starts(pyr)[-1])


def lines_touched(pyr: Pyramid, touched: npt.NDArray[np.bool_], line_bytes: int,
                  base: int = 0) -> int:
    """Distinct cache lines of ``line_bytes`` holding a texel marked in ``touched``, with the
    pyramid stored at byte address ``base`` (:meth:`Pyramid.level_offsets`): the line fills a
    cold cache cannot avoid for those reads (compulsory misses)."""
    flat_offs = _level_starts(pyr)
    byte_offs = pyr.level_offsets()
    bpt = pyr.bits // 8
    lines = []
    for k in range(len(pyr.levels)):
        idx = np.nonzero(touched[flat_offs[k]:flat_offs[k + 1]])[0].astype(np.int64)
        lines.append((base + byte_offs[k] + idx * bpt) // line_bytes)
    return int(np.unique(np.concatenate(lines)).size) if lines else 0


def trace(pyr: Pyramid, rays: Rays, method: str | Method = "park", engine: str | Arith = "f64",
          record: list[dict[str, Any]] | None = None,
          stats: dict[str, int] | None = None,
          touched: npt.NDArray[np.bool_] | None = None) -> TraceResult:
    """Trace rays through the pyramid with an exact method on an engine (``f64`` or ``f24``).

    ``record``, when given, receives one dict per iteration of ray 0 (level, cell, t, H, action):
    the step-by-step trace that lines up with the RTL's waves; a descent whose locate moved its
    estimate one cell on also has ``estimate`` (level, cx, cy: the node the ring reads once more
    before the next iteration).  ``stats``, when given, gets the counts of what the iterations
    did: ``down``, ``cross``, ``hit``, ``miss`` (one per iteration, so they sum to the
    iterations), ``up`` (the crossings that also went up a level) and ``relocate`` (the descents
    that go on whose locate moved the estimate one cell on by its exit check: the ring's redo
    passes, traverse_loop.sv's "Locate's exit check").
    ``touched``, when given (bool, one per texel of every level: :func:`pyramid_texels`), is set
    where an iteration read the texel (:func:`lines_touched` turns it into cache lines).
    """
    with np.errstate(all="ignore"):  # Inf and NaN are values of the datapath, not errors
        return _trace(pyr, rays, METHODS[method] if isinstance(method, str) else method,
                      ENGINES[engine] if isinstance(engine, str) else engine, record, stats,
                      touched)


def _trace(pyr: Pyramid, rays: Rays, m: Method, ar: Arith,
           record: list[dict[str, Any]] | None,
           stats: dict[str, int] | None,
           touched: npt.NDArray[np.bool_] | None = None) -> TraceResult:
    if m.descent not in DESCENT_POLICIES or m.level_up not in LEVEL_UP_POLICIES:
        raise ValueError(f"bad method {m}")
    nrays = len(rays)
    res = TraceResult.empty(nrays)
    invalid, S = setup(pyr, rays, ar)
    res.invalid[:] = invalid
    vidx = np.nonzero(~invalid)[0]
    nv = len(vidx)
    n = pyr.n
    N = pyr.size
    flat, offs = _flat_levels(pyr)
    one = np.ones(nv)
    zero_i = np.zeros(nv, dtype=np.int64)

    # ---- first mode: start time, start level, start cell -------------------------------------
    t0 = np.zeros(nv)
    if m.clip:
        h_root = ar.from_unorm(np.array([pyr.levels[n][0, 0]]), pyr.bits)
        t0 = np.maximum(t0, ar.sub(one, np.broadcast_to(h_root, (nv,))))
    gone = S.t_map <= t0  # leaves the map at once (e.g. u0 = 0 moving to -u), or above the top
    lo0, hi0 = zero_i, zero_i + (N - 1)
    c0x = locate(ar, S.u0, S.du, S.inv_du, S.sx, t0, zero_i, lo0 - 1, hi0 + 1)
    c0y = locate(ar, S.v0, S.dv, S.inv_dv, S.sy, t0, zero_i, lo0 - 1, hi0 + 1)
    ex = ey = None
    if m.start_level:  # (a): the end point A = P + D (or where the ray leaves the map, with clip)
        t_end = np.minimum(one, S.t_map) if m.clip else one
        ex = ar.to_index(np.where(S.sx != 0, position(ar, S.u0, S.du, t_end), S.u0))
        ey = ar.to_index(np.where(S.sy != 0, position(ar, S.v0, S.dv, t_end), S.v0))
    outside, k, cx, cy = start_node(c0x, c0y, ex, ey, pyr.width, pyr.height, n, m.start_level)
    gone |= outside

    # ---- second mode: the iterative search, all rays in lock-step ----------------------------
    t = t0.copy()
    crossed = np.zeros(nv, dtype=bool)
    prev_cross = np.zeros(nv, dtype=bool)
    iters = np.zeros(nv, dtype=np.int64)
    hit_t = np.full(nv, np.nan)
    hit = np.zeros(nv, dtype=bool)
    act = np.nonzero(~gone)[0]
    cap = iteration_cap(pyr)
    while act.size:
        kk, xx, yy, tt = k[act], cx[act], cy[act], t[act]
        u0, v0, du, dv = S.u0[act], S.v0[act], S.du[act], S.dv[act]
        ix, iy, sx, sy, tmap = S.inv_du[act], S.inv_dv[act], S.sx[act], S.sy[act], S.t_map[act]
        ones = one[: act.size]
        fi = texel_offset(offs, n, kk, xx, yy)
        code = flat[fi]
        if touched is not None:
            touched[fi] = True
        iters[act] += 1
        h = ar.from_unorm(code, pyr.bits)
        plane = ar.sub(ones, h)
        tx = crossing_time(ar, (xx + (sx > 0)) << kk, u0, ix, sx)
        ty = crossing_time(ar, (yy + (sy > 0)) << kk, v0, iy, sy)
        t_exit = np.minimum(tx, ty)
        t_new = np.maximum(tt, plane)
        inside = t_new < np.minimum(t_exit, tmap)
        miss = ~inside & (tmap <= t_exit)
        is_hit = inside & (kk == 0)
        down = inside & (kk > 0)
        cross = ~inside & ~miss

        # Descent (policy), for the rays that descend: the new level, then the child that holds
        # the ray at t_new.
        di = np.nonzero(down)[0]
        relocate = 0
        est0: tuple[int, int, int] | None = None
        if di.size:
            dk, dxx, dyy, dt = kk[di], xx[di], yy[di], t_new[di]
            du_, dv_, du0, dv0 = du[di], dv[di], u0[di], v0[di]
            dix, diy, dsx, dsy = ix[di], iy[di], sx[di], sy[di]
            a_x = a_y = b_x = b_y = None
            if m.descent == "xor":  # the ray's cells at t_new and at the node's exit
                t_end = np.minimum(np.minimum(t_exit[di], tmap[di]), ones[: di.size])
                a_x = ar.to_index(np.where(dsx != 0, position(ar, du0, du_, dt), du0))
                b_x = ar.to_index(np.where(dsx != 0, position(ar, du0, du_, t_end), du0))
                a_y = ar.to_index(np.where(dsy != 0, position(ar, dv0, dv_, dt), dv0))
                b_y = ar.to_index(np.where(dsy != 0, position(ar, dv0, dv_, t_end), dv0))
            nk = descent_level(m.descent, m.descent_levels, dk, crossed[act[di]], dxx, dyy,
                               a_x, a_y, b_x, b_y)
            d = dk - nk
            nxd, fx, ex_ = locate_parts(ar, du0, du_, dix, dsx, dt, nk, dxx << d,
                                        ((dxx + 1) << d) - 1)
            nyd, fy, ey_ = locate_parts(ar, dv0, dv_, diy, dsy, dt, nk, dyy << d,
                                        ((dyy + 1) << d) - 1)
            reloc = (fx | fy) & (iters[act[di]] < cap)  # (a capped descent reads no more)
            relocate = int(np.count_nonzero(reloc))
            if record is not None and act[0] == 0 and di[0] == 0 and reloc[0]:
                est0 = (int(nk[0]), int(ex_[0]), int(ey_[0]))
            g = act[di]
            k[g], cx[g], cy[g], t[g] = nk, nxd, nyd, dt
            prev_cross[g] = False

        # Node crossing, for the rays that cross: step to the neighbour, then the level-up policy.
        ci = np.nonzero(cross)[0]
        up = np.zeros(act.size, dtype=bool)
        if ci.size:
            ck, cxx, cyy, csx, csy = kk[ci], xx[ci], yy[ci], sx[ci], sy[ci]
            te = t_exit[ci]
            p1x = p1y = None
            if m.level_up == "selective":  # P1: where the ray meets this node's plane
                cpl = plane[ci]
                p1x = ar.to_index(np.where(csx != 0, position(ar, u0[ci], du[ci], cpl), u0[ci]))
                p1y = ar.to_index(np.where(csy != 0, position(ar, v0[ci], dv[ci], cpl), v0[ci]))
            nck, ncx, ncy, cup = crossing_step(m.level_up, n, ck, cxx, cyy,
                                               np.where(tx[ci] == te, csx, 0),
                                               np.where(ty[ci] == te, csy, 0),
                                               prev_cross[act[ci]], p1x, p1y)
            up[ci] = cup
            g = act[ci]
            k[g], cx[g], cy[g] = nck, ncx, ncy
            t[g] = np.maximum(tt[ci], te)
            crossed[g] = True
            prev_cross[g] = ~cup

        if record is not None and act[0] == 0:
            action = ("hit" if is_hit[0] else "down" if down[0] else "miss" if miss[0] else
                      "cross-up" if up[0] else "cross")
            record.append({"iteration": int(iters[0]), "level": int(kk[0]), "cx": int(xx[0]),
                           "cy": int(yy[0]), "t": float(tt[0]), "H": float(h[0]),
                           "plane": float(plane[0]), "t_exit": float(t_exit[0]),
                           "t_new": float(t_new[0]), "action": action})
            if est0 is not None:
                record[-1]["estimate"] = {"level": est0[0], "cx": est0[1], "cy": est0[2]}

        if stats is not None:
            for key, cnt in (("down", di.size), ("cross", ci.size), ("up", int(up.sum())),
                             ("hit", int(is_hit.sum())), ("miss", int(miss.sum())),
                             ("relocate", relocate)):
                stats[key] = stats.get(key, 0) + cnt

        hit[act] |= is_hit
        hit_t[act] = np.where(is_hit, t_new, hit_t[act])
        done = is_hit | miss | (iters[act] >= cap)
        act = act[~done]

    u = np.where(hit, position(ar, S.u0, S.du, np.nan_to_num(hit_t)), np.nan)
    v = np.where(hit, position(ar, S.v0, S.dv, np.nan_to_num(hit_t)), np.nan)
    res.t[vidx] = hit_t
    res.u[vidx] = u
    res.v[vidx] = v
    res.hit[vidx] = hit
    res.iterations[vidx] = iters
    return res
