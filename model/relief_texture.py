# SPDX-License-Identifier: Apache-2.0
"""Relief texture mapping by pre-warping (Oliveira, Bishop, McAllister 2000) and its serial,
pipelined-parallel and split-image multi-worker variants (Fonseca, Feijo, Dreux, Clua 2006).

A relief texture is a colour image plus, per texel, a depth measured orthogonally from the base
polygon (an orthographic source camera).  Oliveira factors the 3-D image warp of such a texture
to a new view into

1. a **pre-warp**: every texel moves, inside the polygon's own texture plane, to where the eye
   ray through its 3-D point meets that plane (a per-texel shift towards or away from the
   epipole, the foot of the eye on the plane), done as two 1-D passes (rows, then columns);
2. ordinary **texture mapping** of the pre-warped image onto the polygon.

Geometry (the project's, ``model.camera``).  The polygon is the quad z = 0 covering the map
(world x = u, y = v in texels, z up); the relief lies below it, as the displacement volume of
``CONVENTIONS.md``: texel (i, j) with height h is the point
``x = C_s + a (j + 0.5) + b (i + 0.5) + f d`` with ``d = 1 - h`` (depth, 0 on the polygon),
``C_s = 0``, ``a = (1, 0, 0)``, ``b = (0, 1, 0)`` and ``f = (0, 0, -D)`` (D = depth scale in
texels).  For an eye E (``c = C_s - E``), Oliveira's pre-warp equations are

    u_i = (u_s + k1 d) / (1 + k3 d),   v_i = (v_s + k2 d) / (1 + k3 d)
    k1 = f.(b x c) / a.(b x c),  k2 = f.(c x a) / b.(c x a),  k3 = f.(a x b) / c.(a x b)

(here k1 = D E_x / E_z, k2 = D E_y / E_z, k3 = D / E_z).  u_i - e_u = (u_s - e_u) / (1 + k3 d)
with the epipole e = (k1 / k3, k2 / k3) = (E_x, E_y): a texel never crosses the epipole, and of
two texels of a row landing on one spot the one nearer the epipole is nearer the eye.

The two-pass serial warp.  Pass 1 warps each row horizontally (u_s -> u_i, carrying colour and
depth), pass 2 each column of the result vertically (v_s -> v_i).  Inside a line the samples
are taken in **occlusion-compatible order** -- from both ends towards the epipole -- and every
pair of neighbours is a segment: when the second sample lands further along the processing
direction than the first (or on it), the target pixels between them (pixel x has its centre at
u = x + 0.5; both ends included) get colour and depth interpolated linearly, later segments
overwriting earlier ones; a segment that folds back is a surface turned away and is skipped.
The segment that straddles the epipole comes last.  Invalid texels (background, Fonseca's
"invalid values") end segments; target pixels no segment covers stay empty.

Vectorised: a pass builds every segment of every line at once, expands them into (line, pixel,
rank) entries and keeps, per pixel, the entry of highest rank (the last writer of the serial
loop); ``tests/test_relief_texture.py`` checks this equals a literal per-texel Python loop.
Lines are independent, so a pass over a band of lines equals the same lines of a whole pass:
what the split-image variant relies on.

Texture mapping: each covered pixel of the camera image takes the pre-warped texel under the
point where its eye ray meets the quad (nearest texel, ``model.camera.Camera.fragments``);
empty texels show the background.  With zero depth everywhere the pre-warp is the identity
and the result is plain texture mapping of the colour image.

The variants (:func:`render_frames`): ``serial`` (pre-warp then texture-map, frame after frame),
``pipelined`` (a worker pre-warps frame k + 1 while frame k is texture-mapped; Fonseca's
"parallel" approach, synchronised per frame so that every frame shows its own pre-warp) and
``split`` (N workers pre-warp bands of rows, then bands of columns, then the frame is
texture-mapped; Fonseca's "multi-threaded" split of the image), on threads or processes.  All
produce identical images.  Fonseca split the *texture* into halves, each warped through both
passes, and unified the results; that differs from the serial warp wherever the column pass
interpolates between texels that came from different halves, so ``split`` splits each pass
into bands of independent lines instead.  :func:`render_async` is Fonseca's own measure of the
parallel approach (redraws of the latest finished pre-warp while the next one is computed).
"""
from __future__ import annotations

