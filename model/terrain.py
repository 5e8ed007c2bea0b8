# SPDX-License-Identifier: Apache-2.0
"""Terrain from a digital elevation model: tessellation + parallax mapping (Gonzalez, Perez,
Orduna 2016) against the exact render, and the pyramidal traversal of the same DEM.

Gonzalez et al. render a terrain tile as a coarse mesh refined by hardware tessellation, and
correct each fragment's texture coordinate by a parallax method that uses the *tessellated
mesh* as its base surface (their Section 2): parallax with offset limiting 0.5 (Fig. 7) or 1
(Welsh's approximation, Fig. 8), iterative parallax (Fig. 9, 2 iterations) and a binary search
around the mesh hit (Fig. 10, 3 iterations and a secant step).  They measure the MSE of each
image against the full-resolution render as a function of the triangle count (Fig. 11).  This
module reproduces that experiment on the golden model's geometry:

The terrain.  A DEM ``h[row, col]`` in [0, 1] is the project's height field (``CONVENTIONS.md``):
texel (i, j) covers u in [j, j+1), v in [i, i+1) and is solid from depth ``1 - h`` down; the
volume is ``height_scale`` texels deep (height h sits h * height_scale texels above the floor),
so a real DEM with sample spacing ``d`` metres and relief ``r`` metres has
``height_scale = r / d``.  Heights are quantised like every engine's (unorm16 by default here:
DEMs need more than 256 levels).

The camera and rays are the project's (:class:`model.camera.Camera` with
``depth_scale = height_scale``): one ray per pixel whose eye ray enters the volume through its
top face inside the map; the other pixels are not covered and left out of every figure.

The renders.  Every image colours a pixel with the DEM's colour texture (an orthophoto, or
:func:`terrain_texture`'s elevation ramp x hill shading) at a texture coordinate, nearest texel:

* ``reference``: the exact first hit of the full-resolution height field (the pyramidal
  traversal, ``park``, f64: the same hit as a texel-by-texel walk);
* ``tessellation``: the first hit of the coarse mesh (:class:`CoarseMesh`: a vertex every
  ``cell`` texels, two triangles per cell, vertex heights bilinearly sampled from the DEM as a
  tessellation evaluation shader does), ray-cast exactly (:func:`cast_mesh`);
* ``parallax-0.5``, ``parallax-1``: :func:`model.approx.parallax` with ``limit`` 0.5 / 1
  started at the mesh hit with the hit triangle's normal as the base (their Fig. 7 / Fig. 8);
* ``parallax-iter``: :func:`model.approx.parallax_iter`, 2 iterations, limit 1 (Fig. 9; the
  model's variant takes each step from the current depth, see ``model/approx.py``);
* ``binary``: :func:`model.approx.binary`, 3 steps and the secant, on the bracket of ray
  parameters within ``cell`` texels (the triangle size ``tsize``) of arc length either side of
  the mesh hit (Fig. 10).

A pixel whose corrected coordinate leaves the map keeps its mesh hit's coordinate (counted as
``left_map``); a pixel whose ray misses the mesh (it leaves the map first) is background.

MSE: mean over the covered pixels and the three channels of the squared difference of the
8-bit images (0..255), as the images are written.

Everything is vectorised over rays; the only Python loops run over mesh cells crossed (a DDA in
lock-step) and over mesh resolutions.
"""
from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from model import approx, heightmap, scenes, traverse
from model.camera import Camera
from model.rays import Rays, TraceResult

F64 = npt.NDArray[np.float64]
F32 = npt.NDArray[np.float32]
U8 = npt.NDArray[np.uint8]
B = npt.NDArray[np.bool_]
I64 = npt.NDArray[np.int64]


class RtlTrace(Protocol):
    """An RTL trace engine for :func:`pyramidal` (``tb.harness.traverse_system.trace_rtl``)."""

    def __call__(self, pyr: heightmap.Pyramid, rays: Rays, method: str, *,
                 latency: int) -> tuple[TraceResult, dict[str, Any]]: ...

#: The approximate methods of the study, in the paper's order (keys of terrain.json's "mse").
METHODS: tuple[str, ...] = ("tessellation", "parallax-0.5", "parallax-1", "parallax-iter",
                            "binary")
