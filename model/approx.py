# SPDX-License-Identifier: Apache-2.0
"""Approximate (unsafe) inverse displacement mapping methods: the golden model's baselines.

Every method has the signature ``fn(pyr, rays, **params) -> TraceResult`` and traces the box
(nearest-texel) height field of ``docs/conventions.md``: texel (i, j) with h = codes[i, j] /
maxcode covers u in [j, j+1), v in [i, i+1) and is solid from depth s = 1 - h down to depth 1.
A ray is position(t) = (u0 + du t, v0 + dv t) at depth t in [0, 1].  The methods are vectorised
over rays (lock-step loops over a fixed, small number of steps; no per-ray Python loops).

Common definitions
------------------
* **Read** (= one iteration, as in the paper's tables): one fetch of the height map (or, for
  ``distance``, of the 3-D distance map) at a position.  A read at position (u, v) returns the
  surface depth ``s = 1 - h[floor v, floor u]``; the signed gap of the ray there is
  ``g(t) = t - s`` (g >= 0: the point is at or below the surface, i.e. solid).
* **Outside**: a sample position outside the map's own extent [0, W) x [0, H) is detected before
  the fetch, is *not* a read, and ends the ray as a miss ("a method that steps outside reports a
  miss").  The map extent is convex and a valid ray starts inside it, so once outside a ray never
  comes back.
* **Hit**: an approximate method always produces an intersection *estimate*; ``hit`` is true iff
  the method finished without stepping outside the map (its final point then lies in the map).
  Since depth 1 is always solid in the box model, the searches always find a bracket, so a miss
  means exactly "left the map".  ``t`` is in [0, 1], ``(u, v) = position(t)``; NaN where no hit.
  Whether the estimate really lies in the solid can be checked, without counting a read, with
  :func:`solid_at`.
* **Invalid** rays (``Rays.invalid``: a NaN/inf number or a start outside the map): ``hit`` false,
  ``invalid`` true, ``iterations`` 0.
* ``depth_scale`` D: the thickness of the displacement volume in level-0 texels (the scene's depth
  scale; default :data:`DEFAULT_DEPTH_SCALE`).  The ray (du, dv) per unit depth is the geometric
  direction (du, dv, D) in texel units, its length per unit of t is ``L = |(du, dv, D)|`` and the
  cosine of the view angle from the surface normal is ``cos_theta = D / L``.  Only offset limiting
  and the distance-map metric depend on D.

Methods and exact iteration counts
----------------------------------
``parallax`` (limit=1.0, depth_scale=D) -- parallax mapping with offset limiting (Kaneko 2001,
Welsh 2004, Gonzalez et al. 2016 Fig. 7/8).  One read at the entry (u0, v0) gives s.  Unlimited
parallax moves to the plane of that height: offset = (du, dv) * s, i.e. t = s.  Gonzalez's
offset limiting divides by max(V.z, limit) instead of V.z (V the unit view vector), which in this
parameterisation is

    t = s * c,   c = min(1, cos_theta / limit)      (c = 1 for limit = 0: no limiting)

limit = 1 is Welsh's approximation (t = s cos_theta: the offset is s * V.xy, never longer than
the height term); limit = 0.5 leaves views within 60 degrees of the normal unlimited.
Iterations: 1.  Exact for vertical rays and, on a flat plane, whenever c = 1; otherwise the
estimate on a flat plane is t = s c (the documented underestimate of offset limiting).

``parallax-iter`` (iterations=2, limit=1.0, depth_scale=D) -- iterative parallax (Welsh 2004;
Premecz 2006; Gonzalez 2016 Fig. 9, with the offset taken relative to the ray's current depth
rather than a fixed base, so that a converged point stays put):

    t_0 = 0,   t_{k+1} = t_k + c (s(P(t_k)) - t_k)        (t_{k+1} = s(P(t_k)) when c = 1)

one read per step; a step may move backwards (a point below the surface).  ``parallax`` is the
case iterations = 1.  Iterations: ``iterations`` (fewer only if a step leaves the map).  On a flat
plane at depth s: t_n = s (1 - (1 - c)^n); exact for vertical rays.

Base surface (both parallax methods; Gonzalez et al. 2016 Section 2.2, a coarse tessellated mesh
as the base instead of the top plane).  ``t_start`` (per ray, default 0) starts the iteration at
t_0 = t_start: the depth where the ray meets the base surface.  ``base_normal`` (per ray, (N, 3),
components along +u, +v and up in texel units, default (0, 0, 1)) is the unit normal n of the
base there; the step then reaches the plane parallel to the base through the read surface point
(their Fig. 6/7), with offset limiting applied to V.n instead of V.z:

    c = cos_theta n_z / max(V.n, limit)      (V.n for limit = 0; c = 1 where that is <= 0)

V = (-du, -dv, D) / L the unit vector towards the eye.  For n = (0, 0, 1) this is the formula
above (and without ``base_normal`` the code path is the original one, bit for bit).

``binary`` (steps=3) -- binary search with a final secant step (Policarpo 2005's binary search;
Gonzalez 2016 Fig. 10 with PAR_ITER = 3).  Bracket lo = 0 (assumed above), hi = 1 (depth 1 is
solid).  Each step reads the midpoint m: g(m) >= 0 -> hi = m, else lo = m.  The secant needs the
gap at both bracket ends; an end that no midpoint replaced (all midpoints fell on one side) is read
once after the loop (t = 0 or t = 1).  Result: t = lo + (hi - lo) (-g_lo) / (g_hi - g_lo)
(t = lo when g_lo >= 0, i.e. a solid entry).  Iterations: steps + [an end was never replaced]
(= steps + 1 exactly when all midpoints are on one side; steps = 0 reads both ends: 2).
Exact (up to rounding) whenever g is linear on the final bracket: vertical rays, flat planes.
If g is monotone along the ray (a single crossing), |t - t*| <= 2^-steps.
``lo`` / ``hi`` (per ray, defaults 0 and 1) give another initial bracket, e.g. Gonzalez 2016's
segment of the ray around its hit with a coarse base mesh; a bracket end outside the map that
has to be read for the secant ends the ray as a miss like any other outside read, and the
"above / solid" assumptions of the ends are not checked (the secant uses the gaps as read).

``relief`` (linear_steps=16, binary_steps=6) -- relief mapping (Policarpo et al. 2005).  Linear
search at t_k = k / n, k = 1..n, one read each, stopping at the first solid sample (g >= 0); then
binary search of [t_{k-1}, t_k]: binary_steps midpoint reads keeping lo free / hi solid.  Result
t = hi, the last sample found solid (so t >= t*, the exact first hit).  This is Policarpo's
shader minus its first binary read, which re-reads the already known solid t_k.  Iterations:
k + binary_steps.  If the first solid run of the ray (from t* on) is at least 1/n long, the bracket
holds only that crossing and t* <= t <= t* + 2^-binary_steps / n.  Vertical rays: within that
bound (binary search alone is not exact).

``pom`` (steps=16) -- parallax occlusion mapping (Brawley & Tatarchuk 2005; Tatarchuk 2006):
the same linear search, then the intersection of the ray with the line through the last two
samples (secant): t = t_{k-1} + (t_k - t_{k-1}) (-g_{k-1}) / (g_k - g_{k-1}).  For k = 1 the
previous sample t_0 = 0 has not been read and is read once (Tatarchuk's shader assumes a height
of 1 there instead).  Iterations: k + [k = 1].  Exact (up to rounding) for vertical rays and flat
planes; |t - t*| <= 1/n when the first solid run is at least 1/n long.

``distance`` (iterations=16, slices=16, texels_per_voxel=1, depth_scale=D) -- sphere tracing a
3-D distance map (Donnelly 2005), see :func:`build_distance_map`.  From t = 0: read the stored
distance d at the current point (nearest voxel); d = 0 means the point is in a solid voxel and
the tracer stops; otherwise t += d / L; t >= 1 is clamped to 1 (the floor, always solid) and
stops.  Iterations: reads until a read returns 0, t reaches 1 or ``iterations`` reads are done.
The stored distances are centre-to-centre (as in Donnelly's chapter), so a step taken from a
voxel corner can clip a feature by up to half a voxel diagonal: like the others, not a safe method.
Tolerance: a converged point lies in a voxel that intersects the solid (the voxelisation is
conservative, so it can be above the true surface by less than one slice).  With
texels_per_voxel = 1, a vertical ray stays in its own column, never passes the column's first
solid slice and, when depth_scale <= slices (every step then advances t by at least 1/slices),
converges within ``slices`` reads: |t - (1 - h)| < 1 / slices (t = 1 exactly when h = 0).

Unknown method names and bad parameter values raise ``ValueError``; a parameter a method does not
take raises ``TypeError``.
"""
from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy.ndimage import distance_transform_edt

