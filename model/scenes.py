# SPDX-License-Identifier: Apache-2.0
"""Procedural benchmark scenes: height fields, colour textures and normal maps.

Seven scenes in the spirit of the paper's benchmark set (Park et al. 2013, Section 5, Fig. 8),
ordered roughly from low to high coherence between neighbouring heights:

``rocks``
    rough fractal terrain (ridged gradient-noise fBm, seven octaves): the least coherent scene,
    many small sharp features.
``stones``
    cobblestones: Voronoi cells with domed tops separated by low gaps.
``four-shapes``
    a pyramid, a hemisphere, a box and a cylinder on a flat floor, one per quadrant: large flat
    areas with sharp edges and vertical walls.
``saints``
    a carved relief panel: three arched niches, each holding a robed figure with a head and a
    halo, inside a raised frame; smooth rounded forms with fine carving noise.
``wall``
    a brick wall in running bond: flat brick faces with narrow sharp mortar grooves.
``bump``
    one smooth (cos^2) bump in the middle of a flat floor.
``dent``
    a smooth crater with a soft rim pressed into a high flat plane.

Coordinates.  Every scene is a continuous function of (x, y) on the unit square, x along
columns (u), y along rows (v), sampled at texel centres.  The map's larger side spans [0, 1]
and the smaller side the centred part of it, so a non-square map is a centred crop of the
square scene (features keep their shape and stay centred) and any size works, including
non-power-of-two and tiny maps.  Texel (i, j) of an H x W map samples

    x = 0.5 + (j + 0.5 - W/2) / max(H, W),   y = 0.5 + (i + 0.5 - H/2) / max(H, W).

The same (x, y) gives the same height at every resolution (only the sampling changes), and
every random choice comes from a fixed seed, so scenes are bit-for-bit deterministic.

Height fields follow ``CONVENTIONS.md``: ``h[row, col]`` float64 in [0, 1], 1 is the top of
the displacement volume.  Textures are float32 RGB in [0, 1], shape (H, W, 3), row-major like the
height map (texel (i, j) colours the same texel as h[i, j]).

Normal maps (``normal_map``) are tangent-space unit normals, float32 (H, W, 3), components
(n_u, n_v, n_z) in [-1, 1] with n_z > 0 pointing out of the surface (tangent frame T = +u,
B = +v, N = up, as in ``model.camera``).  They come from the height field scaled to texel units
(surface height = h * depth_scale texels) by central differences with edge replication:

    dz/du = depth_scale * (h[i, j+1] - h[i, j-1]) / 2,   dz/dv likewise along rows,
    n = normalize(-dz/du, -dz/dv, 1).

Stored as unorm8 RGB the encoding is the usual ``round((n + 1) / 2 * 255)`` per component
(``encode_normals`` / ``decode_normals``).

``load_scene(name, size)`` bundles heights, texture, normals and the recommended depth scale
(the volume depth in texels, ``model.camera.depth_scale``: 8 % of the map's larger side).
Sizes are ``n`` (an n x n map) or ``(height, width)`` = (rows, columns), like numpy shapes.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]
F32 = npt.NDArray[np.float32]

SCENES: tuple[str, ...] = ("rocks", "stones", "four-shapes", "saints", "wall", "bump", "dent")

Size = int | tuple[int, int]


# --------------------------------------------------------------------------------------------
# helpers


def _shape(size: Size) -> tuple[int, int]:
    """``n`` or ``(rows, cols)`` -> (rows, cols); positive integers only."""
    if isinstance(size, (int, np.integer)) and not isinstance(size, bool):
        hh = ww = int(size)
    else:
        try:
            hh, ww = (int(s) for s in size)  # type: ignore[union-attr]
        except (TypeError, ValueError):
            raise ValueError(f"size must be n or (height, width), got {size!r}") from None
    if hh < 1 or ww < 1:
        raise ValueError(f"size must be positive, got {size!r}")
    return hh, ww


def _check_name(name: str) -> str:
    if name not in SCENES:
        raise ValueError(f"unknown scene {name!r}; valid scenes: {', '.join(SCENES)}")
    return name


def _coords(hh: int, ww: int) -> tuple[F64, F64]:
    """Texel-centre coordinates: x (W,) along columns, y (H,) along rows (module docstring)."""
    s = float(max(hh, ww))
    x = 0.5 + (np.arange(ww) + 0.5 - ww / 2.0) / s
    y = 0.5 + (np.arange(hh) + 0.5 - hh / 2.0) / s
    return x, y


def _fade(t: F64) -> F64:
    """Perlin's quintic fade 6t^5 - 15t^4 + 10t^3."""
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0)