import os
import time
from collections.abc import Callable, Sequence
from concurrent.futures import Executor, Future, ProcessPoolExecutor, ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from model import scenes
from model.camera import Camera

F64 = npt.NDArray[np.float64]
F32 = npt.NDArray[np.float32]
U8 = npt.NDArray[np.uint8]
B = npt.NDArray[np.bool_]
I64 = npt.NDArray[np.int64]

#: Colour of empty pre-warped texels (nothing landed there) in the final image.
BACKGROUND = np.array([0.0, 0.0, 0.0], np.float32)
VARIANTS: tuple[str, ...] = ("serial", "pipelined", "split")
BACKENDS: tuple[str, ...] = ("thread", "process")


# ---- the relief texture and the view ------------------------------------------------------------

@dataclass(frozen=True)
class ReliefTexture:
    """Colour (H, W, 3) float32 in [0, 1], depth (H, W) float64 in [0, 1] below the polygon
    (``1 - h``), valid (H, W) texels, and the depth scale D in texels."""

    colour: F32
    depth: F64
    valid: B
    depth_scale: float

    @property
    def height(self) -> int:
        return int(self.depth.shape[0])

    @property
    def width(self) -> int:
        return int(self.depth.shape[1])

    @classmethod
    def from_heights(cls, h: npt.ArrayLike, colour: npt.ArrayLike, depth_scale: float,
                     valid: npt.ArrayLike | None = None) -> "ReliefTexture":
        """From the project's height field (h in [0, 1], 1 = on the polygon) and a colour
        image of the same size; ``valid`` marks texels with a sample (default: all)."""
        hh = np.asarray(h, dtype=np.float64)
        col = np.asarray(colour, dtype=np.float32)
        if hh.ndim != 2 or min(hh.shape) < 2:
            raise ValueError(f"a relief texture needs at least 2 x 2 texels, got {hh.shape}")
        if col.shape[:2] != hh.shape or col.ndim != 3 or col.shape[2] < 3:
            raise ValueError(f"colour must be (H, W, 3) like the heights {hh.shape}, "
                             f"got {col.shape}")
        d = float(depth_scale)
        if not (np.isfinite(d) and d > 0):
            raise ValueError(f"depth_scale must be a positive number, got {depth_scale!r}")
        v = np.ones(hh.shape, bool) if valid is None else np.asarray(valid, dtype=bool)
        if v.shape != hh.shape:
            raise ValueError(f"valid must have the heights' shape {hh.shape}, got {v.shape}")
        return cls(np.ascontiguousarray(col[..., :3]),
                   np.ascontiguousarray(1.0 - np.clip(hh, 0.0, 1.0)), v, d)


def scene_relief(name: str, size: int, invalid_floor: bool = False) -> ReliefTexture:
    """A procedural scene (``model.scenes``) as a relief texture; ``invalid_floor`` marks the
    texels at the scene's lowest height as background (like Fonseca's sample 3)."""
    sc = scenes.load_scene(name, size)
    valid = None
    if invalid_floor:
        valid = sc.heights > sc.heights.min() + 1e-9
    return ReliefTexture.from_heights(sc.heights, sc.texture, sc.depth_scale, valid)


@dataclass(frozen=True)
class Prewarp:
    """Oliveira's pre-warp constants for one eye: u_i = (u_s + k1 d) / (1 + k3 d), etc."""

    k1: float
    k2: float
    k3: float

    @property
    def epipole(self) -> tuple[float, float]:
        """(e_u, e_v) = (k1 / k3, k2 / k3): where the eye's foot is on the polygon."""
        return self.k1 / self.k3, self.k2 / self.k3