from model.heightmap import Pyramid
from model.rays import Rays, TraceResult

F64 = npt.NDArray[np.float64]
B = npt.NDArray[np.bool_]
I64 = npt.NDArray[np.int64]

#: Default thickness of the displacement volume in level-0 texels (texels per unit of depth t).
DEFAULT_DEPTH_SCALE = 16.0


# ---- shared machinery ------------------------------------------------------------------------

def surface_depth(pyr: Pyramid) -> F64:
    """Surface depth per texel, ``1 - codes / maxcode`` (the solid starts there), shape (H, W)."""
    return 1.0 - pyr.codes.astype(np.float64) / float(pyr.maxcode)


@dataclass
class _Ctx:
    """Per-call working state: sanitised ray arrays (zeros on invalid rays) and the masks."""

    sd: F64          # surface depth map (H, W)
    u0: F64
    v0: F64
    du: F64
    dv: F64
    invalid: B
    iters: I64

    @classmethod
    def make(cls, pyr: Pyramid, rays: Rays) -> "_Ctx":
        inv = rays.invalid(pyr.width, pyr.height)
        ok = ~inv

        def clean(a: F64) -> F64:
            return np.where(ok, np.asarray(a, dtype=np.float64), 0.0)

        return cls(surface_depth(pyr), clean(rays.u0), clean(rays.v0), clean(rays.du),
                   clean(rays.dv), inv, np.zeros(len(rays), np.int64))

    @property
    def valid(self) -> B:
        return ~self.invalid

    def pos(self, t: F64) -> tuple[F64, F64]:
        return self.u0 + self.du * t, self.v0 + self.dv * t

    def inside(self, t: F64) -> B:
        """Position(t) inside [0, W) x [0, H) (no read)."""
        u, v = self.pos(t)
        hh, ww = self.sd.shape
        with np.errstate(invalid="ignore"):
            return (u >= 0) & (u < ww) & (v >= 0) & (v < hh)

    def read(self, t: F64, want: B) -> tuple[F64, B]:
        """Read the surface depth at position(t) for the rays in ``want``.

        Returns (s, inside): ``inside`` marks the rays of ``want`` whose position is in the map;
        exactly those are read and counted; ``s`` is NaN elsewhere.
        """
        u, v = self.pos(t)
        hh, ww = self.sd.shape
        with np.errstate(invalid="ignore"):
            ins = want & (u >= 0) & (u < ww) & (v >= 0) & (v < hh)
        s = np.full(t.shape, np.nan)
        idx = np.nonzero(ins)[0]
        s[idx] = self.sd[np.floor(v[idx]).astype(np.intp), np.floor(u[idx]).astype(np.intp)]
        self.iters += ins
        return s, ins

    def result(self, t: F64, hit: B) -> TraceResult:
        hit = hit & self.valid
        tt = np.where(hit, t, np.nan)
        u, v = self.pos(np.where(hit, t, 0.0))
        return TraceResult(tt, np.where(hit, u, np.nan), np.where(hit, v, np.nan), hit,
                           self.invalid.copy(), np.where(self.valid, self.iters, 0))


