# SPDX-License-Identifier: Apache-2.0
"""The view-calculation unit (Park et al. 2013, Fig. 6, the stage before FIFO #0): a fragment's
world view vector into tangent space, scaled to the contract ray.

The op sequence of the hardware (``rtl/pipe/view_calc.sv`` mirrors it), in the injected
arithmetic (:mod:`model.arith`; ``f24`` is the RTL's specification):

    inputs: T, B, N the columns of the triangle's TBN matrix, V the unit world view vector (from
            the eye towards the surface), D the depth scale (texels per unit depth)
    1. x = dot(T, V);  y = dot(B, V);  z = dot(N, V)
           dot(a, b) = add(add(mul(ax, bx), mul(ay, by)), mul(az, bz))
    2. down = neg(z)                          exact
    3. k = div(D, down)                       the unit's one divider
    4. du = mul(x, k);  dv = mul(y, k);  seg = k
    5. where not (down > 0) -- a view that does not point into the surface, or NaN --
       du = dv = seg = NaN, which the traverse unit turns into an invalid ray

(du, dv) is the ray's movement in texels per unit of depth t (``model.rays``), and seg the world
length of the eye ray per unit of t (D / |N . V| for a unit V), which the MIP-level unit
accumulates into the ray length Pl = Pl0 + t * seg.  With a V that is not unit length seg is
scaled by |V|: the rasteriser hands over unit vectors.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from .arith import Arith

F64 = npt.NDArray[np.float64]


class ViewOut(NamedTuple):
    """Per fragment: the ray (du, dv) and seg, engine values (NaN where the view is unusable)."""

    du: F64
    dv: F64
    seg: F64


def _dot(ar: Arith, a: list[F64], b: list[F64]) -> F64:
    return ar.add(ar.add(ar.mul(a[0], b[0]), ar.mul(a[1], b[1])), ar.mul(a[2], b[2]))


@np.errstate(all="ignore")  # NaN / Inf are ordinary values (model.arith)
def view_calc(ar: Arith, tbn: npt.ArrayLike, view: npt.ArrayLike, depth_scale: float) -> ViewOut:
    """The op sequence above for N fragments: ``tbn`` (N, 3, 3) with columns T, B, N, ``view``
    (N, 3); every input is rounded once to the engine first (the fragment stream's format)."""
    m = np.asarray(tbn, dtype=np.float64)
    v = np.asarray(view, dtype=np.float64)
    if m.ndim != 3 or m.shape[1:] != (3, 3) or v.ndim != 2 or v.shape[1] != 3 \
            or m.shape[0] != v.shape[0]:
        raise ValueError(f"tbn must be (N, 3, 3) and view (N, 3), got {m.shape} and {v.shape}")
    n = v.shape[0]
    vv = [ar.r(v[:, i]) for i in range(3)]
    col = [[ar.r(m[:, i, c]) for i in range(3)] for c in range(3)]  # col[c] = (T|B|N)[0..2]
    x, y, z = (_dot(ar, col[c], vv) for c in range(3))
    down = -z
    k = ar.div(ar.r(np.full(n, float(depth_scale))), down)
    ok = down > 0.0
    nan = np.full(n, np.nan)
    return ViewOut(np.where(ok, ar.mul(x, k), nan), np.where(ok, ar.mul(y, k), nan),
                   np.where(ok, k, nan))
