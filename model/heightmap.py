# SPDX-License-Identifier: Apache-2.0
"""Height maps: loading, quantisation, the max-mipmap pyramid and its memory layout.

Conventions (``docs/conventions.md``): ``h[row, col]`` in [0, 1], 1 is the top of the
displacement volume.  Texel (i, j) covers u in [j, j+1), v in [i, i+1) and is solid from depth
1 - h[i, j] down to depth 1.  Heights are stored as unorm8 (default) or unorm16 codes and every
engine traces the same quantised heights.

The pyramid is built over the map padded to a power-of-two square N = 2^n >= max(W, H) with
height 0 (padding is never hit: leaving the map's own extent is a miss).  Level k has
(N >> k) x (N >> k) texels; texel (i, j) of level k is the maximum of the level-0 block
rows [i 2^k, (i+1) 2^k) x columns [j 2^k, (j+1) 2^k); level n is the single root texel.

Memory layout (what the hardware's height cache reads over AXI): levels stored one after the
other from level 0 up to the root, each row-major with its own row pitch of (N >> k) texels,
one code per texel (1 byte for unorm8, 2 bytes little-endian for unorm16).  ``level_offsets``
gives each level's byte offset from the base; every level starts on a 64-byte boundary.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]


class HeightMapError(ValueError):
    """A height map that cannot be used (unreadable file, wrong shape, empty)."""


def load(path: str | Path) -> F64:
    """Read a height map: an image through OpenImageIO or a ``.npy`` array; returns h in [0, 1].

    Integer images are normalised by their type's maximum, float images are clamped to [0, 1],
    the first channel is used.
    """
    p = Path(path)
    if not p.is_file():
        raise HeightMapError(f"height map not found: {p}")
    if p.suffix.lower() == ".npy":
        try:
            a = np.load(p, allow_pickle=False)
        except Exception as e:  # numpy raises several kinds for a bad file
            raise HeightMapError(f"cannot read {p}: {e}") from None
        if a.ndim == 3:
            a = a[..., 0]
        if a.ndim != 2 or a.size == 0:
            raise HeightMapError(f"{p}: expected a 2-D array, got shape {a.shape}")
        if np.issubdtype(a.dtype, np.integer):
            return a.astype(np.float64) / float(np.iinfo(a.dtype).max)
        if not np.issubdtype(a.dtype, np.floating):
            raise HeightMapError(f"{p}: unsupported dtype {a.dtype}")
        return np.clip(np.nan_to_num(a.astype(np.float64), nan=0.0), 0.0, 1.0)
    import OpenImageIO as oiio

    inp = oiio.ImageInput.open(str(p))
    if inp is None:
        raise HeightMapError(f"cannot read {p}: {oiio.geterror()}")
    try:
        spec = inp.spec()
        native = spec.format.basetype
        is_float = native in (oiio.FLOAT, oiio.HALF, oiio.DOUBLE)
        # Integer images are read in their own type (exact), floats as float.
        a = inp.read_image(0, 0, 0, 1, "float" if is_float else spec.format)
    finally:
        inp.close()
    if a is None or np.size(a) == 0:
        raise HeightMapError(f"cannot read pixels of {p}")
    a = np.asarray(a).reshape(spec.height, spec.width, -1)[..., 0]
    if is_float:
        return np.clip(np.nan_to_num(a.astype(np.float64), nan=0.0), 0.0, 1.0)
    if not np.issubdtype(a.dtype, np.integer):
        raise HeightMapError(f"{p}: unsupported pixel type {spec.format}")
    return a.astype(np.float64) / float(np.iinfo(a.dtype).max)


def quantize(h: F64, bits: int = 8) -> npt.NDArray[np.uint16]:
    """Heights in [0, 1] -> unorm codes (round to nearest)."""
    if bits not in (8, 16):
        raise ValueError("height storage is unorm8 or unorm16")
    m = (1 << bits) - 1
    return np.rint(np.clip(h, 0.0, 1.0) * m).astype(np.uint16)


@dataclass
class Pyramid:
    """A quantised height map with its max-mipmap pyramid."""

    codes: npt.NDArray[np.uint16]  # level-0 codes, shape (H, W)
    bits: int = 8
    levels: list[npt.NDArray[np.uint16]] = field(default_factory=list)  # padded, level 0..n

    @property
    def height(self) -> int:
        return int(self.codes.shape[0])

    @property
    def width(self) -> int:
        return int(self.codes.shape[1])

    @property
    def n(self) -> int:
        """The root level: N = 2^n is the padded size."""
        return len(self.levels) - 1

    @property
    def size(self) -> int:
        return 1 << self.n

    @property
    def maxcode(self) -> int:
        return (1 << self.bits) - 1

    def level_offsets(self, align: int = 64) -> list[int]:
        """Byte offset of each level from the base address (see the module docstring)."""
        bpt = self.bits // 8
        offs, o = [], 0
        for k in range(self.n + 1):
            offs.append(o)
            side = self.size >> k
            o += -(-(side * side * bpt) // align) * align
        return offs

    def memory_image(self, align: int = 64) -> bytes:
        """The pyramid as the bytes the hardware reads (little-endian codes)."""
        offs = self.level_offsets(align)
        dt = np.dtype("<u1") if self.bits == 8 else np.dtype("<u2")
        total = offs[-1] + -(-(dt.itemsize) // align) * align
        buf = bytearray(total)
        for k, lv in enumerate(self.levels):
            raw = lv.astype(dt).tobytes()
            buf[offs[k]:offs[k] + len(raw)] = raw
        return bytes(buf)


def build(h_or_codes: npt.ArrayLike, bits: int = 8) -> Pyramid:
    """Build the pyramid from heights in [0, 1] (float) or from unorm codes (integer array)."""
    a = np.asarray(h_or_codes)
    if a.ndim != 2 or a.size == 0:
        raise HeightMapError(f"a height map is a non-empty 2-D array, got shape {a.shape}")
    codes = a.astype(np.uint16) if np.issubdtype(a.dtype, np.integer) else quantize(a, bits)
    if codes.max(initial=0) > (1 << bits) - 1:
        raise HeightMapError(f"codes exceed unorm{bits}")
    hh, ww = codes.shape
    n = max(0, int(np.ceil(np.log2(max(hh, ww)))))
    size = 1 << n
    lv = np.zeros((size, size), dtype=np.uint16)
    lv[:hh, :ww] = codes
    levels = [lv]
    while lv.shape[0] > 1:
        s = lv.shape[0] // 2
        lv = lv.reshape(s, 2, s, 2).max(axis=(1, 3))
        levels.append(lv)
    return Pyramid(codes=codes, bits=bits, levels=levels)