def _cos_theta(du: F64, dv: F64, depth_scale: float) -> F64:
    """D / |(du, dv, D)|: cosine of the angle between the ray and the surface normal."""
    return depth_scale / np.hypot(np.hypot(du, dv), depth_scale)


def _check_depth_scale(depth_scale: float) -> float:
    d = float(depth_scale)
    if not (np.isfinite(d) and d > 0):
        raise ValueError(f"depth_scale must be a positive number, got {depth_scale!r}")
    return d


def _check_int(name: str, value: int, lo: int) -> int:
    if int(value) != value or value < lo:
        raise ValueError(f"{name} must be an integer >= {lo}, got {value!r}")
    return int(value)


def solid_at(pyr: Pyramid, rays: Rays, t: npt.ArrayLike) -> B:
    """True where position(t) is in the map and at/below the surface (t >= 1 - h); NaN t -> False.

    A classification helper for results (not a read of any method).
    """
    tt = np.asarray(t, dtype=np.float64)
    with np.errstate(invalid="ignore"):
        u, v = rays.u0 + rays.du * tt, rays.v0 + rays.dv * tt
        ins = (u >= 0) & (u < pyr.width) & (v >= 0) & (v < pyr.height) & np.isfinite(tt)
    out = np.zeros(tt.shape, bool)
    idx = np.nonzero(ins)[0]
    sd = surface_depth(pyr)
    out[idx] = tt[idx] >= sd[np.floor(v[idx]).astype(np.intp), np.floor(u[idx]).astype(np.intp)]
    return out