#: Colour of pixels whose ray hits nothing (leaves the map through a side).
BACKGROUND = np.array([0.62, 0.74, 0.90])
#: Elevation colour ramp of :func:`terrain_texture`: (height, R, G, B).
RAMP = np.array([(0.00, 0.16, 0.30, 0.14), (0.25, 0.30, 0.45, 0.20), (0.50, 0.52, 0.50, 0.32),
                 (0.75, 0.55, 0.47, 0.40), (0.90, 0.80, 0.78, 0.76), (1.00, 0.97, 0.97, 0.98)])


class DemError(ValueError):
    """A DEM that cannot be used (unreadable file, wrong shape, no finite value, too small)."""


# ---- DEM input ----------------------------------------------------------------------------------

def load_dem(path: str | Path, *, stretch: bool = False,
             nodata: float | None = None) -> tuple[F64, dict[str, Any]]:
    """Read a DEM as heights in [0, 1] and a dict describing the conversion.

    Without ``stretch`` the project's rule applies (:func:`model.heightmap.load`: integer images
    divided by their type's maximum, float images clamped to [0, 1]).  With ``stretch`` the raw
    values (any unit, e.g. metres in a float or int16 GeoTIFF) are mapped linearly from their own
    [min, max] onto [0, 1]; ``nodata`` samples (and NaN / inf) are set to the minimum first.
    The dict holds the raw ``min`` / ``max`` (stretch) and the conversion used.
    """
    p = Path(path)
    if not stretch:
        if nodata is not None:
            raise DemError("--nodata needs --stretch (it is applied to the raw values)")
        try:
            h = heightmap.load(p)
        except heightmap.HeightMapError as e:
            raise DemError(str(e).splitlines()[0]) from None
        _check_dem(h, p)
        return h, {"conversion": "project rule (integer / type max, float clamped)"}
    raw = _read_raw(p)
    bad = ~np.isfinite(raw)
    if nodata is not None:
        bad |= raw == float(nodata)
    if bad.all():
        raise DemError(f"{p}: no valid elevation sample")
    lo, hi = float(raw[~bad].min()), float(raw[~bad].max())
    raw = np.where(bad, lo, raw)
    h = (raw - lo) / (hi - lo) if hi > lo else np.zeros_like(raw)
    _check_dem(h, p)
    return h, {"conversion": "stretched raw [min, max] to [0, 1]", "min": lo, "max": hi,
               "nodata_samples": int(bad.sum())}


def _read_raw(p: Path) -> F64:
    """The first channel of an image (OpenImageIO, as float) or a .npy array, unscaled."""
    if not p.is_file():
        raise DemError(f"DEM not found: {p}")
    if p.suffix.lower() == ".npy":
        try:
            a = np.load(p, allow_pickle=False)
        except Exception as e:  # numpy raises several kinds for a bad file
            raise DemError(f"cannot read {p}: {e}".splitlines()[0]) from None
        if a.ndim == 3:
            a = a[..., 0]
        if a.ndim != 2 or a.size == 0 or not (np.issubdtype(a.dtype, np.integer)
                                              or np.issubdtype(a.dtype, np.floating)):
            raise DemError(f"{p}: expected a 2-D numeric array, got {a.dtype} {a.shape}")
        return a.astype(np.float64)
    import OpenImageIO as oiio

    inp = oiio.ImageInput.open(str(p))
    if inp is None:
        raise DemError(f"cannot read {p}: {oiio.geterror()}".splitlines()[0])
    try:
        spec = inp.spec()
        a = inp.read_image(0, 0, 0, 1, "float")
    finally:
        inp.close()
    if a is None or np.size(a) == 0:
        raise DemError(f"cannot read pixels of {p}")
    if spec.format.basetype not in (oiio.FLOAT, oiio.HALF, oiio.DOUBLE):
        # OpenImageIO normalises integer pixels to [0, 1] (signed: [-1, 1]); undo it so that
        # the stretch sees the stored numbers.
        a = np.asarray(a, np.float64) * float(_int_max(spec.format.basetype, oiio))
    return np.asarray(a, dtype=np.float64).reshape(spec.height, spec.width)


