# SPDX-License-Identifier: Apache-2.0
"""Normal-mapped Blinn-Phong shading and the model of the whole render pipeline, per pixel.

Everything per pixel is written with the injected arithmetic (:mod:`model.arith`), so the
``f24`` engine is the bit-exact specification of the pipeline's shading unit and the ``f64``
engine its reference.  Comparisons, max / min and the sign flip are exact in both engines.

Tangent space (as ``model.camera`` and ``model.scenes``): x = +u (along the map's columns),
y = +v (along its rows), z = up, out of the surface.  The quad's TBN is the identity, so
tangent space is also the world frame of the quad.

Shading of one hit (:func:`shade`), the op sequence of the hardware:

    inputs: C = (Cr, Cg, Cb) the filtered colour texel, M = (Mx, My, Mz) the filtered normal-map
            texel (encoded values in [0, 1]), (du, dv) the ray, D the depth scale (texels)
    constants (per frame, rounded once to the engine): the unit light vector l = LIGHT_DIR
            normalised, AMBIENT, KD, KS, D2 = mul(D, D), EPS = 2^-40
     1. n_c = sub(mul(M_c, 2), 1)                        decode 2c - 1 (mul by 2 is exact)
     2. nn  = add(add(mul(nx, nx), mul(ny, ny)), mul(nz, nz))
     3. nn  = max(nn, EPS)                               a zero normal shades as unlit, not NaN
     4. rn  = rsqrt(nn);   n_c = mul(n_c, rn)
     5. vv  = add(add(mul(du, du), mul(dv, dv)), D2)
     6. rv  = rsqrt(vv);   v = (mul(neg(du), rv), mul(neg(dv), rv), mul(D, rv))
            the unit vector from the hit towards the eye: the ray goes (du, dv) texels per
            D texels of depth, so back towards the eye is (-du, -dv, +D)
     7. h_c = add(l_c, v_c);  hh = add(add(mul(hx, hx), mul(hy, hy)), mul(hz, hz))
     8. rh  = rsqrt(hh);   h_c = mul(h_c, rh)
     9. ndl = max(dot(n, l), 0);   ndh = max(dot(n, h), 0)
            dot(a, b) = add(add(mul(ax, bx), mul(ay, by)), mul(az, bz))
    10. s = ndh; four times s = mul(s, s)                 s = ndh^16 (SHININESS)
    11. a = add(AMBIENT, mul(KD, ndl));   sp = mul(KS, s)
    12. c_c = add(mul(C_c, a), sp)                       white highlight
    13. c_c = min(max(c_c, 0), 1)
    14. out_c = to_index(add(mul(c_c, 255), 0.5))          unorm8 = floor(c 255 + 0.5)

``rsqrt`` is the engine's: 1 / numpy.sqrt for f64, the hardware's approximate unit
(``model.f24.rsqrt``, bit-exact with ``rtl/fp/f24_rsqrt.sv``) for f24 (:func:`rsqrt`).
The defaults: LIGHT_DIR = (-1, 0.5, 1.5) normalised (light from -u, slightly from +v, i.e. from
the left and the viewer's side in the project's views, 53 degrees above the surface),
AMBIENT = 0.3, KD = 0.7, KS = 0.25, SHININESS = 16 (so a lit flat texel is tex * 1.0 + 0.25).

Colours of pixels without a hit: a covered pixel whose ray misses (leaves the map) or is invalid
gets ``MISS_COLOUR``; a pixel the quad does not cover gets ``BACKGROUND``.

The pipeline per covered pixel (:func:`render_pixels`; ``model.texture`` documents steps 2-3):

    1. trace the ray (u0, v0, du, dv) with the method on the engine -> hit, t, (u, v)
    2. per texture (colour, normal map): the MIP level from Pl = Pl0 + t seg and the
       triangle's log2Pb (level 0 when MIP-mapping is off)
    3. bilinear lookups of the colour texture and the normal map at the hit (u, v)
    4. shading (above)

The pixel inputs the rasteriser hands over (:func:`pixel_inputs`): u0, v0 (the entry texel),
Pl0 (eye to entry point), the triangle id, its TBN and the unit view vector, computed in float64
by ``model.camera`` and rounded once to the engine.  Step 0, the view unit
(:func:`model.view.view_calc`, in the engine's arithmetic), makes the ray (du, dv) and seg (world
length per unit of t, D / |N . view|) from TBN and view.  :func:`render` runs the pipeline over
an image by tiles, optionally on several processes; every per-pixel step is element-wise, so
the image does not depend on the tiling or the number of processes.
"""
from __future__ import annotations

import inspect
from dataclasses import dataclass, field
from typing import Callable, NamedTuple