# ---- parallax family -------------------------------------------------------------------------

def _per_ray(name: str, value: npt.ArrayLike, n: int, shape: tuple[int, ...] = ()) -> F64:
    """A per-ray float64 parameter of shape (n, *shape) (a scalar is broadcast), all finite."""
    a = np.asarray(value, dtype=np.float64)
    try:
        a = np.broadcast_to(a, (n, *shape)).copy()
    except ValueError:
        raise ValueError(f"{name} must have shape ({n}, {', '.join(map(str, shape))}) "
                         f"or broadcast to it, got {np.shape(value)}") from None
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    return a


def _base_factor(cx: _Ctx, d: float, lim: float, base_normal: npt.ArrayLike) -> F64:
    """Gonzalez 2016's step factor on a tilted base: cos_theta n_z / max(V.n, limit)."""
    n = _per_ray("base_normal", base_normal, len(cx.u0), (3,))
    n = n / np.linalg.norm(n, axis=1, keepdims=True)
    ell = np.hypot(np.hypot(cx.du, cx.dv), d)
    vn = (-cx.du * n[:, 0] - cx.dv * n[:, 1] + d * n[:, 2]) / ell   # V.n
    den = np.maximum(vn, lim) if lim > 0.0 else vn
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0.0, (d / ell) * n[:, 2] / den, 1.0)


def parallax_iter(pyr: Pyramid, rays: Rays, *, iterations: int = 2, limit: float = 1.0,
                  depth_scale: float = DEFAULT_DEPTH_SCALE, t_start: npt.ArrayLike | None = None,
                  base_normal: npt.ArrayLike | None = None) -> TraceResult:
    """Iterative parallax mapping with offset limiting (see the module docstring).

    ``t_start`` / ``base_normal``: the optional per-ray base surface (module docstring).
    """
    n = _check_int("iterations", iterations, 1)
    lim = float(limit)
    if not 0.0 <= lim <= 1.0:
        raise ValueError(f"limit must be in [0, 1], got {limit!r}")
    d = _check_depth_scale(depth_scale)
    cx = _Ctx.make(pyr, rays)
    if base_normal is None:
        c = np.ones(len(rays)) if lim == 0.0 else np.minimum(1.0, _cos_theta(cx.du, cx.dv, d) / lim)
    else:
        c = _base_factor(cx, d, lim, base_normal)
    t = np.zeros(len(rays)) if t_start is None else np.where(
        cx.valid, _per_ray("t_start", t_start, len(rays)), 0.0)
    active = cx.valid.copy()
    for _ in range(n):
        s, ins = cx.read(t, active)
        active = ins
        t = np.where(ins, np.where(c == 1.0, s, t + c * (s - t)), t)
    return cx.result(t, active & cx.inside(t))


def parallax(pyr: Pyramid, rays: Rays, *, limit: float = 1.0,
             depth_scale: float = DEFAULT_DEPTH_SCALE, t_start: npt.ArrayLike | None = None,
             base_normal: npt.ArrayLike | None = None) -> TraceResult:
    """Parallax mapping with offset limiting: one read, t = s * min(1, cos_theta / limit)
    (from the top plane; on a base surface t = t_start + c (s - t_start), module docstring)."""
    return parallax_iter(pyr, rays, iterations=1, limit=limit, depth_scale=depth_scale,
                         t_start=t_start, base_normal=base_normal)