def _int_max(basetype: Any, oiio: Any) -> int:
    table = {oiio.UINT8: 255, oiio.INT8: 127, oiio.UINT16: 65535, oiio.INT16: 32767,
             oiio.UINT32: 4294967295, oiio.INT32: 2147483647}
    return table.get(basetype, 1)


def _check_dem(h: F64, p: Path) -> None:
    if h.ndim != 2 or min(h.shape) < 2:
        raise DemError(f"{p}: a DEM needs at least 2 x 2 samples, got shape {h.shape}")


def synthetic_dem(size: int | tuple[int, int], seed: int = 7) -> F64:
    """A fractal mountain terrain (fBm valleys + ridged fBm crests), heights in [0, 1].

    Deterministic for a seed; built from the scene generator's gradient noise
    (``model.scenes``), at the same (x, y) for every resolution.
    """
    hh, ww = scenes._shape(size)
    x, y = scenes._coords(hh, ww)
    hills = scenes._fbm(x, y, 3, 7, 0.5, seed=seed)
    ridges = scenes._fbm(x, y, 2, 6, 0.55, seed=seed + 1, ridged=True)
    z = 0.55 * hills + 0.45 * ridges
    z = (z - z.min()) / max(float(z.max() - z.min()), 1e-12)
    return np.ascontiguousarray(z ** 1.4)     # flatter valleys, sharper peaks


def terrain_texture(h: npt.ArrayLike, height_scale: float) -> F32:
    """An orthophoto stand-in: elevation colour ramp times Lambert hill shading (light from
    the north-west, 45 degrees up), from the full-resolution heights; float32 (H, W, 3)."""
    a = np.asarray(h, dtype=np.float64)
    n = scenes.normal_map(a, height_scale).astype(np.float64)
    light = np.array([-1.0, -1.0, np.sqrt(2.0)]) / 2.0
    shade = np.clip(n @ light, 0.0, 1.0)
    ramp = np.stack([np.interp(a, RAMP[:, 0], RAMP[:, c]) for c in (1, 2, 3)], axis=-1)
    return np.clip(ramp * (0.35 + 0.75 * shade)[..., None], 0.0, 1.0).astype(np.float32)


# ---- the coarse mesh and its ray cast -----------------------------------------------------------

@dataclass(frozen=True)
class CoarseMesh:
    """A regular triangle mesh over the map: a vertex every ``cell`` texels.

    Vertex (I, J) sits at u = xs[J], v = ys[I] (``xs = 0, cell, 2 cell, ..., W``, the last one
    clipped to the map's edge), height ``heights[I, J]`` (units of h, 0..1): the DEM sampled
    bilinearly at that point, texel centres at half-integers, clamped to the edge (at an
    integer corner: the mean of the up to four texels around it).  Cell (I, J) is split by its
    diagonal (xs[J], ys[I]) - (xs[J+1], ys[I+1]) into triangle A (fx >= fy: corners 00, 10, 11)
    and B (fx < fy: corners 00, 11, 01), fx, fy the position inside the cell in [0, 1].
    """

    cell: int
    xs: F64
    ys: F64
    heights: F64

    @property
    def triangles(self) -> int:
        return 2 * (len(self.xs) - 1) * (len(self.ys) - 1)


def vertex_grid(n: int, cell: int) -> F64:
    """0, cell, 2 cell, ... and n (the last vertex on the map's edge)."""
    return np.unique(np.append(np.arange(0, n, cell, dtype=np.float64), float(n)))


def build_mesh(h: npt.ArrayLike, cell: int) -> CoarseMesh:
    """The coarse mesh of a height field (see :class:`CoarseMesh`)."""
    a = np.asarray(h, dtype=np.float64)
    if int(cell) != cell or cell < 1:
        raise ValueError(f"cell must be a positive integer, got {cell!r}")
    hh, ww = a.shape
    xs, ys = vertex_grid(ww, int(cell)), vertex_grid(hh, int(cell))
    p = np.pad(a, 1, mode="edge")          # p[i + 1, j + 1] = a[i, j]
    xi, yi = xs.astype(np.int64), ys.astype(np.int64)
    # bilinear at the integer corner (X, Y): texels (Y-1..Y, X-1..X), i.e. p[Y..Y+1, X..X+1]
    v = 0.25 * (p[yi][:, xi] + p[yi][:, xi + 1] + p[yi + 1][:, xi] + p[yi + 1][:, xi + 1])
    return CoarseMesh(int(cell), xs, ys, v)


