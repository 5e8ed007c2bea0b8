# SPDX-License-Identifier: Apache-2.0
"""Quad request streams for the texture cache test: the byte addresses of bilinear 2x2 footprints
(c00, c01, c10, c11) as the texture address unit computes them (model.texture.sample), in the
orders a renderer produces them.

- :func:`camera`: a camera-like walk: views of a textured plane under perspective (rotation,
  scale, anisotropy, tilt), pixels in 8x8 tiles, the MIP level of each pixel from its footprint
  (floor(log2 rho + 0.5), clamped), two quads per pixel (colour texture, then normal map), the
  clamp-to-edge addressing of model.texture.sample.
- :func:`random_quads`: quads at random levels and positions, a fifth of them on clamped edges,
  some repeated several times in a row.
- :func:`random_addrs`: four unrelated texel addresses (not a quad: exercises the split passes).
- :func:`random_lines`: four texels in one or two neighbouring lines (passes split by the data
  RAM's windows, reads of a window's overlap word).
- :func:`set_conflicts`: one texel per quad, lines that all fall into one set of one sub-cache
  (more of them than it has ways: with responses stalled, the lookup must wait for a victim).
"""
from __future__ import annotations

import random
from dataclasses import dataclass

import numpy as np

from model import texture
from model.tex_cache import TexCacheConfig, set_of
from model.arith import F64Arith

Quad = tuple[int, int, int, int]
AR = F64Arith()


@dataclass
class Placed:
    """A texture in memory."""

    tex: texture.Texture
    base: int
    name: str

    @property
    def size(self) -> int:
        return self.tex.memory_size()

    def quad(self, level: int, i0: int, j0: int) -> Quad:
        """The quad of texel (i0, j0) at ``level`` with clamp-to-edge (i0, j0 may be -1)."""
        w, h = self.tex.level_size(level)
        i1, j1 = min(max(i0 + 1, 0), h - 1), min(max(j0 + 1, 0), w - 1)
        i0, j0 = min(max(i0, 0), h - 1), min(max(j0, 0), w - 1)
        a = self.tex.address(level, [i0, i0, i1, i1], [j0, j1, j0, j1])
        return tuple(int(x) + self.base for x in a)  # type: ignore[return-value]


def random_texture(rng: np.random.Generator, h: int, w: int) -> texture.Texture:
    """A texture of random unorm8 RGBA codes with its MIP chain."""
    return texture.build(rng.integers(0, 256, size=(h, w, 4), dtype=np.uint8))


def _view(rng: random.Random, tex: texture.Texture, sw: int, sh: int):
    """Texture coordinates (u, v) per pixel of one view and the per-pixel footprint rho."""
    w, h = tex.width, tex.height
    scale = 2.0 ** rng.uniform(-1.5, 3.0)        # texels per pixel at the centre
    aniso = rng.uniform(1.0, 2.0)
    theta = rng.uniform(0, 2 * np.pi)
    tilt = rng.uniform(0.0, 2.5) / sh            # perspective: w grows along the screen's y
    ys, xs = np.mgrid[0:sh + 1, 0:sw + 1].astype(np.float64)
    x, y = xs - sw / 2, ys - sh / 2
    den = 1.0 + tilt * y
    den = np.where(den < 0.2, 0.2, den)
    c, s = np.cos(theta), np.sin(theta)
    px, py = scale * x / den, scale * aniso * y / den
    span = scale * max(sw, sh)
    uc = rng.uniform(min(span, w / 2), max(w - span, w / 2))
    vc = rng.uniform(min(span, h / 2), max(h - span, h / 2))
    u = uc + c * px - s * py
    v = vc + s * px + c * py
    dux, dvx = u[:-1, 1:] - u[:-1, :-1], v[:-1, 1:] - v[:-1, :-1]
    duy, dvy = u[1:, :-1] - u[:-1, :-1], v[1:, :-1] - v[:-1, :-1]
    rho = np.maximum(np.hypot(dux, dvx), np.hypot(duy, dvy))
    return u[:-1, :-1] + 0.5, v[:-1, :-1] + 0.5, rho


def _tile_order(sw: int, sh: int, tile: int = 8) -> np.ndarray:
    idx = []
    for ty in range(0, sh, tile):
        for tx in range(0, sw, tile):
            for y in range(ty, min(ty + tile, sh)):
                for x in range(tx, min(tx + tile, sw)):
                    idx.append(y * sw + x)
    return np.array(idx, dtype=np.int64)