def prewarp_constants(eye: npt.ArrayLike, depth_scale: float) -> Prewarp:
    """k1, k2, k3 from Oliveira's vector form (module docstring) for an eye above the quad."""
    e = np.asarray(eye, dtype=np.float64)
    if not (e.shape == (3,) and np.all(np.isfinite(e)) and e[2] > 0):
        raise ValueError(f"the eye must be a finite point above the polygon (z > 0), got {e}")
    a, b = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    f = np.array([0.0, 0.0, -float(depth_scale)])
    c = -e                                           # C_s - E with C_s at the origin
    k1 = f @ np.cross(b, c) / (a @ np.cross(b, c))
    k2 = f @ np.cross(c, a) / (b @ np.cross(c, a))
    k3 = f @ np.cross(a, b) / (c @ np.cross(a, b))
    return Prewarp(float(k1), float(k2), float(k3))


@dataclass
class Warped:
    """A (pre-)warped image: colour (H, W, 3) float32, depth (H, W), valid (H, W)."""

    colour: F32
    depth: F64
    valid: B


# ---- the 1-D warp ------------------------------------------------------------------------------

def warp_lines(colour: F32, depth: F64, valid: B, k: float, k3: float) -> Warped:
    """One pass of the two-pass warp along axis 1 of (lines, samples) arrays.

    Sample j of a line sits at coordinate j + 0.5 and moves to ``(j + 0.5 + k d) / (1 + k3 d)``;
    target pixel x has its centre at x + 0.5.  Serial semantics (module docstring): segments in
    occlusion-compatible order, the last writer of a pixel wins; vectorised over lines and
    segments.  Returns the warped lines (same shape).
    """
    nl, ns = depth.shape
    out_c = np.zeros(colour.shape, np.float32)
    out_d = np.zeros(depth.shape, np.float64)
    out_v = np.zeros(depth.shape, bool)
    if nl == 0 or ns < 2:
        return Warped(out_c, out_d, out_v)
    e = k / k3 - 0.5                                  # epipole, pixel-centre coordinates
    js = np.arange(ns, dtype=np.float64)
    q = (js[None, :] + 0.5 + k * depth) / (1.0 + k3 * depth) - 0.5
    j = np.arange(ns - 1)
    left = (j + 1) <= e                               # processed left to right
    right = j >= e                                    # processed right to left
    # the middle segment (j < e < j + 1) is processed last, left to right
    fwd = ~right
    rank = np.where(left, j, np.where(right, 2 * ns - 2 - j, 3 * ns)).astype(np.int64)
    ia = np.where(fwd, j, j + 1)                      # first sample of the segment
    ib = np.where(fwd, j + 1, j)
    qa, qb = q[:, ia], q[:, ib]                       # (lines, segments)
    ok = valid[:, ia] & valid[:, ib] & np.where(fwd, qb >= qa, qb <= qa)   # no fold
    lo = np.maximum(np.ceil(np.minimum(qa, qb)), 0.0)
    hi = np.minimum(np.floor(np.maximum(qa, qb)), ns - 1.0)
    cnt = np.where(ok, hi - lo + 1.0, 0.0)
    cnt = np.maximum(cnt, 0.0).astype(np.int64).ravel()
    total = int(cnt.sum())
    if total == 0:
        return Warped(out_c, out_d, out_v)
    seg = np.repeat(np.arange(cnt.size, dtype=np.int64), cnt)      # segment of each entry
    start = np.cumsum(cnt) - cnt
    x = lo.ravel()[seg].astype(np.int64) + (np.arange(total, dtype=np.int64) - start[seg])
    line = seg // (ns - 1)
    sj = seg % (ns - 1)
    pix = line * ns + x                                             # flat target pixel
    r = rank[sj]
    best = np.full(nl * ns, -1, np.int64)
    np.maximum.at(best, pix, r)
    win = r == best[pix]                                            # the last writer
    pix, line, sj, x = pix[win], line[win], sj[win], x[win]
    a_flat = line * ns + ia[sj]
    b_flat = line * ns + ib[sj]
    qa_w, qb_w = q.ravel()[a_flat], q.ravel()[b_flat]
    den = qb_w - qa_w
    w = np.where(den != 0.0, (x - qa_w) / np.where(den != 0.0, den, 1.0), 0.0)
    d_flat = depth.ravel()
    c_flat = colour.reshape(nl * ns, -1)
    w32 = w.astype(np.float32)[:, None]
    oc = out_c.reshape(nl * ns, -1)
    oc[pix] = (1.0 - w32) * c_flat[a_flat] + w32 * c_flat[b_flat]
    out_d.ravel()[pix] = (1.0 - w) * d_flat[a_flat] + w * d_flat[b_flat]
    out_v.ravel()[pix] = True
    return Warped(out_c, out_d, out_v)