@dataclass
class MeshHit:
    """The first hit of each ray with a coarse mesh.

    ``t`` the ray's depth parameter there, ``u``, ``v`` the point, ``m`` the mesh height (h
    units: ``t = 1 - m``), ``normal`` (N, 3) the unit normal of the hit triangle in world
    directions (+u, +v, up) with the height scale applied, ``hit`` false where the ray leaves
    the map first (NaN elsewhere), ``cells`` the cells visited per ray.
    """

    t: F64
    u: F64
    v: F64
    m: F64
    normal: F64
    hit: B
    cells: I64


def _exit_times(p0: F64, dp: F64, lo: F64, hi: F64) -> F64:
    """Time the ray leaves [lo, hi] along one axis (inf when it does not move)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(dp > 0, (hi - p0) / dp, np.where(dp < 0, (lo - p0) / dp, np.inf))


def cast_mesh(mesh: CoarseMesh, rays: Rays, height_scale: float) -> MeshHit:
    """Ray-cast the coarse mesh exactly (first hit), vectorised over rays.

    A ray is at height ``1 - t`` (units of h) at (u0 + du t, v0 + dv t); it hits where
    ``1 - t <= m(u, v)``.  The rays march through the mesh's cells in lock-step (a DDA over
    cells, finished rays dropped), from the depth of the mesh's highest vertex; inside a cell
    the ray is split at the diagonal and each piece tested against its triangle's plane (the
    gap ``t - (1 - m)`` is linear there).  Rays that leave the map first miss.
    """
    n = len(rays)
    u0, v0, du, dv = (np.asarray(a, dtype=np.float64) for a in
                      (rays.u0, rays.v0, rays.du, rays.dv))
    xs, ys, vh = mesh.xs, mesh.ys, mesh.heights
    nx, ny = len(xs) - 1, len(ys) - 1
    cell = float(mesh.cell)
    out_t = np.full(n, np.nan)
    out_tri = np.zeros(n, np.int64)          # 0: A, 1: B
    out_ci = np.zeros(n, np.int64)
    out_cj = np.zeros(n, np.int64)
    cells = np.zeros(n, np.int64)
    t_in = np.full(n, max(0.0, 1.0 - float(vh.max())))
    uu, vv = u0 + du * t_in, v0 + dv * t_in
    ww, hh = float(xs[-1]), float(ys[-1])
    with np.errstate(invalid="ignore"):
        inside = (uu >= 0) & (uu < ww) & (vv >= 0) & (vv < hh) & np.isfinite(uu + vv)
    idx = np.nonzero(inside)[0]
    cj = np.minimum(np.floor(uu[idx] / cell), nx - 1).astype(np.int64)
    ci = np.minimum(np.floor(vv[idx] / cell), ny - 1).astype(np.int64)
    ti = t_in[idx]
    for _ in range(nx + ny + 2):
        if idx.size == 0:
            break
        a_u0, a_v0, a_du, a_dv = u0[idx], v0[idx], du[idx], dv[idx]
        x0, x1, y0, y1 = xs[cj], xs[cj + 1], ys[ci], ys[ci + 1]
        tx = _exit_times(a_u0, a_du, x0, x1)
        ty = _exit_times(a_v0, a_dv, y0, y1)
        t_out = np.minimum(np.minimum(tx, ty), 1.0)
        t_out = np.maximum(t_out, ti)
        cells[idx] += 1
        h00, h10 = vh[ci, cj], vh[ci, cj + 1]
        h01, h11 = vh[ci + 1, cj], vh[ci + 1, cj + 1]
        wx, wy = x1 - x0, y1 - y0

        def frac(t: F64) -> tuple[F64, F64]:
            return (a_u0 + a_du * t - x0) / wx, (a_v0 + a_dv * t - y0) / wy

        # the diagonal s = fx - fy = 0, linear in t
        fx_a, fy_a = frac(ti)
        fx_b, fy_b = frac(t_out)
        s_a, s_b = fx_a - fy_a, fx_b - fy_b
        with np.errstate(divide="ignore", invalid="ignore"):
            t_d = ti + (t_out - ti) * s_a / (s_a - s_b)
        split = (s_a * s_b < 0) & np.isfinite(t_d)
        t_mid = np.where(split, np.clip(t_d, ti, t_out), t_out)
        found = np.zeros(idx.size, bool)
        t_hit = np.full(idx.size, np.nan)
        tri_hit = np.zeros(idx.size, np.int64)
        for ta, tb in ((ti, t_mid), (t_mid, t_out)):
            fxm, fym = frac(0.5 * (ta + tb))
            tri_b = fxm < fym                      # which triangle this piece lies in
            fxa, fya = frac(ta)
            fxb, fyb = frac(tb)

            def mesh_h(fx: F64, fy: F64) -> F64:
                ma = h00 + (h10 - h00) * fx + (h11 - h10) * fy
                mb = h00 + (h11 - h01) * fx + (h01 - h00) * fy
                return np.where(tri_b, mb, ma)

            ga = ta - (1.0 - mesh_h(fxa, fya))
            gb = tb - (1.0 - mesh_h(fxb, fyb))
            with np.errstate(divide="ignore", invalid="ignore"):
                root = np.where(ga >= 0, ta, ta + (tb - ta) * (-ga) / (gb - ga))
            new = ~found & (tb >= ta) & ((ga >= 0) | (gb >= 0))
            t_hit = np.where(new, np.clip(root, ta, tb), t_hit)
            tri_hit = np.where(new, tri_b.astype(np.int64), tri_hit)
            found |= new
        # t = 1 is the floor (height 0 <= every vertex): a hit there by construction
        floor = ~found & (t_out >= 1.0)
        t_hit = np.where(floor, 1.0, t_hit)
        found |= floor
        done = idx[found]
        out_t[done] = t_hit[found]
        out_tri[done] = tri_hit[found]
        out_ci[done], out_cj[done] = ci[found], cj[found]
        # step to the next cell (both axes at a corner)
        go = ~found
        step_u = go & (tx <= ty)
        step_v = go & (ty <= tx)
        cj = cj + np.where(step_u, np.sign(a_du).astype(np.int64), 0)
        ci = ci + np.where(step_v, np.sign(a_dv).astype(np.int64), 0)
        keep = go & (cj >= 0) & (cj < nx) & (ci >= 0) & (ci < ny)
        idx, cj, ci, ti = idx[keep], cj[keep], ci[keep], t_out[keep]
    hit = np.isfinite(out_t)
    tt = np.where(hit, out_t, 0.0)
    u, v = u0 + du * tt, v0 + dv * tt
    # triangle slopes (per unit of u and v, h units) -> world normals
    ci, cj = out_ci, out_cj
    h00, h10 = vh[ci, cj], vh[ci, cj + 1]
    h01, h11 = vh[ci + 1, cj], vh[ci + 1, cj + 1]
    wx, wy = xs[cj + 1] - xs[cj], ys[ci + 1] - ys[ci]
    tri_b = out_tri == 1
    dmu = np.where(tri_b, h11 - h01, h10 - h00) / wx
    dmv = np.where(tri_b, h01 - h00, h11 - h10) / wy
    nrm = np.stack([-height_scale * dmu, -height_scale * dmv, np.ones(n)], axis=1)
    nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
    nan = np.full(n, np.nan)
    return MeshHit(np.where(hit, out_t, nan), np.where(hit, u, nan), np.where(hit, v, nan),
                   np.where(hit, 1.0 - out_t, nan), np.where(hit[:, None], nrm, np.nan), hit,
                   cells)


# ---- colouring and error ------------------------------------------------------------------------

def sample_nearest(tex: npt.ArrayLike, u: npt.ArrayLike, v: npt.ArrayLike, map_w: int,
                   map_h: int) -> F64:
    """Colour (N, 3) of texture ``tex`` (any size) at map coordinates (u, v), nearest texel;
    the texture spans the map (texel scale Tw / W); NaN coordinates give the background."""
    t = np.asarray(tex)
    th, tw = t.shape[:2]
    uu, vv = np.asarray(u, np.float64), np.asarray(v, np.float64)
    ok = np.isfinite(uu) & np.isfinite(vv)
    j = np.clip(np.floor(np.where(ok, uu, 0.0) * (tw / map_w)), 0, tw - 1).astype(np.intp)
    i = np.clip(np.floor(np.where(ok, vv, 0.0) * (th / map_h)), 0, th - 1).astype(np.intp)
    c = t[i, j].astype(np.float64)
    return np.where(ok[:, None], c, BACKGROUND[None, :])


def to_image(colours: npt.ArrayLike, row: I64, col: I64, image_h: int, image_w: int) -> U8:
    """8-bit RGB image (image_h, image_w, 3): the covered pixels' colours, black elsewhere."""
    img = np.zeros((image_h, image_w, 3), np.uint8)
    img[row, col] = np.rint(np.clip(np.asarray(colours), 0.0, 1.0) * 255.0).astype(np.uint8)
    return img