# ---- binary search with secant ---------------------------------------------------------------

def binary(pyr: Pyramid, rays: Rays, *, steps: int = 3, lo: npt.ArrayLike | None = None,
           hi: npt.ArrayLike | None = None) -> TraceResult:
    """Binary search over t in [lo, hi] (default [0, 1]) with a final secant step (see the
    module docstring)."""
    n = _check_int("steps", steps, 0)
    cx = _Ctx.make(pyr, rays)
    m_ = len(rays)
    lo = np.zeros(m_) if lo is None else np.where(cx.valid, _per_ray("lo", lo, m_), 0.0)
    hi = np.ones(m_) if hi is None else np.where(cx.valid, _per_ray("hi", hi, m_), 1.0)
    if np.any(lo > hi):
        raise ValueError("binary: the bracket needs lo <= hi on every ray")
    glo, ghi = np.full(m_, np.nan), np.full(m_, np.nan)
    active = cx.valid.copy()
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        s, ins = cx.read(mid, active)
        active = ins
        g = mid - s
        below = ins & (g >= 0)
        above = ins & (g < 0)
        hi, ghi = np.where(below, mid, hi), np.where(below, g, ghi)
        lo, glo = np.where(above, mid, lo), np.where(above, g, glo)
    # Bracket ends never replaced by a midpoint: read them once for the secant.
    need = active & np.isnan(glo)
    s, ins = cx.read(lo, need)        # lo = 0 (default): the entry, inside for every valid ray
    active = active & ~(need & ~ins)
    glo = np.where(need, lo - s, glo)
    need = active & np.isnan(ghi)
    s, ins = cx.read(hi, need)        # hi = 1: may be outside the map -> miss
    active = active & ~(need & ~ins)
    ghi = np.where(need, hi - s, ghi)
    with np.errstate(invalid="ignore", divide="ignore"):
        sec = lo + (hi - lo) * (-glo) / (ghi - glo)
    t = np.where(glo >= 0, lo, sec)
    return cx.result(t, active)


# ---- linear search: relief mapping and parallax occlusion mapping ----------------------------

@dataclass
class _Linear:
    found: B         # a solid sample was found (ray still valid and in the map)
    k: I64           # index of the first solid sample (0 where not found)
    t_prev: F64      # t_{k-1}
    g_prev: F64      # gap at t_{k-1} (NaN for k = 1: not read)
    t_k: F64
    g_k: F64


def _linear_search(cx: _Ctx, n: int) -> _Linear:
    """Samples t_k = k/n, k = 1..n, stopping each ray at its first solid sample."""
    m_ = len(cx.u0)
    found = np.zeros(m_, bool)
    k_hit = np.zeros(m_, np.int64)
    t_prev, g_prev = np.zeros(m_), np.full(m_, np.nan)
    t_k, g_k = np.zeros(m_), np.full(m_, np.nan)
    active = cx.valid.copy()
    for k in range(1, n + 1):
        if not active.any():
            break
        tk = np.full(m_, k / n)
        s, ins = cx.read(tk, active)
        g = tk - s
        solid = ins & (g >= 0)
        free = ins & ~solid
        found |= solid
        k_hit = np.where(solid, k, k_hit)
        t_k, g_k = np.where(solid, tk, t_k), np.where(solid, g, g_k)
        t_prev, g_prev = np.where(free, tk, t_prev), np.where(free, g, g_prev)
        active = free
    return _Linear(found, k_hit, t_prev, g_prev, t_k, g_k)


def relief(pyr: Pyramid, rays: Rays, *, linear_steps: int = 16,
           binary_steps: int = 6) -> TraceResult:
    """Relief mapping: linear search then binary search; t is the last solid sample."""
    n = _check_int("linear_steps", linear_steps, 1)
    b = _check_int("binary_steps", binary_steps, 0)
    cx = _Ctx.make(pyr, rays)
    ls = _linear_search(cx, n)
    lo, hi = ls.t_prev.copy(), ls.t_k.copy()
    for _ in range(b):
        mid = 0.5 * (lo + hi)
        s, _ = cx.read(mid, ls.found)  # between two in-map points: always inside
        solid = ls.found & (mid >= s)
        hi = np.where(solid, mid, hi)
        lo = np.where(ls.found & ~solid, mid, lo)
    return cx.result(hi, ls.found)