def prewarp_rows(rt: ReliefTexture, pw: Prewarp, rows: slice = slice(None)) -> Warped:
    """Pass 1 on a band of rows: each row warped horizontally (u), shape (band, W)."""
    return warp_lines(rt.colour[rows], rt.depth[rows], rt.valid[rows], pw.k1, pw.k3)


def prewarp_columns(mid: Warped, pw: Prewarp, cols: slice = slice(None)) -> Warped:
    """Pass 2 on a band of columns of the pass-1 image: warped vertically (v), (H, band)."""
    c = np.ascontiguousarray(mid.colour[:, cols].transpose(1, 0, 2))
    res = warp_lines(c, np.ascontiguousarray(mid.depth[:, cols].T),
                     np.ascontiguousarray(mid.valid[:, cols].T), pw.k2, pw.k3)
    return Warped(np.ascontiguousarray(res.colour.transpose(1, 0, 2)),
                  np.ascontiguousarray(res.depth.T), np.ascontiguousarray(res.valid.T))


def prewarp(rt: ReliefTexture, pw: Prewarp) -> Warped:
    """The whole two-pass serial pre-warp of a relief texture for one eye."""
    return prewarp_columns(prewarp_rows(rt, pw), pw)


# ---- texture mapping ----------------------------------------------------------------------------

@dataclass(frozen=True)
class View:
    """One frame's camera and its texture-mapping lookup: the covered pixels' texel indices."""

    cam: Camera
    pw: Prewarp
    pixel: I64        # flat index (row * image_w + col) of each covered pixel
    texel: I64        # flat index (i * W + j) of the texel under it


def make_view(cam: Camera, rt: ReliefTexture) -> View:
    """The pre-warp constants and the texture-mapping lookup of a camera over the texture."""
    if (cam.map_w, cam.map_h) != (rt.width, rt.height):
        raise ValueError("the camera frames a map of another size")
    fr = cam.fragments()
    j = np.minimum(np.floor(fr.u0), rt.width - 1).astype(np.int64)
    i = np.minimum(np.floor(fr.v0), rt.height - 1).astype(np.int64)
    return View(cam, prewarp_constants(cam.eye, rt.depth_scale),
                fr.row * cam.image_w + fr.col, i * rt.width + j)


def texture_map(img: Warped, view: View) -> U8:
    """Map a (pre-warped) image onto the quad as seen by ``view``: 8-bit RGB (image_h, image_w,
    3), nearest texel; empty texels and uncovered pixels are the background (black)."""
    cam = view.cam
    out = np.zeros((cam.image_h * cam.image_w, 3), np.uint8)
    c = img.colour.reshape(-1, 3)[view.texel]
    c = np.where(img.valid.ravel()[view.texel][:, None], c, BACKGROUND[None, :])
    out[view.pixel] = np.rint(np.clip(c, 0.0, 1.0) * 255.0).astype(np.uint8)
    return out.reshape(cam.image_h, cam.image_w, 3)


def plain_texture_map(rt: ReliefTexture, view: View) -> U8:
    """Ordinary texture mapping of the colour image (no pre-warp), same sampling."""
    return texture_map(Warped(rt.colour, np.zeros_like(rt.depth), rt.valid), view)


def render(rt: ReliefTexture, view: View) -> U8:
    """Pre-warp then texture-map: one frame of relief texture mapping."""
    return texture_map(prewarp(rt, view.pw), view)