def _lattice_weights(c: F64, freq: int) -> tuple[F64, F64]:
    """Interpolation matrices of a periodic lattice with ``freq`` cells over [0, 1).

    Returns (W, D), both (len(c), freq): W holds the fade weights of the two lattice points
    around each coordinate, D the same weights times the offset from that lattice point (for
    the gradient term).  Noise is then a product of small dense matrices (separable).
    """
    xs = c * freq
    i0f = np.floor(xs)
    f = xs - i0f
    i0 = i0f.astype(np.int64) % freq
    i1 = (i0 + 1) % freq
    w = _fade(f)
    rows = np.arange(c.shape[0])
    wm = np.zeros((c.shape[0], freq))
    dm = np.zeros((c.shape[0], freq))
    wm[rows, i0] = 1.0 - w
    wm[rows, i1] += w          # (rows, i1) pairs are distinct, so += is exact; freq 1 adds up
    dm[rows, i0] = (1.0 - w) * f
    dm[rows, i1] += w * (f - 1.0)
    return wm, dm


def _gradient_noise(x: F64, y: F64, freq: int, seed: int) -> F64:
    """Periodic 2-D gradient (Perlin) noise at ``freq`` cells per unit, (H, W), about [-0.7, 0.7].

    Separable evaluation: sum over lattice corners of w_y w_x (g_x dx + g_y dy) equals
    Wy @ Gx @ Dx^T + Dy @ Gy @ Wx^T.
    """
    rng = np.random.default_rng(seed)
    ang = rng.random((freq, freq)) * (2.0 * np.pi)
    gx, gy = np.cos(ang), np.sin(ang)
    wx, dx = _lattice_weights(x, freq)
    wy, dy = _lattice_weights(y, freq)
    return (wy @ gx) @ dx.T + (dy @ gy) @ wx.T


def _fbm(x: F64, y: F64, base: int, octaves: int, gain: float, seed: int,
         ridged: bool = False) -> F64:
    """Fractal sum of gradient noise, normalised by the amplitude sum (about [-0.7, 0.7]).

    ``ridged``: each octave is 0.7 - 2|n|, sharp crests where the noise crosses zero.
    """
    total = np.zeros((y.shape[0], x.shape[0]))
    amp, norm = 1.0, 0.0
    for k in range(octaves):
        n = _gradient_noise(x, y, base << k, seed * 101 + k)
        if ridged:
            n = 0.7 - 2.0 * np.abs(n)
        total += amp * n
        norm += amp
        amp *= gain
    return total / norm