import numpy as np
import numpy.typing as npt

from . import f24, texture, traverse, view
from .arith import ENGINES, Arith
from .camera import Camera, Fragments
from .heightmap import Pyramid
from .rays import Rays, TraceResult
from .texture import Texture

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]
U8 = npt.NDArray[np.uint8]
B = npt.NDArray[np.bool_]

LIGHT_DIR = (-1.0, 0.5, 1.5)
"""Direction towards the light in tangent space (normalised before use)."""
AMBIENT = 0.3
KD = 0.7
KS = 0.25
SHININESS = 16  # = 2^4: four squarings
EPS = 2.0**-40
BACKGROUND = (24, 26, 34)
"""unorm8 RGB of pixels the quad does not cover."""
MISS_COLOUR = (0, 0, 0)
"""unorm8 RGB of covered pixels whose ray misses the height field or is invalid."""


# --------------------------------------------------------------------------------------------
# shading


def rsqrt(ar: Arith, x: npt.ArrayLike) -> F64:
    """1/sqrt(x) in the engine: numpy for f64, the approximate unit ``model.f24.rsqrt`` for f24."""
    xa = np.asarray(x, dtype=np.float64)
    if ar.name == "f24":
        return f24.to_float(f24.rsqrt(f24.from_float(xa)))
    with np.errstate(divide="ignore", invalid="ignore"):
        return 1.0 / np.sqrt(xa)


@dataclass(frozen=True)
class Material:
    """Lighting constants (the module docstring's defaults)."""

    light: tuple[float, float, float] = LIGHT_DIR
    ambient: float = AMBIENT
    kd: float = KD
    ks: float = KS

    def light_unit(self) -> F64:
        """The normalised light direction in float64 (each engine rounds it once)."""
        v = np.asarray(self.light, dtype=np.float64)
        n = float(np.linalg.norm(v))
        if not np.all(np.isfinite(v)) or n == 0.0:
            raise ValueError(f"bad light direction {self.light!r}")
        return v / n


def _dot(ar: Arith, a: list[F64], b: list[F64]) -> F64:
    return ar.add(ar.add(ar.mul(a[0], b[0]), ar.mul(a[1], b[1])), ar.mul(a[2], b[2]))


@np.errstate(all="ignore")  # NaN / Inf are ordinary values (model.arith)
def shade(ar: Arith, colour: npt.ArrayLike, nmap: npt.ArrayLike, du: npt.ArrayLike,
          dv: npt.ArrayLike, depth_scale: float, material: Material = Material()) -> U8:
    """The shading op sequence (module docstring) -> unorm8 RGB codes (N, 3).

    ``colour`` (N, 3+) and ``nmap`` (N, 3+) are engine values in [0, 1] (the filtered texels),
    ``du``, ``dv`` (N,) the rays, ``depth_scale`` D in texels.
    """
    col = ar.r(np.asarray(colour, dtype=np.float64))  # the filter's outputs: engine values already
    nm = ar.r(np.asarray(nmap, dtype=np.float64))
    du = ar.r(np.asarray(du, dtype=np.float64))
    dv = ar.r(np.asarray(dv, dtype=np.float64))
    n_pix = du.shape[0]

    def const(x: float) -> F64:
        return ar.r(np.full(n_pix, float(x)))

    lu = material.light_unit()
    light = [const(c) for c in lu]
    d = const(depth_scale)
    two, one, zero = const(2.0), const(1.0), const(0.0)
    # 1-4: the normal
    n = [ar.sub(ar.mul(nm[:, c], two), one) for c in range(3)]
    nn = np.maximum(_dot(ar, n, n), const(EPS))
    rn = rsqrt(ar, nn)
    n = [ar.mul(c, rn) for c in n]
    # 5-6: the view vector
    vv = ar.add(ar.add(ar.mul(du, du), ar.mul(dv, dv)), ar.mul(d, d))
    rv = rsqrt(ar, vv)
    v = [ar.mul(-du, rv), ar.mul(-dv, rv), ar.mul(d, rv)]
    # 7-8: the half vector
    h = [ar.add(light[c], v[c]) for c in range(3)]
    rh = rsqrt(ar, _dot(ar, h, h))
    h = [ar.mul(c, rh) for c in h]
    # 9-10: the cosines and the specular power
    ndl = np.maximum(_dot(ar, n, light), zero)
    s = np.maximum(_dot(ar, n, h), zero)
    for _ in range(4):
        s = ar.mul(s, s)
    # 11-14: combine, clamp, unorm8
    a = ar.add(const(material.ambient), ar.mul(const(material.kd), ndl))
    sp = ar.mul(const(material.ks), s)
    out = np.empty((n_pix, 3), dtype=np.uint8)
    k255, half = const(255.0), const(0.5)
    for c in range(3):
        cc = ar.add(ar.mul(col[:, c], a), sp)
        cc = np.minimum(np.maximum(cc, zero), one)
        out[:, c] = np.clip(ar.to_index(ar.add(ar.mul(cc, k255), half)), 0, 255)
    return out