def mse(a: U8, b: U8, mask: B) -> float:
    """Mean squared difference of two 8-bit images over ``mask``'s pixels and all channels."""
    if not mask.any():
        return 0.0
    d = a[mask].astype(np.float64) - b[mask].astype(np.float64)
    return float(np.mean(d * d))


# ---- the study ----------------------------------------------------------------------------------

@dataclass
class Terrain:
    """A DEM ready to render: quantised heights (its pyramid), colour texture, height scale."""

    pyr: heightmap.Pyramid
    texture: npt.NDArray[Any]     # (Th, Tw, 3) float, any size (it spans the map)
    height_scale: float

    @property
    def heights(self) -> F64:
        """The quantised heights every method sees, in [0, 1]."""
        return self.pyr.codes.astype(np.float64) / float(self.pyr.maxcode)

    @property
    def width(self) -> int:
        return self.pyr.width

    @property
    def height(self) -> int:
        return self.pyr.height


def make_terrain(h: npt.ArrayLike, height_scale: float, texture: npt.ArrayLike | None = None,
                 bits: int = 16) -> Terrain:
    """Quantise a DEM (unorm ``bits``), build its pyramid and (without one) its texture."""
    s = float(height_scale)
    if not (np.isfinite(s) and s > 0):
        raise ValueError(f"height_scale must be a positive number, got {height_scale!r}")
    pyr = heightmap.build(np.asarray(h, dtype=np.float64), bits=bits)
    tex = terrain_texture(pyr.codes / float(pyr.maxcode), s) if texture is None else \
        np.asarray(texture)
    if tex.ndim != 3 or tex.shape[2] < 3:
        raise ValueError(f"a texture is (H, W, 3+) RGB, got shape {tex.shape}")
    return Terrain(pyr, tex[..., :3], s)