def _smoothstep(e0: float, e1: float, v: F64) -> F64:
    t = np.clip((v - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def _round_profile(inside: F64, radius: float) -> F64:
    """0 outside, rising along a quarter circle to 1 at ``radius`` inside an edge.

    ``inside`` is the distance inside a shape (negative outside).
    """
    p = np.clip(inside / radius, 0.0, 1.0)
    return np.sqrt(1.0 - (1.0 - p) ** 2)


def _grid(x: F64, y: F64) -> tuple[F64, F64]:
    return np.broadcast_to(x[None, :], (y.shape[0], x.shape[0])), \
        np.broadcast_to(y[:, None], (y.shape[0], x.shape[0]))


def _checker(x: F64, y: F64, n: int) -> F64:
    """1 on the 'white' squares of an n x n checkerboard over the unit square, else 0."""
    cx = np.floor(x * n).astype(np.int64)
    cy = np.floor(y * n).astype(np.int64)
    return ((cy[:, None] + cx[None, :]) & 1).astype(np.float64)


def _mix(c0: tuple[float, float, float], c1: tuple[float, float, float], t: F64) -> F64:
    a = np.asarray(c0)
    b = np.asarray(c1)
    return a + (b - a) * t[..., None]


@dataclass
class _Fields:
    """One scene sampled on a grid: heights and (optionally) its colour texture."""

    h: F64
    rgb: F64 | None


# --------------------------------------------------------------------------------------------
# the scenes: each maps texel-centre coordinates to heights (and colours when asked)


def _rocks(x: F64, y: F64, colour: bool) -> _Fields:
    cells = 12
    edge, _, cid = _voronoi(x, y, cells, seed=11)
    rng = np.random.default_rng(12)
    top = 0.55 + 0.4 * rng.random(cells * cells)
    facet = np.clip(edge / (0.45 / cells), 0.0, 1.0) ** 0.8   # angular, ridged rock tops
    rock = top[cid] * facet
    rough = _fbm(x, y, 16, 5, 0.6, seed=13, ridged=True)
    ground = 0.14 + 0.1 * rough
    h = np.clip(np.maximum(rock, ground) + 0.12 * rough, 0.0, 1.0)
    rgb = None
    if colour:
        tint = 0.75 + 0.35 * rng.random(cells * cells)
        base = _mix((0.33, 0.29, 0.25), (0.66, 0.62, 0.56), np.clip(h * 1.2, 0.0, 1.0))
        on_rock = (rock > ground)[..., None]
        rgb = np.where(on_rock, base * tint[cid][..., None], base * 0.7) \
            * (1.0 + 0.35 * rough)[..., None]
    return _Fields(h, rgb)


def _voronoi(x: F64, y: F64, cells: int, seed: int
             ) -> tuple[F64, F64, npt.NDArray[np.int64]]:
    """Periodic jittered-grid Voronoi diagram with ``cells`` x ``cells`` sites over the unit square.

    Returns, per sample, the distance to its cell's border (exact over the 3 x 3 neighbourhood
    of grid cells), the distance to its cell's site (both in units of the unit square) and the
    cell id (row-major over the site grid).  Sites sit in [0.15, 0.85] of their grid cell, so
    the 3 x 3 neighbourhood holds the nearest site.
    """
    rng = np.random.default_rng(seed)
    sites = 0.15 + 0.7 * rng.random((2, cells, cells))
    step = max(1, 32768 // max(1, x.shape[0]))  # row blocks that stay in cache: ~2x faster
    parts = [_voronoi_rows(x, y[i:i + step], cells, sites) for i in range(0, y.shape[0], step)]
    return (np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts]),
            np.concatenate([p[2] for p in parts]))


def _voronoi_rows(x: F64, y: F64, cells: int, sites: F64
                  ) -> tuple[F64, F64, npt.NDArray[np.int64]]:
    """``_voronoi`` on a block of rows, with the sites given."""
    xs, ys = x * cells, y * cells
    ix = np.floor(xs).astype(np.int64)
    iy = np.floor(ys).astype(np.int64)
    shape = (y.shape[0], x.shape[0])
    offsets = [(oy, ox) for oy in (-1, 0, 1) for ox in (-1, 0, 1)]

    def site(oy: int, ox: int) -> tuple[F64, F64]:
        """Candidate site (x, y) relative to each sample, in grid-cell units."""
        cy, cx = iy + oy, ix + ox
        ty, tx = cy % cells, cx % cells
        sx = sites[0][ty][:, tx]  # two 1-D gathers: much faster than one 2-D fancy index
        sy = sites[1][ty][:, tx]
        sx += (cx - xs)[None, :]
        sy += (cy - ys)[:, None]
        return sx, sy

    best = np.full(shape, np.inf)
    bx = np.zeros(shape)
    by = np.zeros(shape)
    bk = np.zeros(shape, np.int64)
    for k, (oy, ox) in enumerate(offsets):
        px, py = site(oy, ox)
        d = px * px + py * py
        m = d < best
        np.copyto(best, d, where=m)
        np.copyto(bx, px, where=m)
        np.copyto(by, py, where=m)
        bk[m] = k
    edge = np.full(shape, np.inf)
    for oy, ox in offsets:
        px, py = site(oy, ox)
        d = px * px + py * py
        sep = np.hypot(px - bx, py - by)
        with np.errstate(divide="ignore", invalid="ignore"):
            e = (d - best) / (2.0 * sep)
        np.minimum(edge, e, out=edge, where=sep > 1e-9)
    oy_k = np.array([o[0] for o in offsets])[bk]
    ox_k = np.array([o[1] for o in offsets])[bk]
    cid = ((iy[:, None] + oy_k) % cells) * cells + (ix[None, :] + ox_k) % cells
    return edge / cells, np.sqrt(best) / cells, cid


def _stones(x: F64, y: F64, colour: bool) -> _Fields:
    cells = 8
    edge, dsite, cid = _voronoi(x, y, cells, seed=21)
    rng = np.random.default_rng(22)
    top = 0.72 + 0.26 * rng.random(cells * cells)
    gap = 0.006
    rim = _round_profile(edge - gap, 0.25 / cells)            # rounded edges
    dome = 1.0 - 0.3 * np.minimum(dsite * cells, 1.0) ** 2     # gently domed top
    rough = _fbm(x, y, 24, 3, 0.5, seed=23)
    stone = top[cid] * rim * dome * (1.0 + 0.05 * rough)
    ground = 0.08 + 0.05 * rough
    h = np.clip(np.maximum(stone, ground), 0.0, 1.0)
    rgb = None
    if colour:
        palette = np.array([(0.62, 0.60, 0.56), (0.70, 0.64, 0.54), (0.52, 0.50, 0.50),
                            (0.66, 0.55, 0.47), (0.58, 0.60, 0.62), (0.75, 0.70, 0.60)])
        pick = rng.integers(0, len(palette), cells * cells)
        base = palette[pick][cid]
        soil = np.array((0.26, 0.21, 0.16))
        on_stone = (stone > ground)[..., None]
        shade = (0.75 + 0.25 * rim + 0.4 * rough)[..., None]
        rgb = np.where(on_stone, base * shade, soil * (1.0 + 0.6 * rough)[..., None])
    return _Fields(h, rgb)


def _four_shapes(x: F64, y: F64, colour: bool) -> _Fields:
    gx, gy = _grid(x, y)
    a = 0.19  # half-size of each shape
    # pyramid (top left): sharp ridges
    dx, dy = np.abs(gx - 0.25), np.abs(gy - 0.25)
    pyramid = np.clip(1.0 - np.maximum(dx, dy) / a, 0.0, 1.0)
    # hemisphere (top right): smooth
    r = np.hypot(gx - 0.75, gy - 0.25)
    hemi = np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, 1.0)) * 0.9
    # box (bottom left): flat top, vertical walls
    box = np.where(np.maximum(np.abs(gx - 0.25), np.abs(gy - 0.75)) < 0.85 * a, 0.6, 0.0)
    # cylinder (bottom right): flat top, round vertical wall
    cyl = np.where(np.hypot(gx - 0.75, gy - 0.75) < 0.85 * a, 0.8, 0.0)
    h = np.clip(np.maximum.reduce([pyramid, hemi, box, cyl]), 0.0, 1.0)
    rgb = None
    if colour:
        chk = _checker(x, y, 16)
        floor = _mix((0.35, 0.35, 0.38), (0.75, 0.75, 0.78), chk)
        quad = (gy >= 0.5).astype(np.int64) * 2 + (gx >= 0.5).astype(np.int64)
        tints = np.array([(0.85, 0.25, 0.20), (0.25, 0.70, 0.30),
                          (0.25, 0.40, 0.85), (0.90, 0.80, 0.25)])
        shape_col = tints[quad] * (0.8 + 0.2 * chk)[..., None]
        rgb = np.where((h > 1e-6)[..., None], shape_col, floor)
    return _Fields(h, rgb)