def camera(rng: random.Random, texs: list[Placed], views: int, sw: int = 64,
           sh: int = 64) -> list[Quad]:
    """Views of the first texture's plane; every pixel reads one quad from each texture in turn
    (the same surface point: coordinates scaled to each texture's size)."""
    out: list[Quad] = []
    t0 = texs[0].tex
    order = _tile_order(sw, sh)
    for _ in range(views):
        u, v, rho = _view(rng, t0, sw, sh)
        per_tex = []
        for p in texs:
            su, sv = p.tex.width / t0.width, p.tex.height / t0.height
            r = rho * max(su, sv)
            lvl = np.clip(np.floor(np.log2(np.maximum(r, 1e-9)) + 0.5), 0,
                          p.tex.n_levels - 1).astype(np.int64)
            look = texture.sample(p.tex, AR, (u * su).ravel(), (v * sv).ravel(), lvl.ravel(),
                                  with_addresses=True)
            per_tex.append(look.addr + p.base)
        for i in order:
            for a in per_tex:
                out.append(tuple(int(x) for x in a[i]))  # type: ignore[arg-type]
    return out


def levels_used(texs: list[Placed], stream: list[Quad]) -> dict[str, dict[int, int]]:
    """Quads per texture and level (for the log)."""
    out: dict[str, dict[int, int]] = {}
    for p in texs:
        offs = p.tex.level_offsets() + [p.tex.memory_size()]
        hist: dict[int, int] = {}
        for q in stream:
            o = q[0] - p.base
            if 0 <= o < p.size:
                k = max(i for i in range(p.tex.n_levels) if offs[i] <= o)
                hist[k] = hist.get(k, 0) + 1
        out[p.name] = dict(sorted(hist.items()))
    return out


def random_quads(rng: random.Random, texs: list[Placed], n: int, p_edge=0.2,
                 p_repeat=0.1) -> list[Quad]:
    out: list[Quad] = []
    while len(out) < n:
        p = rng.choice(texs)
        lvl = min(int(rng.expovariate(0.6)), p.tex.n_levels - 1)
        w, h = p.tex.level_size(lvl)
        i0, j0 = rng.randrange(-1, h), rng.randrange(-1, w)
        if rng.random() < p_edge:
            if rng.random() < 0.5:
                i0 = rng.choice([-1, h - 1])
            else:
                j0 = rng.choice([-1, w - 1])
        q = p.quad(lvl, i0, j0)
        out.extend([q] * (rng.randint(2, 6) if rng.random() < p_repeat else 1))
    return out[:n]


def random_addrs(rng: random.Random, texs: list[Placed], n: int) -> list[Quad]:
    """Four texel addresses anywhere in the images (mostly in different lines)."""
    out: list[Quad] = []
    for _ in range(n):
        q = []
        for _ in range(4):
            p = rng.choice(texs)
            q.append(p.base + 4 * rng.randrange(p.size // 4))
        out.append(tuple(q))  # type: ignore[arg-type]
    return out


def random_lines(rng: random.Random, texs: list[Placed], n: int, line_bytes: int) -> list[Quad]:
    """Four texels at random words of one line or two neighbouring lines: pairs of one line in
    different windows (split passes) and at a window's last word + 1 (the overlap word)."""
    out: list[Quad] = []
    for _ in range(n):
        p = rng.choice(texs)
        base = p.base + line_bytes * rng.randrange(max(1, p.size // line_bytes - 1))
        span = 2 * line_bytes if rng.random() < 0.3 else line_bytes
        q = tuple(base + 4 * rng.randrange(span // 4) for _ in range(4))
        out.append(q)  # type: ignore[arg-type]
    return out


def set_conflicts(texs: list[Placed], cfg: TexCacheConfig, rounds: int = 3) -> list[Quad]:
    """Quads of one texel (all four addresses equal: rows clamped, row bit 0, so the sub-cache is
    the line's parity) in ``cfg.ways + 2`` lines of the images that share a sub-cache and a set,
    requested in turn ``rounds`` times."""
    lb = cfg.line_bytes
    groups: dict[tuple[int, int], list[int]] = {}
    for p in texs:
        for la in range(-(-p.base // lb), (p.base + p.size) // lb):
            groups.setdefault((la & 1, set_of(la, cfg)), []).append(la)
    lines = max(groups.values(), key=len)[:cfg.ways + 2]
    if len(lines) < cfg.ways + 2:
        raise ValueError("set_conflicts: the images hold too few lines of one set")
    return [(a, a, a, a) for _ in range(rounds) for a in (la * lb for la in lines)]
