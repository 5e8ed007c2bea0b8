# SPDX-License-Identifier: Apache-2.0
"""The texel-by-texel reference walk that proves the pyramidal traversals exact.

It visits every level-0 texel the ray passes, in order, and stops at the first one whose solid
part the ray meets: hit at max(t_enter, 1 - h) when that is before the texel's exit.  It shares
only the definition of a crossing time and the ray set-up with ``model/traverse.py`` (the rule
that makes "the cell at time t" well defined), not the traversal.
"""
from __future__ import annotations

import numpy as np

from model.arith import ENGINES
from model.heightmap import Pyramid
from model.rays import Rays, TraceResult
from model.traverse import crossing_time, setup


def walk(pyr: Pyramid, rays: Rays, engine: str = "f64") -> TraceResult:
    with np.errstate(all="ignore"):
        return _walk(pyr, rays, engine)


def _walk(pyr: Pyramid, rays: Rays, engine: str) -> TraceResult:
    ar = ENGINES[engine]
    res = TraceResult.empty(len(rays))
    invalid, S = setup(pyr, rays, ar)
    res.invalid[:] = invalid
    vidx = np.nonzero(~invalid)[0]
    nv = len(vidx)
    # Start texel at t = 0 by the crossing-time rule: floor(u0), except a ray moving to -u from
    # an integer u0 is already in the texel to the left.
    cx = np.floor(S.u0).astype(np.int64)
    cy = np.floor(S.v0).astype(np.int64)
    cx -= (S.sx < 0) & (S.u0 == np.floor(S.u0))
    cy -= (S.sy < 0) & (S.v0 == np.floor(S.v0))
    t = np.zeros(nv)
    hit = np.zeros(nv, dtype=bool)
    hit_t = np.full(nv, np.nan)
    iters = np.zeros(nv, dtype=np.int64)
    codes = pyr.codes.astype(np.int64)
    act = np.nonzero((S.t_map > 0) & (cx >= 0) & (cy >= 0))[0]
    one = np.ones(nv)
    while act.size:
        x, y, tt = cx[act], cy[act], t[act]
        h = ar.from_unorm(codes[y, x], pyr.bits)
        iters[act] += 1
        plane = ar.sub(one[: act.size], h)
        tx = crossing_time(ar, x + (S.sx[act] > 0), S.u0[act], S.inv_du[act], S.sx[act])
        ty = crossing_time(ar, y + (S.sy[act] > 0), S.v0[act], S.inv_dv[act], S.sy[act])
        t_exit = np.minimum(tx, ty)
        t_new = np.maximum(tt, plane)
        tmap = S.t_map[act]
        is_hit = t_new < np.minimum(t_exit, tmap)
        leave = ~is_hit & (tmap <= t_exit)
        move = ~is_hit & ~leave
        hit[act] |= is_hit
        hit_t[act] = np.where(is_hit, t_new, hit_t[act])
        cx[act] = x + np.where(move & (tx == t_exit), S.sx[act], 0)
        cy[act] = y + np.where(move & (ty == t_exit), S.sy[act], 0)
        t[act] = np.where(move, np.maximum(tt, t_exit), tt)
        act = act[move]
    res.t[vidx] = hit_t
    res.u[vidx] = np.where(hit, ar.add(S.u0, ar.mul(S.du, np.nan_to_num(hit_t))), np.nan)
    res.v[vidx] = np.where(hit, ar.add(S.v0, ar.mul(S.dv, np.nan_to_num(hit_t))), np.nan)
    res.hit[vidx] = hit
    res.iterations[vidx] = iters
    return res