# --------------------------------------------------------------------------------------------
# the pipeline per pixel


@dataclass
class Frame:
    """Everything one frame's pipeline needs besides the per-pixel inputs.

    ``log2pb_colour`` / ``log2pb_normal``: log2(Pb) of the quad's two triangles for each texture
    (``Camera.log2_pb(Wt, Ht)``).  ``method`` is an exact method name or an approximate one
    (``model.approx.APPROX_METHODS``, f64 only).
    """

    pyr: Pyramid
    colour: Texture
    normals: Texture
    depth_scale: float
    log2pb_colour: F64
    log2pb_normal: F64
    method: str = "park"
    engine: str = "f24"
    mip: bool = True
    material: Material = field(default_factory=Material)


class PixelInputs(NamedTuple):
    """Per covered pixel (float64), what the rasteriser hands the pipeline: the entry texel
    (u0, v0), Pl0 (eye to entry point), the triangle id, its TBN (N, 3, 3) and the unit view
    vector (N, 3).  The view unit (:func:`model.view.view_calc`) makes the ray from the last two."""

    u0: F64
    v0: F64
    pl0: F64
    tri: I64
    tbn: F64
    view: F64

    def subset(self, idx: npt.ArrayLike) -> "PixelInputs":
        return PixelInputs(*(a[idx] for a in self))


class PixelOutputs(NamedTuple):
    """Per covered pixel: ``rgb`` unorm8 (N, 3), ``hit``, ``invalid``, ``iterations``, and the
    MIP levels of the colour texture and the normal map (-1 where there is no hit)."""

    rgb: U8
    hit: B
    invalid: B
    iterations: I64
    level: I64
    level_normal: I64


def pixel_inputs(cam: Camera, frags: Fragments | None = None) -> tuple[Fragments, PixelInputs]:
    """The camera's fragments and the pipeline inputs of every covered pixel."""
    f = cam.fragments() if frags is None else frags
    return f, PixelInputs(f.u0.copy(), f.v0.copy(), f.ray_length.copy(), f.tri.copy(),
                          f.tbn.copy(), f.view.copy())


def approx_methods() -> dict[str, Callable[..., TraceResult]]:
    try:
        from . import approx
    except ImportError:  # pragma: no cover - the approximate methods are part of the model
        return {}
    return dict(approx.APPROX_METHODS)


def trace_rays(frame: Frame, rays: Rays) -> TraceResult:
    """Step 1: an exact method on the frame's engine, or an approximate one (f64)."""
    if frame.method in traverse.METHODS:
        return traverse.trace(frame.pyr, rays, frame.method, frame.engine)
    fn = approx_methods().get(frame.method)
    if fn is None:
        raise ValueError(f"unknown method {frame.method!r}")
    if frame.engine != "f64":
        raise ValueError(f"approximate method {frame.method!r} runs on the f64 engine only")
    try:
        params = inspect.signature(fn).parameters
    except (TypeError, ValueError):  # pragma: no cover
        params = {}
    if "depth_scale" in params:
        return fn(frame.pyr, rays, depth_scale=frame.depth_scale)
    return fn(frame.pyr, rays)


@np.errstate(all="ignore")  # NaN / Inf are ordinary values (model.arith)
def pixel_rays(frame: Frame, inp: PixelInputs) -> tuple[Rays, view.ViewOut]:
    """The view unit's rays of a set of covered pixels (the first step of :func:`render_pixels`)
    and its outputs."""
    vo = view.view_calc(ENGINES[frame.engine], inp.tbn, inp.view, frame.depth_scale)
    return Rays(inp.u0, inp.v0, vo.du, vo.dv), vo