@dataclass
class MethodRender:
    """One method at one mesh resolution: the texture coordinate per ray and statistics."""

    u: F64
    v: F64
    reads: float          # mean height-map reads per pixel on the mesh (0 for tessellation)
    left_map: int         # pixels whose corrected coordinate left the map (kept the mesh's)


def corrected(terrain: Terrain, rays: Rays, mh: MeshHit, method: str,
              cell: int, binary_span: float = 1.0) -> MethodRender:
    """Texture coordinates of ``method`` (a name of :data:`METHODS`) on the mesh hit ``mh``."""
    if method == "tessellation":
        return MethodRender(mh.u, mh.v, 0.0, 0)
    ok = mh.hit
    sub = rays.subset(ok)
    t0, nrm = mh.t[ok], mh.normal[ok]
    d = terrain.height_scale
    res: TraceResult
    if method in ("parallax-0.5", "parallax-1"):
        res = approx.parallax(terrain.pyr, sub, limit=0.5 if method == "parallax-0.5" else 1.0,
                              depth_scale=d, t_start=t0, base_normal=nrm)
    elif method == "parallax-iter":
        res = approx.parallax_iter(terrain.pyr, sub, iterations=2, limit=1.0, depth_scale=d,
                                   t_start=t0, base_normal=nrm)
    elif method == "binary":
        ell = np.hypot(np.hypot(sub.du, sub.dv), d)      # arc length per unit of t
        dt = binary_span * cell / ell
        res = approx.binary(terrain.pyr, sub, steps=3, lo=t0 - dt, hi=t0 + dt)
    else:
        raise ValueError(f"unknown terrain method {method!r} (known: {', '.join(METHODS)})")
    u, v = mh.u.copy(), mh.v.copy()
    got = res.hit
    sel = np.nonzero(ok)[0]
    u[sel[got]], v[sel[got]] = res.u[got], res.v[got]
    return MethodRender(u, v, float(res.iterations.sum()) / max(int(ok.sum()), 1),
                        int((~got).sum()))