def _saints(x: F64, y: F64, colour: bool) -> _Fields:
    gx, gy = _grid(x, y)
    panel = 0.42
    # raised frame with a bevel along the border of the unit square
    border = np.minimum(np.minimum(gx, 1.0 - gx), np.minimum(gy, 1.0 - gy))
    frame = 0.68 * (1.0 - _smoothstep(0.035, 0.05, border))
    h = np.maximum(np.full_like(gx, panel), frame)
    carve = _fbm(x, y, 48, 2, 0.5, seed=31)
    rng = np.random.default_rng(32)
    halo_mask = np.zeros(gx.shape, dtype=bool)
    for i in range(3):
        xc = (i + 0.5) / 3.0 + 0.01 * (rng.random() - 0.5)
        # everything below lies within |x - xc| < 0.14: work on those columns only
        cols = np.nonzero(np.abs(x - xc) < 0.14)[0]
        if cols.size == 0:
            continue
        sl = slice(int(cols[0]), int(cols[-1]) + 1)
        fx, fy = gx[:, sl], gy[:, sl]
        hw, top, bot = 0.125, 0.22, 0.90
        # arched niche: rectangle below y = top, half-disc above it
        dx = np.abs(fx - xc)
        rect_in = np.minimum(hw - dx, np.minimum(fy - top, bot - fy))
        arch_in = np.minimum(hw - np.hypot(fx - xc, fy - top), bot - fy)
        niche_in = np.where(fy < top, arch_in, rect_in)
        recess = _smoothstep(0.0, 0.015, niche_in)
        sub = h[:, sl] - (panel - 0.18) * recess
        # the figure: robe widening downwards, clasped hands, head and halo
        ry, yc = 0.27, 0.61
        t = np.clip((fy - 0.34) / 0.52, 0.0, 1.0)
        rx = 0.055 + 0.045 * t
        robe_r = np.hypot((fx - xc) / rx, (fy - yc) / ry)
        robe_in = (1.0 - robe_r) * np.minimum(rx, ry)
        folds = 0.04 * np.cos((fx - xc) * 2.0 * np.pi * 45.0) * (0.3 + t)
        robe = (0.66 + folds) * _round_profile(robe_in, 0.05)
        hands = 0.80 * _round_profile(0.022 - np.hypot(fx - xc, (fy - 0.47) * 1.3), 0.02)
        head_r = np.hypot(fx - xc, fy - 0.285)
        head = 0.88 * _round_profile(0.048 - head_r, 0.045)
        ring = 0.012 - np.abs(head_r - 0.078)
        halo = 0.55 * _round_profile(ring, 0.010)
        halo_mask[:, sl] |= ring > 0.0
        h[:, sl] = np.maximum.reduce([sub, robe, hands, head, halo])
    h = np.clip(h + 0.018 * carve, 0.0, 1.0)
    rgb = None
    if colour:
        stone = _mix((0.30, 0.24, 0.17), (0.90, 0.80, 0.64), np.clip((h - 0.15) * 1.4, 0.0, 1.0))
        gold = np.array((0.90, 0.72, 0.28))
        rgb = np.where(halo_mask[..., None], gold, stone) * (0.95 + 0.3 * carve)[..., None]
    return _Fields(h, rgb)