def orbit(rt: ReliefTexture, frames: int, image: int, elevation: float = 45.0,
          start_deg: float = 0.0) -> list[View]:
    """A camera path: ``frames`` views orbiting the quad at ``elevation`` degrees."""
    az = start_deg + 360.0 * np.arange(frames) / max(frames, 1)
    return [make_view(Camera.for_view(elevation, rt.width, rt.height, image, image,
                                      depth_scale=rt.depth_scale, azimuth_deg=float(a)), rt)
            for a in az]


# ---- the variants -------------------------------------------------------------------------------

_WORKER_RT: ReliefTexture | None = None


def _init_worker(rt: ReliefTexture) -> None:
    """Process workers get the relief texture once, at start-up."""
    global _WORKER_RT
    _WORKER_RT = rt


def _w_prewarp(pw: Prewarp) -> Warped:
    assert _WORKER_RT is not None
    return prewarp(_WORKER_RT, pw)


def _w_rows(pw: Prewarp, rows: slice) -> Warped:
    assert _WORKER_RT is not None
    return prewarp_rows(_WORKER_RT, pw, rows)


def _w_cols(mid: Warped, pw: Prewarp) -> Warped:
    return prewarp_columns(mid, pw)


def _executor(backend: str, workers: int, rt: ReliefTexture) -> Executor:
    if backend == "thread":
        _init_worker(rt)
        return ThreadPoolExecutor(max_workers=workers)
    if backend == "process":
        import multiprocessing as mp

        ctx = mp.get_context("fork" if "fork" in mp.get_all_start_methods() else "spawn")
        return ProcessPoolExecutor(max_workers=workers, mp_context=ctx,
                                   initializer=_init_worker, initargs=(rt,))
    raise ValueError(f"backend is one of {BACKENDS}, got {backend!r}")


def bands(n: int, parts: int) -> list[slice]:
    """``parts`` contiguous, nearly equal slices covering range(n) (empty ones dropped)."""
    edges = np.linspace(0, n, max(1, parts) + 1).round().astype(int)
    return [slice(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:]) if b > a]


@dataclass
class FrameRun:
    """The frames of one variant and when each was finished (seconds since the start)."""

    variant: str
    backend: str
    workers: int
    images: list[U8]
    done: list[float]
    seconds: float

    @property
    def fps(self) -> float:
        return len(self.done) / self.seconds if self.seconds > 0 else float("inf")

    def fps_sd(self) -> float:
        """Standard deviation of the per-frame rate 1 / (interval between frame completions)."""
        t = np.diff(np.concatenate([[0.0], np.asarray(self.done)]))
        t = t[t > 0]
        return float(np.std(1.0 / t)) if t.size > 1 else 0.0


def render_frames(rt: ReliefTexture, views: Sequence[View], variant: str = "serial", *,
                  backend: str = "thread", workers: int = 2, keep: bool = True,
                  on_frame: Callable[[int], None] | None = None) -> FrameRun:
    """Render ``views`` one frame each with a variant (module docstring); identical images.

    ``workers``: pre-warp workers of ``split`` (``pipelined`` uses one); ``keep``: return the
    images (else only the last).  Timing starts after the workers are up.
    """
    if variant not in VARIANTS:
        raise ValueError(f"variant is one of {VARIANTS}, got {variant!r}")
    if backend not in BACKENDS:
        raise ValueError(f"backend is one of {BACKENDS}, got {backend!r}")
    if int(workers) != workers or workers < 1:
        raise ValueError(f"workers must be a positive integer, got {workers!r}")
    images: list[U8] = []
    done: list[float] = []

    def finish(k: int, img: U8, t0: float) -> None:
        if keep or k == len(views) - 1:
            images.append(img)
        done.append(time.perf_counter() - t0)
        if on_frame is not None:
            on_frame(k + 1)

    if variant == "serial":
        t0 = time.perf_counter()
        for k, v in enumerate(views):
            finish(k, texture_map(prewarp(rt, v.pw), v), t0)
        return FrameRun(variant, "-", 1, images, done, time.perf_counter() - t0)

    n_workers = 1 if variant == "pipelined" else int(workers)
    with _executor(backend, n_workers, rt) as ex:
        _warm_up(ex, n_workers)
        t0 = time.perf_counter()
        if variant == "pipelined":
            fut: Future[Warped] | None = ex.submit(_w_prewarp, views[0].pw) if views else None
            for k, v in enumerate(views):
                assert fut is not None
                cur = fut.result()
                fut = ex.submit(_w_prewarp, views[k + 1].pw) if k + 1 < len(views) else None
                finish(k, texture_map(cur, v), t0)
        else:
            rb, cb = bands(rt.height, n_workers), bands(rt.width, n_workers)
            for k, v in enumerate(views):
                mid = _gather([ex.submit(_w_rows, v.pw, s) for s in rb], axis=0)
                cols = [ex.submit(_w_cols, _column_band(mid, s), v.pw) for s in cb]
                finish(k, texture_map(_gather(cols, axis=1), v), t0)
        return FrameRun(variant, backend, n_workers, images, done, time.perf_counter() - t0)