@dataclass
class StudyResult:
    """What :func:`run_study` measured (terrain.json is its :meth:`to_json`)."""

    cells: list[int]
    triangles: list[int]
    mse: dict[str, list[float]]
    reads: dict[str, list[float]]
    left_map: dict[str, list[int]]
    mesh_cells_visited: list[float]
    pixels: int
    image_size: tuple[int, int]
    reference_hits: int
    reference_iterations: float
    images: dict[str, U8] = field(default_factory=dict)
    seconds: float = 0.0

    def improvement(self) -> dict[str, float]:
        """Fig. 11 b): the inverse slope of each method's MSE against tessellation's (least
        squares through the origin over the resolutions): how many times smaller its MSE is."""
        x = np.asarray(self.mse["tessellation"])
        out = {}
        for m in METHODS[1:]:
            y = np.asarray(self.mse[m])
            slope = float(x @ y / (x @ x)) if x @ x > 0 else float("nan")
            out[m] = 1.0 / slope if slope > 0 else float("nan")
        return out

    def to_json(self) -> dict[str, Any]:
        return {"mse": self.mse, "triangles": self.triangles, "cells": self.cells,
                "mse_unit": "8-bit RGB, mean over covered pixels and channels",
                "improvement_over_tessellation": self.improvement(),
                "reads_per_pixel": self.reads, "left_map": self.left_map,
                "mesh_cells_visited_per_ray": self.mesh_cells_visited,
                "pixels": self.pixels, "image_size": list(self.image_size),
                "reference": {"method": "park", "engine": "f64", "hits": self.reference_hits,
                              "iterations_per_ray": self.reference_iterations},
                "seconds": self.seconds}