def _wall(x: F64, y: F64, colour: bool) -> _Fields:
    rows, per_row = 8, 4
    bw, bh = 1.0 / per_row, 1.0 / rows
    mortar, bevel = 0.009, 0.004
    gx, gy = _grid(x, y)
    row = np.floor(gy / bh).astype(np.int64)
    shift = np.where(row % 2 == 1, 0.5 * bw, 0.0)
    xx = gx + shift
    col = np.floor(xx / bw).astype(np.int64)
    fx = xx - col * bw
    fy = gy - row * bh
    inside = np.minimum(np.minimum(fx, bw - fx), np.minimum(fy, bh - fy)) - mortar
    rng = np.random.default_rng(41)
    nb = (rows + 2) * (per_row + 2)
    bid = (row % rows) * (per_row + 2) + (col % (per_row + 1))
    face = 0.86 + 0.12 * rng.random(nb)
    rough = _fbm(x, y, 32, 3, 0.55, seed=42)
    brick = face[bid] + 0.03 * rough
    groove = 0.22 + 0.04 * rough
    t = np.clip(inside / bevel, 0.0, 1.0)
    h = np.clip(groove + (brick - groove) * t, 0.0, 1.0)
    rgb = None
    if colour:
        tint = 0.8 + 0.35 * rng.random(nb)
        red = np.array((0.66, 0.28, 0.18)) * tint[bid][..., None]
        grey = np.array((0.74, 0.72, 0.67))
        speck = (1.0 + 0.5 * rough)[..., None]
        rgb = np.where((inside > 0.0)[..., None], red, grey) * speck
    return _Fields(h, rgb)


def _bump(x: F64, y: F64, colour: bool) -> _Fields:
    gx, gy = _grid(x, y)
    r = np.hypot(gx - 0.5, gy - 0.5)
    radius = 0.4
    h = np.where(r < radius, np.cos(0.5 * np.pi * r / radius) ** 2, 0.0)
    rgb = None
    if colour:
        rgb = _mix((0.95, 0.55, 0.15), (0.97, 0.95, 0.90), _checker(x, y, 8))
    return _Fields(np.clip(h, 0.0, 1.0), rgb)


def _dent(x: F64, y: F64, colour: bool) -> _Fields:
    gx, gy = _grid(x, y)
    r = np.hypot(gx - 0.5, gy - 0.5)
    radius = 0.36
    bowl = np.where(r < radius, np.cos(0.5 * np.pi * r / radius) ** 2, 0.0)
    rim = np.exp(-(((r - 0.95 * radius) / 0.05) ** 2))
    h = np.clip(0.82 - 0.78 * bowl + 0.16 * rim, 0.0, 1.0)
    rgb = None
    if colour:
        rgb = _mix((0.20, 0.40, 0.75), (0.92, 0.94, 0.97), _checker(x, y, 8))
    return _Fields(h, rgb)