@dataclass
class AsyncRun:
    """Fonseca's own count for the parallel approach: the display loop redraws the latest
    finished pre-warp as often as it can while a worker pre-warps the next view; ``draws`` are
    what their Table 2 calls frames, ``warps`` the fresh pre-warps among them."""

    backend: str
    draws: int
    warps: int
    seconds: float

    @property
    def draws_per_s(self) -> float:
        return self.draws / self.seconds if self.seconds > 0 else float("inf")

    @property
    def warps_per_s(self) -> float:
        return self.warps / self.seconds if self.seconds > 0 else float("inf")


def render_async(rt: ReliefTexture, views: Sequence[View], backend: str = "thread") -> AsyncRun:
    """The unsynchronised parallel approach (Fonseca Section 3.1): a worker pre-warps
    ``views`` one after the other; meanwhile the main loop texture-maps the most recent
    finished pre-warp again and again.  Timed from the first finished pre-warp to the last."""
    if backend not in BACKENDS:
        raise ValueError(f"backend is one of {BACKENDS}, got {backend!r}")
    if not views:
        return AsyncRun(backend, 0, 0, 0.0)
    with _executor(backend, 1, rt) as ex:
        _warm_up(ex, 1)
        cur = ex.submit(_w_prewarp, views[0].pw).result()       # the first draw waits
        shown = 0
        nxt: Future[Warped] | None = ex.submit(_w_prewarp, views[1].pw) if len(views) > 1 \
            else None
        draws, warps = 0, 0                  # pre-warps finished inside the timed interval
        t0 = time.perf_counter()
        while True:
            texture_map(cur, views[shown])
            draws += 1
            if nxt is None:
                break
            if nxt.done():
                cur, shown, warps = nxt.result(), shown + 1, warps + 1
                nxt = ex.submit(_w_prewarp, views[shown + 1].pw) if shown + 1 < len(views) \
                    else None
        return AsyncRun(backend, draws, warps, time.perf_counter() - t0)


def _warm_up(ex: Executor, n: int) -> None:
    """Start every worker before the clock starts (processes fork lazily)."""
    for f in [ex.submit(time.sleep, 0.01) for _ in range(n)]:
        f.result()


def _gather(futs: list[Future[Warped]], axis: int) -> Warped:
    """Join the workers' bands (rows: axis 0, columns: axis 1) into one image."""
    parts = [f.result() for f in futs]
    return Warped(np.concatenate([p.colour for p in parts], axis=axis),
                  np.concatenate([p.depth for p in parts], axis=axis),
                  np.concatenate([p.valid for p in parts], axis=axis))


def _column_band(mid: Warped, s: slice) -> Warped:
    return Warped(mid.colour[:, s], mid.depth[:, s], mid.valid[:, s])


def cpu_count() -> int:
    """CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def frames_identical(runs: Sequence[FrameRun]) -> bool:
    """True when every run produced exactly the same images, frame for frame."""
    ref = runs[0].images
    return all(len(r.images) == len(ref) and all(np.array_equal(a, b) for a, b in
                                                 zip(r.images, ref)) for r in runs[1:])