def pom(pyr: Pyramid, rays: Rays, *, steps: int = 16) -> TraceResult:
    """Parallax occlusion mapping: linear search then the secant of the last two samples."""
    n = _check_int("steps", steps, 1)
    cx = _Ctx.make(pyr, rays)
    ls = _linear_search(cx, n)
    need = ls.found & (ls.k == 1)
    s, _ = cx.read(np.zeros(len(rays)), need)  # t_0 = 0, the entry
    g_prev = np.where(need, -s, ls.g_prev)
    with np.errstate(invalid="ignore", divide="ignore"):
        sec = ls.t_prev + (ls.t_k - ls.t_prev) * (-g_prev) / (ls.g_k - g_prev)
    t = np.where(g_prev >= 0, ls.t_prev, sec)
    return cx.result(t, ls.found)


# ---- distance mapping (sphere tracing) -------------------------------------------------------

@dataclass(frozen=True)
class DistanceMap:
    """A 3-D distance map over the displacement volume (Donnelly 2005).

    Voxel (z, i, j) covers u in [j k, (j+1) k), v in [i k, (i+1) k) (k = ``texels_per_voxel``)
    and depth [z / Z, (z+1) / Z) (Z = ``slices``).  It is *solid* when that box meets the solid,
    i.e. (z+1)/Z > 1 - hmax with hmax the maximum height of the texels of the block inside the
    map (conservative: the true solid lies inside the solid voxels).  ``dist[z, i, j]`` (float32)
    is the Euclidean distance from the voxel's centre to the nearest solid voxel's centre, in
    level-0 texel units of the metric (u, v, D * depth): voxel spacing (D/Z, k, k) for the axes
    (z, i, j) (``scipy.ndimage.distance_transform_edt`` with that anisotropic ``sampling``); 0 in
    solid voxels, +inf everywhere when no voxel is solid.  A step of d along a ray advances t by
    d / |(du, dv, D)|.
    """

    dist: npt.NDArray[np.float32]   # (slices, ceil(H/k), ceil(W/k))
    width: int
    height: int
    slices: int
    texels_per_voxel: int
    depth_scale: float

    def lookup(self, u: F64, v: F64, t: F64) -> F64:
        """Nearest-voxel distance at points inside the map with t in [0, 1]."""
        k, z = self.texels_per_voxel, self.slices
        zi = np.minimum(np.floor(t * z).astype(np.intp), z - 1)
        return self.dist[zi, np.floor(v / k).astype(np.intp),
                         np.floor(u / k).astype(np.intp)].astype(np.float64)