_GENERATORS: dict[str, Callable[[F64, F64, bool], _Fields]] = {
    "rocks": _rocks, "stones": _stones, "four-shapes": _four_shapes, "saints": _saints,
    "wall": _wall, "bump": _bump, "dent": _dent,
}


def _fields(name: str, size: Size, colour: bool) -> _Fields:
    gen = _GENERATORS[_check_name(name)]
    hh, ww = _shape(size)
    x, y = _coords(hh, ww)
    return gen(x, y, colour)


# --------------------------------------------------------------------------------------------
# public API


def height(name: str, size: Size) -> F64:
    """The scene's height field, float64 (H, W) in [0, 1]; ``size`` is n or (height, width)."""
    return np.ascontiguousarray(_fields(name, size, False).h, dtype=np.float64)


def texture(name: str, size: Size) -> F32:
    """The scene's colour texture, float32 (H, W, 3) RGB in [0, 1], aligned with ``height``."""
    f = _fields(name, size, True)
    assert f.rgb is not None
    return np.clip(f.rgb, 0.0, 1.0).astype(np.float32)


def normal_map(h: npt.ArrayLike, depth_scale: float) -> F32:
    """Tangent-space unit normals (H, W, 3) float32 of a height field.

    ``depth_scale`` is the depth of the volume in texel units (a height step of 1 is
    ``depth_scale`` texels).  Central differences with edge replication (so a border texel
    uses half its one-sided difference); components (n_u, n_v, n_z) in [-1, 1], n_z > 0.
    """
    a = np.asarray(h, dtype=np.float64)
    if a.ndim != 2 or a.size == 0:
        raise ValueError(f"a height field is a non-empty 2-D array, got shape {a.shape}")
    p = np.pad(a, 1, mode="edge")
    dzdu = (p[1:-1, 2:] - p[1:-1, :-2]) * (0.5 * depth_scale)
    dzdv = (p[2:, 1:-1] - p[:-2, 1:-1]) * (0.5 * depth_scale)
    n = np.stack([-dzdu, -dzdv, np.ones_like(a)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return n.astype(np.float32)


def encode_normals(n: npt.ArrayLike) -> npt.NDArray[np.uint8]:
    """Unit normals in [-1, 1] -> unorm8 RGB: round((n + 1) / 2 * 255)."""
    a = np.clip(np.asarray(n, dtype=np.float64), -1.0, 1.0)
    return np.rint((a + 1.0) * 127.5).astype(np.uint8)


def decode_normals(rgb: npt.ArrayLike) -> F32:
    """unorm8 RGB -> normals: code / 255 * 2 - 1, renormalised to unit length."""
    a = np.asarray(rgb, dtype=np.float64) / 127.5 - 1.0
    norm = np.linalg.norm(a, axis=-1, keepdims=True)
    return (a / np.where(norm > 0.0, norm, 1.0)).astype(np.float32)


@dataclass
class Scene:
    """A scene ready to render: heights, colour texture, normal map and depth scale."""

    name: str
    heights: F64          # (H, W) float64 in [0, 1]
    texture: F32          # (H, W, 3) float32 RGB in [0, 1]
    normals: F32          # (H, W, 3) float32 tangent-space unit normals
    depth_scale: float    # depth of the volume in texels (model.camera.depth_scale)

    @property
    def height(self) -> int:
        return int(self.heights.shape[0])

    @property
    def width(self) -> int:
        return int(self.heights.shape[1])


def load_scene(name: str, size: Size, depth_scale: float | None = None) -> Scene:
    """Heights, texture and normals of a named scene at ``size`` (n or (height, width)).

    ``depth_scale`` defaults to the project rule ``model.camera.depth_scale(W, H)``.
    """
    from model.camera import depth_scale as rule

    f = _fields(name, size, True)
    assert f.rgb is not None
    hh, ww = f.h.shape
    d = float(rule(ww, hh) if depth_scale is None else depth_scale)
    return Scene(name=name, heights=np.ascontiguousarray(f.h, dtype=np.float64),
                 texture=np.clip(f.rgb, 0.0, 1.0).astype(np.float32),
                 normals=normal_map(f.h, d), depth_scale=d)