def default_cells(width: int, height: int) -> list[int]:
    """Mesh cell sizes from a quarter of the map's larger side (4 x 4 cells) down to 1."""
    top = max(1, max(width, height) // 4)
    out, c = [], 1
    while c <= top:
        out.append(c)
        c *= 2
    return out[::-1]


def render_reference(terrain: Terrain, rays: Rays) -> TraceResult:
    """The exact full-resolution hit of every ray (pyramidal traversal ``park``, f64)."""
    return traverse.trace(terrain.pyr, rays, "park", "f64")


def run_study(terrain: Terrain, cam: Camera, cells: Sequence[int], *,
              binary_span: float = 1.0, keep_images: bool = True,
              progress: Callable[[int, int], None] | None = None) -> StudyResult:
    """Render the reference and every method at every mesh cell size; MSE against the reference.

    ``progress(done, total)`` is called after each mesh resolution.
    """
    t_start = time.time()
    cr = cam.rays()
    rays, row, col = cr.rays, cr.row, cr.col
    mask = np.zeros((cam.image_h, cam.image_w), bool)
    mask[row, col] = True
    ih, iw = cam.image_h, cam.image_w
    ref = render_reference(terrain, rays)
    ref_img = to_image(sample_nearest(terrain.texture, ref.u, ref.v, terrain.width,
                                      terrain.height), row, col, ih, iw)
    heights = terrain.heights
    out: dict[str, list[float]] = {m: [] for m in METHODS}
    reads: dict[str, list[float]] = {m: [] for m in METHODS}
    left: dict[str, list[int]] = {m: [] for m in METHODS}
    tris, visited = [], []
    images: dict[str, U8] = {"reference": ref_img} if keep_images else {}
    for k, c in enumerate(cells):
        mesh = build_mesh(heights, int(c))
        mh = cast_mesh(mesh, rays, terrain.height_scale)
        tris.append(mesh.triangles)
        visited.append(float(mh.cells.mean()) if len(rays) else 0.0)
        for m in METHODS:
            r = corrected(terrain, rays, mh, m, int(c), binary_span)
            img = to_image(sample_nearest(terrain.texture, r.u, r.v, terrain.width,
                                          terrain.height), row, col, ih, iw)
            out[m].append(mse(img, ref_img, mask))
            reads[m].append(r.reads)
            left[m].append(r.left_map)
            if keep_images:
                images[f"{m}_cell{int(c)}"] = img
        if progress is not None:
            progress(k + 1, len(cells))
    return StudyResult([int(c) for c in cells], tris, out, reads, left, visited, len(rays),
                       (ih, iw), int(ref.hit.sum()),
                       float(ref.iterations.mean()) if len(rays) else 0.0, images,
                       time.time() - t_start)


# ---- the pyramidal traversal of the DEM (the traversal paper's future work) ---------------------

def pyramidal(terrain: Terrain, cam: Camera, method: str = "park",
              rtl: RtlTrace | None = None, rtl_latency: int = 20) -> dict[str, Any]:
    """Ray-cast the DEM with the exact pyramidal traversal on the f64, f24 and (``rtl``) RTL
    engines; iterations per ray, agreement with f64, the f24 image's MSE against the f64
    reference and, for the RTL, the clock count and whether it equals f24 bit for bit.

    ``rtl``: the RTL trace engine, called as ``rtl(pyr, rays, method, latency=rtl_latency)`` and
    returning (TraceResult, statistics) -- ``tb.harness.traverse_system.trace_rtl``; the model
    itself does not drive the RTL."""
    cr = cam.rays()
    rays, row, col = cr.rays, cr.row, cr.col
    mask = np.zeros((cam.image_h, cam.image_w), bool)
    mask[row, col] = True
    out: dict[str, Any] = {"method": method, "rays": len(rays),
                           "map": [terrain.height, terrain.width], "bits": terrain.pyr.bits}
    res: dict[str, TraceResult] = {}
    imgs: dict[str, U8] = {}
    for eng in ("f64", "f24"):
        t0 = time.time()
        r = traverse.trace(terrain.pyr, rays, method, eng)
        sec = time.time() - t0
        res[eng] = r
        imgs[eng] = to_image(sample_nearest(terrain.texture, r.u, r.v, terrain.width,
                                            terrain.height), row, col, cam.image_h, cam.image_w)
        out[eng] = {"iterations_per_ray": float(r.iterations.mean()) if len(rays) else 0.0,
                    "max_iterations": int(r.iterations.max(initial=0)),
                    "hits": int(r.hit.sum()), "seconds": sec}
    same = _same_texel(res["f64"], res["f24"])
    out["f24"]["same_hit_texel_as_f64"] = same
    out["f24"]["mse_vs_f64"] = mse(imgs["f24"], imgs["f64"], mask)
    if rtl is not None:
        t0 = time.time()
        r, st = rtl(terrain.pyr, rays, method, latency=rtl_latency)
        f24 = res["f24"]
        identical = bool(np.array_equal(r.hit, f24.hit) and np.array_equal(r.invalid, f24.invalid)
                         and np.array_equal(r.iterations, f24.iterations)
                         and all(np.array_equal(getattr(r, k), getattr(f24, k), equal_nan=True)
                                 for k in ("t", "u", "v")))
        out["rtl"] = {"cycles": int(st["cycles"]), "iterations": int(st["iterations"]),
                      "iterations_per_ray": float(r.iterations.mean()) if len(rays) else 0.0,
                      "cycles_per_iteration": float(st["cycles"]) / max(int(st["iterations"]), 1),
                      "height_cache_hit_rate": st.get("height_cache_hit_rate"),
                      "mem_bytes": st.get("mem_bytes"), "axi_latency": rtl_latency,
                      "identical_to_f24": identical, "seconds": time.time() - t0}
    out["images"] = imgs
    return out


def _same_texel(a: TraceResult, b: TraceResult) -> float:
    """Share of rays with the same hit flag and, for hits, the same texel (floor u, floor v)."""
    n = len(a.hit)
    if n == 0:
        return 1.0
    both = a.hit & b.hit
    with np.errstate(invalid="ignore"):
        same = (np.floor(a.u) == np.floor(b.u)) & (np.floor(a.v) == np.floor(b.v))
    agree = (a.hit == b.hit) & (~both | same)
    return float(agree.mean())