def build_distance_map(pyr: Pyramid, *, slices: int = 16, texels_per_voxel: int = 1,
                       depth_scale: float = DEFAULT_DEPTH_SCALE) -> DistanceMap:
    """Voxelise the box height field and compute its 3-D distance map (see :class:`DistanceMap`)."""
    z = _check_int("slices", slices, 1)
    k = _check_int("texels_per_voxel", texels_per_voxel, 1)
    d = _check_depth_scale(depth_scale)
    hh, ww = pyr.height, pyr.width
    hc, wc = -(-hh // k), -(-ww // k)
    pad = np.zeros((hc * k, wc * k), np.int64)
    pad[:hh, :ww] = pyr.codes
    hmax = pad.reshape(hc, k, wc, k).max(axis=(1, 3))
    sdb = 1.0 - hmax / float(pyr.maxcode)                      # block surface depth
    bottoms = (np.arange(z, dtype=np.float64) + 1.0) / z        # (z+1)/Z
    solid = bottoms[:, None, None] > sdb[None, :, :]
    if solid.any():
        dist = distance_transform_edt(~solid, sampling=(d / z, float(k), float(k)))
    else:
        dist = np.full(solid.shape, np.inf)
    return DistanceMap(np.asarray(dist, np.float32), ww, hh, z, k, d)


_DMAP_CACHE: OrderedDict[tuple, DistanceMap] = OrderedDict()
_DMAP_CACHE_SIZE = 4


def cached_distance_map(pyr: Pyramid, *, slices: int = 16, texels_per_voxel: int = 1,
                        depth_scale: float = DEFAULT_DEPTH_SCALE) -> DistanceMap:
    """:func:`build_distance_map` memoised on the map's content and the parameters (LRU of 4)."""
    key = (hashlib.sha1(np.ascontiguousarray(pyr.codes).tobytes()).hexdigest(), pyr.codes.shape,
           pyr.bits, int(slices), int(texels_per_voxel), float(depth_scale))
    if key in _DMAP_CACHE:
        _DMAP_CACHE.move_to_end(key)
        return _DMAP_CACHE[key]
    dm = build_distance_map(pyr, slices=slices, texels_per_voxel=texels_per_voxel,
                            depth_scale=depth_scale)
    _DMAP_CACHE[key] = dm
    while len(_DMAP_CACHE) > _DMAP_CACHE_SIZE:
        _DMAP_CACHE.popitem(last=False)
    return dm


def distance(pyr: Pyramid, rays: Rays, *, iterations: int = 16, dmap: DistanceMap | None = None,
             slices: int | None = None, texels_per_voxel: int | None = None,
             depth_scale: float | None = None) -> TraceResult:
    """Sphere tracing of a 3-D distance map (see the module docstring).

    ``dmap`` (from :func:`build_distance_map`) is used as given; without it the map is built with
    ``slices`` (16), ``texels_per_voxel`` (1) and ``depth_scale`` (:data:`DEFAULT_DEPTH_SCALE`)
    and cached per map content.  Resolution parameters that contradict a given ``dmap`` are an
    error.
    """
    n = _check_int("iterations", iterations, 1)
    if dmap is None:
        dmap = cached_distance_map(
            pyr, slices=16 if slices is None else slices,
            texels_per_voxel=1 if texels_per_voxel is None else texels_per_voxel,
            depth_scale=DEFAULT_DEPTH_SCALE if depth_scale is None else depth_scale)
    else:
        for name, val in (("slices", slices), ("texels_per_voxel", texels_per_voxel),
                          ("depth_scale", depth_scale)):
            if val is not None and val != getattr(dmap, name):
                raise ValueError(f"{name}={val!r} contradicts the given distance map "
                                 f"({getattr(dmap, name)!r})")
        if (dmap.width, dmap.height) != (pyr.width, pyr.height):
            raise ValueError("the distance map was built for a map of another size")
    cx = _Ctx.make(pyr, rays)
    step_scale = 1.0 / np.hypot(np.hypot(cx.du, cx.dv), dmap.depth_scale)   # 1 / L
    t = np.zeros(len(rays))
    active = cx.valid.copy()
    for _ in range(n):
        if not active.any():
            break
        ins = active & cx.inside(t)
        active = ins                      # stepped outside: miss (no read)
        idx = np.nonzero(ins)[0]
        ti = t[idx]
        dd = dmap.lookup(cx.u0[idx] + cx.du[idx] * ti, cx.v0[idx] + cx.dv[idx] * ti, ti)
        cx.iters[idx] += 1
        moving = dd > 0
        tn = ti + np.where(moving, dd, 0.0) * step_scale[idx]
        floor = tn >= 1.0
        t[idx] = np.minimum(tn, 1.0)
        done = ~moving | floor
        active[idx[done]] = False
    # A ray that stepped outside kept its (outside) t, so the final in-map check covers it, the
    # rays that ran out of iterations and the floor rays (position(1) may be outside).
    return cx.result(t, cx.valid & cx.inside(np.where(cx.valid, t, 0.0)))


# ---- registry --------------------------------------------------------------------------------

#: Approximate methods by their CONVENTIONS names.
APPROX_METHODS: dict[str, Callable[..., TraceResult]] = {
    "parallax": parallax,
    "parallax-iter": parallax_iter,
    "binary": binary,
    "relief": relief,
    "pom": pom,
    "distance": distance,
}


def trace_approx(name: str, pyr: Pyramid, rays: Rays, **params: object) -> TraceResult:
    """Run the approximate method ``name`` (a key of :data:`APPROX_METHODS`) with its parameters."""
    try:
        fn = APPROX_METHODS[name]
    except KeyError:
        raise ValueError(f"unknown approximate method {name!r} "
                         f"(known: {', '.join(APPROX_METHODS)})") from None
    return fn(pyr, rays, **params)
