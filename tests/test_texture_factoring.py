# SPDX-License-Identifier: Apache-2.0
"""model.texture.sample factored into lookup_addresses (tex_addr) and filter_texels (tex_filter).

The factoring must not change the lookup: ``sample`` is checked against a verbatim copy of the
unfactored implementation, in both engines, on random, edge and special (NaN / Inf / huge)
coordinates, every level, scale != 1.  The addresses are checked against the memory image: the
four bytes at each address are the texel the filter reads.
"""
from __future__ import annotations

import numpy as np
import pytest

from model import texture
from model.arith import ENGINES, Arith


@np.errstate(all="ignore")
def sample_unfactored(tex: texture.Texture, ar: Arith, u, v, level, scale=None):
    """model.texture.sample before the factoring (verbatim, addresses always computed)."""
    u = np.asarray(u, dtype=np.float64)
    v = np.asarray(v, dtype=np.float64)
    lvl = np.broadcast_to(np.asarray(level, dtype=np.int64), u.shape)
    if scale is not None:
        u = ar.mul(u, scale[0])
        v = ar.mul(v, scale[1])
    half = np.full(u.shape, 0.5)
    inv = np.ldexp(1.0, -lvl)
    x = ar.sub(ar.mul(u, inv), half)
    y = ar.sub(ar.mul(v, inv), half)
    j0 = ar.to_index(x)
    i0 = ar.to_index(y)
    fx = ar.sub(x, ar.from_int(j0))[:, None]
    fy = ar.sub(y, ar.from_int(i0))[:, None]
    widths = np.array([lv.shape[1] for lv in tex.levels], dtype=np.int64)[lvl]
    heights = np.array([lv.shape[0] for lv in tex.levels], dtype=np.int64)[lvl]
    j1 = np.clip(j0 + 1, 0, widths - 1)
    i1 = np.clip(i0 + 1, 0, heights - 1)
    j0 = np.clip(j0, 0, widths - 1)
    i0 = np.clip(i0, 0, heights - 1)
    flat = np.concatenate([lv.reshape(-1, 4) for lv in tex.levels])
    starts = np.cumsum([0] + [lv.shape[0] * lv.shape[1] for lv in tex.levels[:-1]])
    base = starts[lvl]

    def read(i, j):
        return ar.from_unorm(flat[base + i * widths + j], 8)

    c00, c01 = read(i0, j0), read(i0, j1)
    c10, c11 = read(i1, j0), read(i1, j1)
    top = ar.add(c00, ar.mul(fx, ar.sub(c01, c00)))
    bot = ar.add(c10, ar.mul(fx, ar.sub(c11, c10)))
    out = ar.add(top, ar.mul(fy, ar.sub(bot, top)))
    addr = np.stack([tex.address(lvl, i0, j0), tex.address(lvl, i0, j1),
                     tex.address(lvl, i1, j0), tex.address(lvl, i1, j1)], axis=-1)
    return out, addr


def coords(rng: np.random.Generator, n: int, w: int, h: int) -> tuple[np.ndarray, np.ndarray]:
    u = rng.uniform(-0.2 * w, 1.2 * w, n)
    v = rng.uniform(-0.2 * h, 1.2 * h, n)
    special = np.array([np.nan, np.inf, -np.inf, 0.0, -0.0, 1e30, -1e30, 2.0**19, -2.0**19,
                        2.0**20, 1e-30, float(w), float(h), 0.5, 3e6])
    m = n // 5
    u[:m] = rng.choice(special, m)
    v[m:2 * m] = rng.choice(special, m)
    return u, v


@pytest.mark.parametrize("eng", ["f64", "f24"])
@pytest.mark.parametrize("shape", [(1, 1), (37, 100), (100, 37), (8, 8), (5, 1)])
def test_sample_unchanged(eng: str, shape: tuple[int, int], rng: np.random.Generator) -> None:
    ar = ENGINES[eng]
    hh, ww = shape
    tex = texture.build(rng.integers(0, 256, (hh, ww, 4)).astype(np.uint8))
    for scale in (None, tex.scale_for(ar, 64, 48), tex.scale_for(ar, ww, hh)):
        u, v = coords(rng, 3000, ww, hh)
        lvl = rng.integers(0, tex.n_levels, u.size)
        if scale is not None:
            u, v = ar.r(u), ar.r(v)
        got = texture.sample(tex, ar, u, v, lvl, scale, with_addresses=True)
        want, addr = sample_unfactored(tex, ar, u, v, lvl, scale)
        assert got.value.dtype == want.dtype and got.value.shape == want.shape
        assert np.array_equal(got.value, want, equal_nan=True)
        assert got.addr is not None and np.array_equal(got.addr, addr)
        assert texture.sample(tex, ar, u, v, lvl, scale).addr is None


def test_addresses_point_at_the_texels(rng: np.random.Generator) -> None:
    ar = ENGINES["f24"]
    tex = texture.build(rng.integers(0, 256, (37, 100, 4)).astype(np.uint8))
    mem = np.frombuffer(tex.memory_image(), dtype=np.uint8)
    u, v = coords(rng, 4000, 100, 37)
    u, v = ar.r(u), ar.r(v)
    lvl = rng.integers(0, tex.n_levels, u.size)
    base = 0x1234_5640
    la = texture.lookup_addresses(tex, ar, u, v, lvl, base=base)
    ij = [(la.i0, la.j0), (la.i0, la.j1), (la.i1, la.j0), (la.i1, la.j1)]
    texels = np.empty((u.size, 4, 4), dtype=np.uint8)
    for k, (i, j) in enumerate(ij):
        a = la.addr[:, k] - base
        for n in range(u.size):  # the bytes R, G, B, A at the address
            texels[n, k] = mem[a[n]:a[n] + 4]
        assert np.array_equal(texels[:, k], np.stack(
            [tex.levels[int(lv)][int(ii), int(jj)] for lv, ii, jj in zip(lvl, i, j)]))
    # the filter on those reads is the sample
    got = texture.filter_texels(ar, texels, la.fx, la.fy)
    assert np.array_equal(got, texture.sample(tex, ar, u, v, lvl).value, equal_nan=True)
    # the clamped indices: j1 - j0 and i1 - i0 are 0 or 1, all inside the level
    for lo, hi, size in ((la.j0, la.j1, 0), (la.i0, la.i1, 1)):
        assert set(np.unique(hi - lo)) <= {0, 1}
        dims = np.array([tex.levels[int(k)].shape[1 - size] for k in lvl])
        assert (lo >= 0).all() and (hi < dims).all()


def test_lookup_addresses_reads_only_sizes() -> None:
    """A texture of zero-stride levels (no texel memory) is enough for the addresses: the RTL
    test uses it for the largest configuration (32768 texels wide, 16 levels)."""
    ar = ENGINES["f24"]
    big = texture.Texture([np.broadcast_to(np.zeros(4, np.uint8),
                                           (-(-3 // 2**k), -(-32768 // 2**k), 4))
                           for k in range(16)])
    assert big.level_size(15) == (1, 1)
    u = np.array([0.0, 32767.5, 40000.0, np.nan, 16384.0])
    la = texture.lookup_addresses(big, ar, u, np.full(5, 2.5), np.zeros(5, np.int64))
    assert list(la.j0) == [0, 32767, 32767, 0, 16383] and list(la.j1) == [0, 32767, 32767, 1, 16384]
    assert np.isnan(la.fx[3]) and la.fx[1] == 0.0
    assert int(la.addr[1, 3]) == 4 * (2 * 32768 + 32767)
    assert (la.fy == 0.0).all()  # v = 2.5: the centre of row 2
