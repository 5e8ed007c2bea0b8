# SPDX-License-Identifier: Apache-2.0
"""MIP-level selection after Park et al., IEICE Electronics Express 2011: the model's one place for it.

The algorithm is written once, where the rest of the model already uses it; this module gathers
it, documents it as a whole and adds the hardware's view of it (``rtl/mip/mip_level.sv``,
``rtl/mip/tri_table.sv``).  Nothing here recomputes what those functions compute.

Pre-processing, once per triangle and texture (:func:`log2_pb` = ``model.camera.log2_pb``, in
float64 on the host; the five steps of the paper's Section 4):

    1. texels in the triangle:      T_XN = |s0 t1 + s1 t2 + s2 t0 - t0 s1 - t1 s2 - t2 s0| / 2
                                           * RES_texture          (RES_texture = Wt Ht)
    2. texture-to-screen ratio:     X_PR = 1 / RES_screen          (pixels per unit image-plane
                                                                    area at unit distance)
    3. texels in screen terms:      T_XS = T_XN X_PR
    4. the triangle's world area:   T_size = |(P1 - P0) x (P2 - P0)| / 2
    5. log2(Pb) = 1/2 log2(T_size / T_XS)
       (the reciprocal of the ratio printed in the paper; ``model.camera.log2_pb`` explains why)

The driver rounds each log2(Pb) to f24 once (:func:`table_words`) and writes it into the
triangle table: word ``{triangle, texture}``, texture 0 the colour texture, 1 the normal map.

Per hit, in the injected arithmetic (``f24`` is the RTL's specification):

    Pl  = add(Pl0, mul(t, seg))                      :func:`ray_length` (model.texture)
    lod = sub(log2(Pl), log2Pb[tri])                 :func:`mip_level` (model.texture); log2 is
    L   = clamp(to_index(add(lod, 0.5)), 0, levels - 1)  the approximate unit f24_log2 in f24
    L   = 0 with MIP mapping off (``mip=False``)

Pl0 is the eye-to-entry length from the rasteriser, seg the view unit's k (``model.view``), t
the hit depth, levels the texture's MIP level count (``Texture.n_levels``).  to_index is the
engine's floor, saturating to +-2^19 in f24 (``model.arith.INDEX_W``) with NaN -> 0, so a NaN
t, Pl0 or seg, a negative or NaN Pl and Pl = 0 (log2 = -Inf) all give level 0, Pl = +Inf gives
levels - 1.  :func:`level` is this per-hit sequence as one call (the composition
``model.shade.render_pixels`` uses); ``rtl/mip/mip_level.sv`` computes it for both textures of
a hit, one after the other on one datapath (a hit every other clock at most).
"""
from __future__ import annotations

import numpy as np
import numpy.typing as npt

from . import f24
from .arith import Arith
from .camera import log2_pb, mip_lod
from .texture import log2, mip_level, ray_length

__all__ = ["log2_pb", "mip_lod", "log2", "ray_length", "mip_level", "level", "table_words",
           "TEX_COLOUR", "TEX_NORMAL"]

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]
U32 = npt.NDArray[np.uint32]

#: Texture select bit of a triangle-table word address {triangle, texture}.
TEX_COLOUR = 0
TEX_NORMAL = 1


def level(ar: Arith, pl0: npt.ArrayLike, t: npt.ArrayLike, seg: npt.ArrayLike,
          log2pb: npt.ArrayLike, n_levels: int, mip: bool = True) -> I64:
    """The per-hit MIP level: ``mip_level(ar, ray_length(ar, pl0, t, seg), log2pb, n_levels)``,
    or 0 everywhere with ``mip=False``.  Inputs are engine values (already rounded)."""
    pl0a = np.asarray(pl0, dtype=np.float64)
    if not mip:
        return np.zeros(pl0a.shape, dtype=np.int64)
    pl = ray_length(ar, pl0a, np.asarray(t, dtype=np.float64), np.asarray(seg, dtype=np.float64))
    return mip_level(ar, pl, np.asarray(log2pb, dtype=np.float64), n_levels)


def table_words(log2pb_colour: npt.ArrayLike, log2pb_normal: npt.ArrayLike) -> U32:
    """The triangle table's contents: (T, 2) f24 patterns of log2(Pb) per triangle, column
    TEX_COLOUR / TEX_NORMAL (word address ``2 * triangle + texture``), each value rounded once
    (the f24 engine's ``ar.r`` of the float64 constant)."""
    c = np.asarray(log2pb_colour, dtype=np.float64)
    n = np.asarray(log2pb_normal, dtype=np.float64)
    if c.shape != n.shape or c.ndim != 1:
        raise ValueError(f"log2pb_colour and log2pb_normal must be 1-D of one length, "
                         f"got {c.shape} and {n.shape}")
    return np.stack([f24.from_float(c), f24.from_float(n)], axis=1)