@np.errstate(all="ignore")  # NaN / Inf are ordinary values (model.arith)
def render_pixels(frame: Frame, inp: PixelInputs) -> PixelOutputs:
    """The pipeline (module docstring) for a set of covered pixels."""
    ar = ENGINES[frame.engine]
    n = inp.u0.shape[0]
    rays, vo = pixel_rays(frame, inp)
    res = trace_rays(frame, rays)
    rgb = np.empty((n, 3), dtype=np.uint8)
    rgb[:] = MISS_COLOUR
    level = np.full(n, -1, dtype=np.int64)
    level_n = np.full(n, -1, dtype=np.int64)
    idx = np.nonzero(res.hit)[0]
    if idx.size:
        u, v, t = (ar.r(a[idx]) for a in (res.u, res.v, res.t))
        tri = inp.tri[idx]
        if frame.mip:
            pl = texture.ray_length(ar, ar.r(inp.pl0[idx]), t, vo.seg[idx])
            lc = texture.mip_level(ar, pl, ar.r(np.asarray(frame.log2pb_colour, float)[tri]),
                                   frame.colour.n_levels)
            ln = texture.mip_level(ar, pl, ar.r(np.asarray(frame.log2pb_normal, float)[tri]),
                                   frame.normals.n_levels)
        else:
            lc = ln = np.zeros(idx.size, dtype=np.int64)
        mw, mh = frame.pyr.width, frame.pyr.height
        col = texture.sample(frame.colour, ar, u, v, lc, frame.colour.scale_for(ar, mw, mh))
        nrm = texture.sample(frame.normals, ar, u, v, ln, frame.normals.scale_for(ar, mw, mh))
        rgb[idx] = shade(ar, col.value[:, :3], nrm.value[:, :3], vo.du[idx], vo.dv[idx],
                         frame.depth_scale, frame.material)
        level[idx] = lc
        level_n[idx] = ln
    return PixelOutputs(rgb, res.hit.copy(), res.invalid.copy(), res.iterations.copy(), level,
                        level_n)


# --------------------------------------------------------------------------------------------
# the whole image, by tiles


class Image(NamedTuple):
    """A rendered image: ``rgb`` (H, W, 3) unorm8 and the per-pixel outputs of covered pixels
    (in the fragments' row-major order), with the fragments."""

    rgb: U8
    frags: Fragments
    out: PixelOutputs


def tiles_of(frags: Fragments, tile: int) -> list[I64]:
    """Indices (into the fragments) of the covered pixels of each image tile of tile x tile
    pixels, tiles in row-major order, empty tiles left out."""
    ntx = -(-frags.mask.shape[1] // tile)
    key = (frags.row // tile) * ntx + frags.col // tile
    order = np.argsort(key, kind="stable")
    ks = key[order]
    cuts = np.nonzero(np.diff(ks))[0] + 1
    return [g for g in np.split(order, cuts) if g.size]


_WORKER_FRAME: Frame | None = None


def _worker_init(frame: Frame) -> None:
    global _WORKER_FRAME
    _WORKER_FRAME = frame


def _worker_run(inp: PixelInputs) -> PixelOutputs:
    assert _WORKER_FRAME is not None
    return render_pixels(_WORKER_FRAME, inp)


def render(frame: Frame, cam: Camera, jobs: int = 1, tile: int = 128,
           progress: Callable[[int, int], None] | None = None) -> Image:
    """Render the camera's image: the pipeline on every covered pixel, by tiles.

    ``jobs`` > 1 runs the tiles on that many processes (``multiprocessing``); the result is
    identical to ``jobs`` = 1.  ``progress(done, total)`` is called with covered pixels done.
    """
    if tile < 1 or jobs < 1:
        raise ValueError("tile and jobs must be positive")
    frags, inp = pixel_inputs(cam)
    n = len(frags)
    rgb_cov = np.empty((n, 3), dtype=np.uint8)
    hit = np.zeros(n, bool)
    inval = np.zeros(n, bool)
    iters = np.zeros(n, np.int64)
    level = np.full(n, -1, np.int64)
    level_n = np.full(n, -1, np.int64)
    groups = tiles_of(frags, tile)
    tasks = [inp.subset(g) for g in groups]
    done = 0

    def store(g: I64, o: PixelOutputs) -> None:
        nonlocal done
        rgb_cov[g], hit[g], inval[g], iters[g] = o.rgb, o.hit, o.invalid, o.iterations
        level[g], level_n[g] = o.level, o.level_normal
        done += g.size
        if progress is not None:
            progress(done, n)

    if jobs == 1 or len(tasks) <= 1:
        for g, t in zip(groups, tasks):
            store(g, render_pixels(frame, t))
    else:
        import multiprocessing as mp

        with mp.get_context().Pool(min(jobs, len(tasks)), initializer=_worker_init,
                                   initargs=(frame,)) as pool:
            for g, o in zip(groups, pool.imap(_worker_run, tasks)):
                store(g, o)
    img = np.empty(frags.mask.shape + (3,), dtype=np.uint8)
    img[:] = BACKGROUND
    img[frags.row, frags.col] = rgb_cov
    return Image(img, frags, PixelOutputs(rgb_cov, hit, inval, iters, level, level_n))
