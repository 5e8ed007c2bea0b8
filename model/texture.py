# SPDX-License-Identifier: Apache-2.0
"""Colour textures and normal maps: unorm8 RGBA MIP chains, their memory layout, the bilinear lookup.

Storage.  A texture is stored as unorm8 RGBA texels (code k means k / 255).  RGB images get
A = 255; grey images are replicated to RGB.  A normal map is stored the same way with the usual
encoding ``code = round((n + 1) / 2 * 255)`` per component (``model.scenes.encode_normals``)
and A = 255.  Texel (i, j) of level 0 is row i, column j; its centre is at texture coordinate
(u, v) = (j + 0.5, i + 0.5) in level-0 texel units of the texture (the height map's convention:
texel (i, j) covers u in [j, j+1), v in [i, i+1)).

MIP chain (:func:`build`).  Level 0 is the image, W0 x H0 (any size, not necessarily square or
a power of two).  Level k+1 has W_{k+1} = ceil(W_k / 2) by H_{k+1} = ceil(H_k / 2) texels, down
to 1 x 1 (``levels = 1 + ceil(log2(max(W0, H0)))``).  Texel (i, j) of level k+1 is the box
filter of level k's texels (2i, 2j), (2i, 2j+1), (2i+1, 2j), (2i+1, 2j+1), with indices clamped
to the edge of level k (so an odd level's last row / column is counted twice in its parent),
in integers per channel: ``(a + b + c + d + 2) >> 2`` (round half up).  Each level is built
from the one below it, exactly as written: the chain is a pure function of the level-0 codes.
A level-k texel covers level-0 texels [2^k i, 2^k (i+1)) x [2^k j, 2^k (j+1)) (clipped to the
image), so level k's texel centre i + 0.5 sits at level-0 coordinate 2^k (i + 0.5).

Memory layout (what the hardware's texture cache reads over AXI, like ``model.heightmap``):
levels one after the other from level 0 to the 1 x 1 level, each row-major with a row pitch of
W_k texels (no row padding), 4 bytes per texel in the order R, G, B, A.  Every level starts on a
64-byte boundary: ``level_offsets()[k]`` is level k's byte offset from the texture's base, and
texel (i, j) of level k is at ``base + level_offsets()[k] + 4 (i W_k + j)``
(:meth:`Texture.address`).

Texture coordinates.  The traversal returns the hit (u, v) in level-0 texel units of the
*height map* (W x H).  A texture of another size (Wt x Ht) is addressed with
``u_t = u * (Wt / W)``, ``v_t = v * (Ht / H)``: each scale is one per-texture constant, the
engine's rounding of Wt / W (computed once by the driver: ``div(from_int(Wt), from_int(W))``),
and the multiplication is done per lookup (a multiplication by 1.0 when the sizes agree, exact).

MIP level (Park et al., IEICE Electronics Express 2011, eq. (2)).  Per hit:

    Pl  = add(Pl0, mul(t, seg))       ray length from the eye to the hit point (world = texels):
                                      Pl0 = eye to entry point, seg = world length per unit of
                                      depth t (D / |N . view|, the view unit's factor k)
    lod = sub(log2(Pl), log2Pb[tri])  log2Pb the per-triangle, per-texture constant of
                                      ``model.camera.log2_pb`` for this texture's Wt x Ht
    L   = clamp(to_index(add(lod, 0.5)), 0, levels - 1)      = clamp(floor(lod + 0.5), ...)

``log2`` is the engine's: numpy ``log2`` for f64, the hardware's approximate unit
(``model.f24.log2``, bit-exact with ``rtl/fp/f24_log2.sv``) for f24 (:func:`log2`).  With
``mip=False`` the level is always 0 (the "MIP-map off" case of the paper's hit-rate table).

Bilinear lookup at level L (:func:`sample`), in the engine's arithmetic, per lookup:

    1. ut = mul(u, su);  vt = mul(v, sv)                     (su, sv the texture's scales)
    2. x = sub(mul(ut, 2^-L), 0.5);  y = sub(mul(vt, 2^-L), 0.5)   (mul by 2^-L is exact)
    3. j0 = to_index(x);  i0 = to_index(y)                   (floor)
    4. fx = sub(x, from_int(j0));  fy = sub(y, from_int(i0))  (the weights, in [0, 1])
    5. j1 = j0 + 1, i1 = i0 + 1; clamp j0, j1 to [0, W_L - 1] and i0, i1 to [0, H_L - 1]
       (clamp-to-edge addressing, in integers)
    6. four reads: c00 = T[i0, j0], c01 = T[i0, j1], c10 = T[i1, j0], c11 = T[i1, j1]
       (RGBA codes), each channel converted with from_unorm(code, 8)
    7. per channel:  top = add(c00, mul(fx, sub(c01, c00)))
                     bot = add(c10, mul(fx, sub(c11, c10)))
                     out = add(top, mul(fy, sub(bot, top)))

The f24 engine of these steps is the exact specification of the hardware's texture address
calculation and filter; the f64 engine is the reference.  :func:`sample` is the composition of
:func:`lookup_addresses` (steps 1-5 and the four byte addresses ``base + level_offsets()[L] +
4 (i W_L + j)``: ``rtl/pipe/tex_addr.sv``), the four reads and :func:`filter_texels` (steps 6-7:
``rtl/pipe/tex_filter.sv``, which takes each texel as the little-endian 32-bit word of its four
bytes, R in bits 7:0, G 15:8, B 23:16, A 31:24).  At a texel centre the weights are 0
and the lookup returns that texel exactly (both engines); halfway between two texels it
returns their average (exactly in f64, rounded in f24).
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from . import f24
from .arith import Arith

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]
U8 = npt.NDArray[np.uint8]

#: Bytes per texel (RGBA unorm8) and the alignment of every level's start.
TEXEL_BYTES = 4
ALIGN = 64


class TextureError(ValueError):
    """A texture or normal map that cannot be used (unreadable file, wrong shape, empty)."""


# --------------------------------------------------------------------------------------------
# storage


def quantize(rgb: npt.ArrayLike) -> U8:
    """Colours in [0, 1] (H, W), (H, W, 1|3|4) -> unorm8 RGBA codes round(c * 255) (A = 255)."""
    a = np.asarray(rgb)
    if np.issubdtype(a.dtype, np.integer):
        if a.min(initial=0) < 0 or a.max(initial=0) > 255:
            raise TextureError("integer texels must be unorm8 codes (0..255)")
        codes = a.astype(np.uint8)
    else:
        codes = np.rint(np.clip(np.nan_to_num(a.astype(np.float64), nan=0.0), 0.0, 1.0)
                        * 255.0).astype(np.uint8)
    return to_rgba(codes)


def to_rgba(codes: npt.ArrayLike) -> U8:
    """unorm8 codes (H, W), (H, W, 1|2|3|4) -> (H, W, 4): grey replicated, A = 255 if absent."""
    c = np.asarray(codes, dtype=np.uint8)
    if c.ndim == 2:
        c = c[..., None]
    if c.ndim != 3 or c.shape[0] == 0 or c.shape[1] == 0 or c.shape[2] not in (1, 2, 3, 4):
        raise TextureError(f"a texture is a non-empty (H, W[, 1..4]) array, got shape {c.shape}")
    hh, ww, ch = c.shape
    out = np.full((hh, ww, 4), 255, dtype=np.uint8)
    if ch <= 2:  # grey (+ alpha)
        out[..., :3] = c[..., :1]
        if ch == 2:
            out[..., 3] = c[..., 1]
    else:
        out[..., :ch] = c
    return out


def downsample(lv: U8) -> U8:
    """One MIP step: ceil-halved size, 2 x 2 box filter with clamp-to-edge, (a+b+c+d+2) >> 2."""
    hh, ww = lv.shape[:2]
    h2, w2 = -(-hh // 2), -(-ww // 2)
    r0 = np.arange(h2) * 2
    r1 = np.minimum(r0 + 1, hh - 1)
    c0 = np.arange(w2) * 2
    c1 = np.minimum(c0 + 1, ww - 1)
    a = lv.astype(np.uint16)
    s = a[r0][:, c0] + a[r0][:, c1] + a[r1][:, c0] + a[r1][:, c1]
    return ((s + 2) >> 2).astype(np.uint8)


@dataclass
class Texture:
    """An unorm8 RGBA texture with its MIP chain; ``levels[k]`` is (H_k, W_k, 4) uint8."""

    levels: list[U8]

    @property
    def width(self) -> int:
        return int(self.levels[0].shape[1])

    @property
    def height(self) -> int:
        return int(self.levels[0].shape[0])

    @property
    def n_levels(self) -> int:
        return len(self.levels)

    def level_size(self, k: int) -> tuple[int, int]:
        """(W_k, H_k) of level k."""
        return int(self.levels[k].shape[1]), int(self.levels[k].shape[0])

    def level_offsets(self, align: int = ALIGN) -> list[int]:
        """Byte offset of each level from the base address (see the module docstring)."""
        offs, o = [], 0
        for lv in self.levels:
            offs.append(o)
            o += -(-(lv.shape[0] * lv.shape[1] * TEXEL_BYTES) // align) * align
        return offs

    def memory_size(self, align: int = ALIGN) -> int:
        """Total bytes of the memory image (the last level padded to the alignment too)."""
        lv = self.levels[-1]
        return self.level_offsets(align)[-1] + \
            -(-(lv.shape[0] * lv.shape[1] * TEXEL_BYTES) // align) * align

    def memory_image(self, align: int = ALIGN) -> bytes:
        """The MIP chain as the bytes the hardware reads (R, G, B, A per texel, row-major)."""
        buf = bytearray(self.memory_size(align))
        for o, lv in zip(self.level_offsets(align), self.levels):
            raw = np.ascontiguousarray(lv).tobytes()
            buf[o:o + len(raw)] = raw
        return bytes(buf)

    def address(self, level: npt.ArrayLike, i: npt.ArrayLike, j: npt.ArrayLike,
                align: int = ALIGN) -> I64:
        """Byte address (from the base) of texel (i, j) of ``level``, vectorised."""
        lvl = np.asarray(level, dtype=np.int64)
        offs = np.asarray(self.level_offsets(align), dtype=np.int64)
        widths = np.array([lv.shape[1] for lv in self.levels], dtype=np.int64)
        return offs[lvl] + TEXEL_BYTES * (np.asarray(i, np.int64) * widths[lvl]
                                          + np.asarray(j, np.int64))

    def scale_for(self, ar: Arith, map_w: int, map_h: int) -> tuple[F64, F64]:
        """The constants (su, sv) = engine(Wt / W), engine(Ht / H) for a map of W x H."""
        su = ar.div(ar.from_int(np.array([self.width])), ar.from_int(np.array([map_w])))
        sv = ar.div(ar.from_int(np.array([self.height])), ar.from_int(np.array([map_h])))
        return su, sv


def build(image: npt.ArrayLike) -> Texture:
    """A texture with its full MIP chain from colours in [0, 1] (float) or unorm8 codes (int)."""
    lv = quantize(image)
    levels = [lv]
    while lv.shape[0] > 1 or lv.shape[1] > 1:
        lv = downsample(lv)
        levels.append(lv)
    return Texture(levels)


def load_image(path: str | Path) -> F64:
    """Read an image through OpenImageIO as float (H, W, C) in [0, 1] (integer images normalised
    by their type's maximum, float images clamped), or a ``.npy`` array (same rules)."""
    p = Path(path)
    if not p.is_file():
        raise TextureError(f"image not found: {p}")
    if p.suffix.lower() == ".npy":
        try:
            a = np.load(p, allow_pickle=False)
        except Exception as e:
            raise TextureError(f"cannot read {p}: {e}".splitlines()[0]) from None
        if a.ndim not in (2, 3) or a.size == 0:
            raise TextureError(f"{p}: expected an (H, W[, C]) array, got shape {a.shape}")
        if np.issubdtype(a.dtype, np.integer):
            a = a.astype(np.float64) / float(np.iinfo(a.dtype).max)
        elif not np.issubdtype(a.dtype, np.floating):
            raise TextureError(f"{p}: unsupported dtype {a.dtype}")
        a = np.clip(np.nan_to_num(a.astype(np.float64), nan=0.0), 0.0, 1.0)
        return a if a.ndim == 3 else a[..., None]
    import OpenImageIO as oiio

    inp = oiio.ImageInput.open(str(p))
    if inp is None:
        raise TextureError(f"cannot read {p}: {oiio.geterror()}".splitlines()[0])
    try:
        spec = inp.spec()
        a = inp.read_image(0, 0, 0, min(spec.nchannels, 4), "float")
    finally:
        inp.close()
    if a is None or np.asarray(a).size == 0:
        raise TextureError(f"cannot read pixels of {p}")
    a = np.asarray(a, dtype=np.float64).reshape(spec.height, spec.width, -1)
    return np.clip(np.nan_to_num(a, nan=0.0), 0.0, 1.0)


# --------------------------------------------------------------------------------------------
# the engine's log2 and the MIP level


def log2(ar: Arith, x: npt.ArrayLike) -> F64:
    """log2 in the engine: numpy for f64, the approximate unit ``model.f24.log2`` for f24."""
    xa = np.asarray(x, dtype=np.float64)
    if ar.name == "f24":
        return f24.to_float(f24.log2(f24.from_float(xa)))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.log2(xa)


@np.errstate(all="ignore")  # NaN / Inf are ordinary values (model.arith)
def ray_length(ar: Arith, pl0: F64, t: F64, seg: F64) -> F64:
    """Pl = add(Pl0, mul(t, seg)): the eye-to-hit length (module docstring)."""
    return ar.add(pl0, ar.mul(t, seg))


@np.errstate(all="ignore")  # NaN / Inf are ordinary values (model.arith)
def mip_level(ar: Arith, pl: F64, log2pb: F64, n_levels: int) -> I64:
    """L = clamp(floor(log2(Pl) - log2Pb + 0.5), 0, n_levels - 1) in the engine."""
    lod = ar.sub(log2(ar, pl), ar.r(np.asarray(log2pb, dtype=np.float64)))  # the table's word
    return np.clip(ar.to_index(ar.add(lod, np.full_like(lod, 0.5))), 0, n_levels - 1)


# --------------------------------------------------------------------------------------------
# the bilinear lookup


class Lookup(NamedTuple):
    """The result of :func:`sample`: ``value`` (N, 4) engine values of R, G, B, A in [0, 1];
    ``addr`` (N, 4) byte addresses of the reads c00, c01, c10, c11 (or None)."""

    value: F64
    addr: I64 | None


class TexAddr(NamedTuple):
    """The result of :func:`lookup_addresses` (steps 1-5), what ``rtl/pipe/tex_addr.sv`` computes.

    ``addr`` (N, 4): byte addresses of c00, c01, c10, c11 (``base`` + :meth:`Texture.address`);
    ``fx``, ``fy`` (N,): the engine's weights; ``i0``, ``i1``, ``j0``, ``j1`` (N,): the clamped
    rows and columns of the four reads (c00 = (i0, j0), c01 = (i0, j1), c10 = (i1, j0),
    c11 = (i1, j1)); ``level`` (N,) the level of each lookup.  For a NaN coordinate the weight
    is NaN (index 0); for +-Inf or |x| >= 2^19 the index saturates and the weight may lie
    outside [0, 1] (e.g. +Inf, or x - 2^19), as the hardware computes it."""

    addr: I64
    fx: F64
    fy: F64
    i0: I64
    i1: I64
    j0: I64
    j1: I64
    level: I64


@np.errstate(all="ignore")  # NaN / Inf are ordinary values (model.arith)
def lookup_addresses(tex: Texture, ar: Arith, u: npt.ArrayLike, v: npt.ArrayLike,
                     level: npt.ArrayLike, scale: tuple[F64, F64] | None = None, base: int = 0,
                     align: int = ALIGN) -> TexAddr:
    """Steps 1-5 of the bilinear lookup (module docstring) for 1-D arrays ``u``, ``v``: the
    weights, the clamped texel indices and the four byte addresses (the texture at byte address
    ``base``).  ``ValueError`` for a level outside 0 .. n_levels - 1.  Only the levels' sizes are
    read, not their texels."""
    u = np.asarray(u, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64)
    lvl = np.broadcast_to(np.asarray(level, dtype=np.int64), u.shape)
    if lvl.size and (lvl.min() < 0 or lvl.max() >= tex.n_levels):
        raise ValueError(f"texture level out of range 0..{tex.n_levels - 1}")
    if scale is not None:
        u = ar.mul(u, scale[0])
        v = ar.mul(v, scale[1])
    half = np.full(u.shape, 0.5)
    inv = np.ldexp(1.0, -lvl)  # 2^-L: exact in both engines
    x = ar.sub(ar.mul(u, inv), half)
    y = ar.sub(ar.mul(v, inv), half)
    j0 = ar.to_index(x)
    i0 = ar.to_index(y)
    fx = ar.sub(x, ar.from_int(j0))
    fy = ar.sub(y, ar.from_int(i0))
    widths = np.array([lv.shape[1] for lv in tex.levels], dtype=np.int64)[lvl]
    heights = np.array([lv.shape[0] for lv in tex.levels], dtype=np.int64)[lvl]
    j1 = np.clip(j0 + 1, 0, widths - 1)
    i1 = np.clip(i0 + 1, 0, heights - 1)
    j0 = np.clip(j0, 0, widths - 1)
    i0 = np.clip(i0, 0, heights - 1)
    addr = base + np.stack([tex.address(lvl, i0, j0, align), tex.address(lvl, i0, j1, align),
                            tex.address(lvl, i1, j0, align), tex.address(lvl, i1, j1, align)],
                           axis=-1)
    return TexAddr(addr, fx, fy, i0, i1, j0, j1, np.asarray(lvl))


@np.errstate(all="ignore")  # NaN / Inf are ordinary values (model.arith)
def filter_texels(ar: Arith, texels: npt.ArrayLike, fx: npt.ArrayLike,
                  fy: npt.ArrayLike) -> F64:
    """Steps 6-7 of the bilinear lookup (module docstring), what ``rtl/pipe/tex_filter.sv``
    computes: ``texels`` (N, 4, C) unorm8 codes of the reads c00, c01, c10, c11 (C channels,
    R, G, B, A), ``fx``, ``fy`` (N,) the weights; returns the (N, C) filtered engine values."""
    t = np.asarray(texels)
    c00, c01, c10, c11 = (ar.from_unorm(t[:, k], 8) for k in range(4))
    fxc = np.asarray(fx, dtype=np.float64)[:, None]
    fyc = np.asarray(fy, dtype=np.float64)[:, None]
    top = ar.add(c00, ar.mul(fxc, ar.sub(c01, c00)))
    bot = ar.add(c10, ar.mul(fxc, ar.sub(c11, c10)))
    return ar.add(top, ar.mul(fyc, ar.sub(bot, top)))


def sample(tex: Texture, ar: Arith, u: npt.ArrayLike, v: npt.ArrayLike, level: npt.ArrayLike,
           scale: tuple[F64, F64] | None = None, with_addresses: bool = False) -> Lookup:
    """Bilinear lookup at integer ``level`` (per lookup) with clamp-to-edge addressing.

    ``u``, ``v`` are engine values in level-0 texel units of the height map (or of the texture
    when ``scale`` is None); ``scale`` = :meth:`Texture.scale_for`.  The steps are those of the
    module docstring, in the engine ``ar``: :func:`lookup_addresses` (steps 1-5, the hardware's
    address unit), the four reads, :func:`filter_texels` (steps 6-7, the hardware's filter).
    """
    la = lookup_addresses(tex, ar, u, v, level, scale)
    # All levels in one flat array (the memory layout's order, without the alignment gaps).
    flat, starts = _flat(tex)
    base = starts[la.level]
    widths = np.array([lv.shape[1] for lv in tex.levels], dtype=np.int64)[la.level]
    texels = np.stack([flat[base + i * widths + j] for i, j in
                       ((la.i0, la.j0), (la.i0, la.j1), (la.i1, la.j0), (la.i1, la.j1))], axis=1)
    out = filter_texels(ar, texels, la.fx, la.fy)
    return Lookup(out, la.addr if with_addresses else None)


_FLAT_CACHE: dict[int, tuple[Texture, U8, I64]] = {}


def _flat(tex: Texture) -> tuple[U8, I64]:
    """(texels, 4) of all levels concatenated, and each level's first texel index (cached)."""
    hit = _FLAT_CACHE.get(id(tex))
    if hit is not None and hit[0] is tex:
        return hit[1], hit[2]
    flat = np.concatenate([lv.reshape(-1, 4) for lv in tex.levels])
    starts = np.cumsum([0] + [lv.shape[0] * lv.shape[1] for lv in tex.levels[:-1]]).astype(np.int64)
    if len(_FLAT_CACHE) > 8:
        _FLAT_CACHE.clear()
    _FLAT_CACHE[id(tex)] = (tex, flat, starts)
    return flat, starts
