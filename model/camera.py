# SPDX-License-Identifier: Apache-2.0
"""A pinhole camera over the displacement-mapped quad: fragments, rays and MIP pre-processing.

World and tangent space.  The surface is one flat square-texel quad covering the whole height
map: world x = u and world y = v in level-0 texel units (1 world unit = 1 texel), z up.  The
quad lies in the plane z = 0, the top of the displacement volume; the volume's floor is the
plane z = -depth_scale.  It is two triangles, with texture coordinates (s, t) = (u/W, v/H):

    triangle 0: (0, 0, 0) (W, 0, 0) (W, H, 0)     st (0, 0) (1, 0) (1, 1)
    triangle 1: (0, 0, 0) (W, H, 0) (0, H, 0)     st (0, 0) (1, 1) (0, 1)

A point with v W <= u H (on or above the diagonal in the map image) belongs to triangle 0.
Each triangle's TBN matrix has the columns T = dP/du, B = dP/dv, N = up, orthonormalised; for
this quad both are the identity, but every per-pixel array carries its own [3, 3] TBN.

Views.  The eye looks at the quad's centre from a fixed distance (``EYE_DISTANCE`` = 2 times
the map's larger side) at azimuth ``AZIMUTH_DEG`` = 30 degrees (measured in the u-v plane from
the +v axis towards +u: the eye stands beyond the map's bottom edge, turned by 30 degrees so
that no ray is axis-parallel) and at the elevation above the surface plane named by the view:

    ============  =========  ==================================================
    view          elevation  horizontal texels per unit of depth at the centre
    ============  =========  ==================================================
    ``front``     80 deg     depth_scale / tan(80 deg) = 0.18 depth_scale
    ``oblique``   45 deg     depth_scale / tan(45 deg) = 1.00 depth_scale
    ``grazing``   15 deg     depth_scale / tan(15 deg) = 3.73 depth_scale
    ============  =========  ==================================================

(Perspective makes the elevation vary over the image: the far side of the quad is seen lower.)
Any elevation in (0, 90] degrees can be given as a number instead of a name.

Depth scale.  The volume depth is ``DEPTH_FRACTION`` = 8 % of the map's larger side, in texels:
``depth_scale(W, H) = 0.08 max(W, H)`` (20.48 texels for a 256 x 256 map), the same for every
scene and view.  A ray's depth parameter t runs from 0 at the top (z = 0) to 1 at the floor.

Image.  Pixel (row, col) samples the ray through its centre (col + 0.5, row + 0.5); rows run
down the image.  The camera is framed so that the projected quad's bounding box is centred and
fills the image up to a 2 % margin on its tighter axis.  The image is laid out like the map file:
seen from the front, u points right and v points down the image (the far side, small v, is at
the top).  The camera basis (right, down, forward) is thus right-handed in the frame
(u, v, depth) of ``CONVENTIONS.md``, whose depth axis is -z.

Rays.  ``Camera.rays()`` gives for every covered pixel the contract's ray: the entry point
(u0, v0) where the eye ray crosses z = 0 and (du, dv) = the texels moved per unit of depth t,
``(T.view, B.view) / |N.view| * depth_scale`` (``view_to_tangent``, the model of the pipeline's
view-calculation unit).

MIP level (Park et al., IEICE Electronics Express 2011).  ``lod = log2(Pl) - log2(Pb)``
(their eq. (2)): Pl is the ray length from the eye to the entry point and log2(Pb) a per-
triangle constant from the pre-processing of ``log2_pb`` (five steps, see there).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from model.rays import Rays

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

VIEWS: dict[str, float] = {"front": 80.0, "oblique": 45.0, "grazing": 15.0}
"""Elevation above the surface plane of each named view, in degrees."""
AZIMUTH_DEG = 30.0
"""Azimuth of the eye around the quad's centre: from +v towards +u, in degrees."""
DEPTH_FRACTION = 0.08
"""Volume depth as a fraction of the map's larger side."""
EYE_DISTANCE = 2.0
"""Eye distance from the quad's centre in units of the map's larger side."""
FRAME_MARGIN = 0.02
"""Empty margin left around the projected quad on its tighter image axis."""


def depth_scale(map_w: int, map_h: int) -> float:
    """The project's volume depth in texels: ``DEPTH_FRACTION * max(map_w, map_h)``."""
    return DEPTH_FRACTION * float(max(map_w, map_h))


_rule_depth = depth_scale  # reachable where a parameter named depth_scale shadows it


def elevation(angle: str | float) -> float:
    """A view name or an elevation in degrees -> the elevation in degrees, in (0, 90]."""
    if isinstance(angle, str):
        if angle not in VIEWS:
            raise ValueError(f"unknown view angle {angle!r}; valid angles: {', '.join(VIEWS)} "
                             "or an elevation in degrees")
        return VIEWS[angle]
    e = float(angle)
    if not 0.0 < e <= 90.0:
        raise ValueError(f"elevation must be in (0, 90] degrees, got {angle!r}")
    return e


def quad_triangles(map_w: int, map_h: int) -> tuple[F64, F64]:
    """The quad's two triangles: world positions (2, 3, 3) and texture coordinates (2, 3, 2)."""
    w, h = float(map_w), float(map_h)
    p = np.array([[0, 0, 0], [w, 0, 0], [w, h, 0], [0, h, 0]], dtype=np.float64)
    st = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float64)
    idx = np.array([[0, 1, 2], [0, 2, 3]])
    return p[idx], st[idx]


def tangent_frames(positions: npt.ArrayLike, texcoords: npt.ArrayLike,
                   tex_w: float, tex_h: float) -> F64:
    """Per-triangle TBN matrices (T, 3, 3), columns T, B, N, orthonormal.

    T and B are the world directions of increasing u = s tex_w and v = t tex_h (solved from the
    triangle's edges), N = normalize(T x B); T is then made orthogonal to N and B = +-N x T
    keeps the sign of the original B (mirrored texture mappings stay mirrored).
    """
    pos = np.asarray(positions, dtype=np.float64)
    uv = np.asarray(texcoords, dtype=np.float64) * np.array([tex_w, tex_h])
    e1, e2 = pos[:, 1] - pos[:, 0], pos[:, 2] - pos[:, 0]
    d1, d2 = uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0]
    det = d1[:, 0] * d2[:, 1] - d2[:, 0] * d1[:, 1]
    t = (e1 * d2[:, 1:2] - e2 * d1[:, 1:2]) / det[:, None]
    b = (e2 * d1[:, 0:1] - e1 * d2[:, 0:1]) / det[:, None]
    n = np.cross(t, b)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    t = t - np.sum(t * n, axis=-1, keepdims=True) * n
    t /= np.linalg.norm(t, axis=-1, keepdims=True)
    bo = np.cross(n, t)
    bo *= np.where(np.sum(bo * b, axis=-1) < 0.0, -1.0, 1.0)[:, None]
    return np.stack([t, bo, n], axis=-1)


def view_to_tangent(tbn: npt.ArrayLike, view: npt.ArrayLike,
                    depth_scale: float) -> tuple[F64, F64]:
    """The view calculation: a world view vector -> the ray's (du, dv) in texels per unit depth.

    ``tbn`` (N, 3, 3) with columns T, B, N; ``view`` (N, 3) the direction from the eye towards
    the surface (any length).  With (x, y, z) = TBN^T view (tangent-space view vector),
    du = depth_scale * x / -z and dv = depth_scale * y / -z.  A vector that does not point into
    the surface (z >= 0) gives NaN (an invalid ray).
    """
    m = np.asarray(tbn, dtype=np.float64)
    v = np.asarray(view, dtype=np.float64)
    vt = np.einsum("nij,ni->nj", m, v)
    down = -vt[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where(down > 0.0, depth_scale / down, np.nan)
    return vt[:, 0] * k, vt[:, 1] * k


def log2_pb(positions: npt.ArrayLike, texcoords: npt.ArrayLike, tex_w: int, tex_h: int,
            res_screen: float) -> F64:
    """log2(Pb) of each triangle: the MIP pre-processing of Park et al. (IEICE 2011, Section 4).

    ``positions`` (T, 3, 3) world vertices, ``texcoords`` (T, 3, 2) normalised (s, t),
    ``tex_w`` x ``tex_h`` the texture's level-0 resolution, ``res_screen`` the screen
    resolution as a pixel density: pixels per unit area of the image plane at unit distance
    from the eye (``f_x f_y`` for focal lengths in pixels; ``Camera.res_screen``).

    Pb is the distance from the eye at which one pixel's footprint on a triangle facing the
    eye has the area of one texel, so that eq. (2), lod = log2(Pl) - log2(Pb), is the
    log2 of the texels per pixel (linear) at ray length Pl.  The paper's five steps:

    1. texels in the triangle (first equation of Section 4):
       T_XN = |s0 t1 + s1 t2 + s2 t0 - t0 s1 - t1 s2 - t2 s0| / 2 * RES_texture,
       RES_texture = tex_w tex_h;
    2. texture-to-screen resolution ratio: X_PR = 1 / RES_screen (the paper writes
       RES_texture / RES_screen; RES_texture already entered in step 1, so only the
       screen part remains here);
    3. the triangle's texels in screen terms: T_XS = T_XN X_PR (image-plane area at unit
       distance that the triangle's texels would cover at one pixel each);
    4. the triangle's world area: T_size = |(P1 - P0) x (P2 - P0)| / 2;
    5. log2(Pb) = 1/2 log2(T_size / T_XS).

    Step 5 is the reciprocal of the ratio printed in the paper (1/2 log2(T_XS / T_size)),
    which would make lod fall as the texture gets finer; the form above follows from the
    paper's definition of Pb: a pixel covers Pb^2 / RES_screen of world area at distance Pb,
    a texel T_size / T_XN.  Hence doubling the texture resolution on both axes lowers log2(Pb)
    by exactly 1 (lod + 1); doubling the image resolution (or the scene's scale) raises it by 1.
    """
    pos = np.asarray(positions, dtype=np.float64)
    st = np.asarray(texcoords, dtype=np.float64)
    s, t = st[..., 0], st[..., 1]
    area_st = 0.5 * np.abs(s[:, 0] * t[:, 1] + s[:, 1] * t[:, 2] + s[:, 2] * t[:, 0]
                           - t[:, 0] * s[:, 1] - t[:, 1] * s[:, 2] - t[:, 2] * s[:, 0])
    t_xn = area_st * float(tex_w) * float(tex_h)                 # step 1
    x_pr = 1.0 / float(res_screen)                               # step 2
    t_xs = t_xn * x_pr                                           # step 3
    cr = np.cross(pos[:, 1] - pos[:, 0], pos[:, 2] - pos[:, 0])  # step 4
    t_size = 0.5 * np.linalg.norm(cr, axis=-1)
    return 0.5 * np.log2(t_size / t_xs)                          # step 5


def mip_lod(ray_length: npt.ArrayLike, log2pb: npt.ArrayLike) -> F64:
    """Eq. (2) of the IEICE 2011 paper: lod = log2(Pl) - log2(Pb) (unclamped)."""
    return np.log2(np.asarray(ray_length, dtype=np.float64)) - np.asarray(log2pb, np.float64)


@dataclass
class Fragments:
    """What the rasteriser hands the pipeline, one entry per covered pixel (row-major order).

    ``mask`` (image_h, image_w) marks covered pixels; the other arrays have N = mask.sum()
    entries: ``row``, ``col`` pixel indices, ``u0``, ``v0`` the texel coordinate where the eye
    ray enters the volume (z = 0), ``view`` (N, 3) the unit world direction from the eye,
    ``tbn`` (N, 3, 3) the triangle's TBN (columns T, B, N), ``ray_length`` Pl (eye to entry
    point, world units = texels), ``tri`` the triangle id (0 or 1).
    """

    mask: npt.NDArray[np.bool_]
    row: I64
    col: I64
    u0: F64
    v0: F64
    view: F64
    tbn: F64
    ray_length: F64
    tri: I64

    def __len__(self) -> int:
        return int(self.row.shape[0])


def _interleave(x: I64) -> I64:
    """Spread the bits of x (< 2^21) to the even bit positions (a Morton code's half)."""
    x = x & 0x1FFFFF
    x = (x | (x << 32)) & 0x1F00000000FFFF
    x = (x | (x << 16)) & 0x1F0000FF0000FF
    x = (x | (x << 8)) & 0x100F00F00F00F00F
    x = (x | (x << 4)) & 0x10C30C30C30C30C3
    x = (x | (x << 2)) & 0x1249249249249249
    return x


def tile_order(row: npt.ArrayLike, col: npt.ArrayLike, image_w: int, tile: int,
               blocks: str = "rows") -> I64:
    """The permutation that sorts pixels (row, col) into tile x tile blocks (row-major inside a
    block): how a tiled rasteriser hands fragments to the pipeline.  ``blocks`` orders the blocks:
    ``"rows"`` row-major, ``"morton"`` along a Z-order curve (blocks near in the image stay near
    in time, which keeps the texels they share in a small cache)."""
    if int(tile) != tile or tile < 1:
        raise ValueError(f"tile must be a positive integer, got {tile!r}")
    if blocks not in ("rows", "morton"):
        raise ValueError(f"blocks must be 'rows' or 'morton', got {blocks!r}")
    r, c = np.asarray(row, np.int64), np.asarray(col, np.int64)
    br, bc = r // tile, c // tile
    if blocks == "morton":
        block = (_interleave(br) << 1) | _interleave(bc)
    else:
        block = br * -(-int(image_w) // int(tile)) + bc
    key = block * (tile * tile) + (r % tile) * tile + c % tile
    return np.argsort(key, kind="stable").astype(np.int64)


class CameraRays(NamedTuple):
    """Contract rays of the covered pixels and their pixel indices."""

    rays: Rays
    row: I64
    col: I64


@dataclass(eq=False)
class Camera:
    """A pinhole camera framing the quad of a ``map_w`` x ``map_h`` height map.

    Pixel (row, col) looks along ``forward + ((col + 0.5 - cx) right + (row + 0.5 - cy) down)
    / focal``; ``eye``, ``forward``, ``right``, ``down`` are world vectors (the last three
    orthonormal), ``focal`` in pixels.
    """

    map_w: int
    map_h: int
    image_w: int
    image_h: int
    eye: F64
    forward: F64
    right: F64
    down: F64
    focal: float
    cx: float
    cy: float
    depth_scale: float
    elevation_deg: float
    azimuth_deg: float

    @classmethod
    def for_view(cls, angle: str | float, map_w: int, map_h: int, image_w: int, image_h: int,
                 depth_scale: float | None = None, azimuth_deg: float = AZIMUTH_DEG) -> "Camera":
        """The camera of a named view (``VIEWS``) or an elevation in degrees, framing the quad.

        ``depth_scale`` defaults to the project rule ``depth_scale(map_w, map_h)``.
        """
        for what, val in (("map_w", map_w), ("map_h", map_h), ("image_w", image_w),
                          ("image_h", image_h)):
            if int(val) != val or val < 1:
                raise ValueError(f"{what} must be a positive integer, got {val!r}")
        e = np.radians(elevation(angle))
        a = np.radians(float(azimuth_deg))
        dist = EYE_DISTANCE * max(map_w, map_h)
        centre = np.array([map_w / 2.0, map_h / 2.0, 0.0])
        to_eye = np.array([np.cos(e) * np.sin(a), np.cos(e) * np.cos(a), np.sin(e)])
        eye = centre + dist * to_eye
        forward = -to_eye
        far = -np.array([np.sin(a), np.cos(a), 0.0])          # horizontal, away from the eye
        up = far * np.sin(e) + np.array([0.0, 0.0, 1.0]) * np.cos(e)
        down = -up
        right = np.cross(forward, down)
        # frame the quad: project its corners with focal 1, centre and fit their bounding box
        corners = np.array([[0, 0, 0], [map_w, 0, 0], [map_w, map_h, 0], [0, map_h, 0]], float)
        q = corners - eye
        zc = q @ forward
        xs, ys = (q @ right) / zc, (q @ down) / zc
        span_x, span_y = xs.max() - xs.min(), ys.max() - ys.min()
        focal = (1.0 - FRAME_MARGIN) * min(image_w / span_x, image_h / span_y)
        cx = image_w / 2.0 - focal * (xs.max() + xs.min()) / 2.0
        cy = image_h / 2.0 - focal * (ys.max() + ys.min()) / 2.0
        d = float(_rule_depth(map_w, map_h) if depth_scale is None else depth_scale)
        return cls(int(map_w), int(map_h), int(image_w), int(image_h), eye, forward, right, down,
                   float(focal), float(cx), float(cy), d, float(np.degrees(e)),
                   float(azimuth_deg))

    @property
    def res_screen(self) -> float:
        """Pixels per unit area of the image plane at unit distance from the eye (focal^2)."""
        return self.focal * self.focal

    def triangles(self) -> tuple[F64, F64]:
        """World positions (2, 3, 3) and texture coordinates (2, 3, 2) of the quad's triangles."""
        return quad_triangles(self.map_w, self.map_h)

    def pixel_directions(self) -> F64:
        """Unnormalised world direction of every pixel's ray, (image_h, image_w, 3)."""
        px = (np.arange(self.image_w) + 0.5 - self.cx) / self.focal
        py = (np.arange(self.image_h) + 0.5 - self.cy) / self.focal
        return (self.forward[None, None, :] + px[None, :, None] * self.right[None, None, :]
                + py[:, None, None] * self.down[None, None, :])

    def fragments(self) -> Fragments:
        """Per covered pixel: entry texel (u0, v0), view vector, TBN, ray length Pl, triangle."""
        dirs = self.pixel_directions().reshape(-1, 3)
        dz = dirs[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(dz < 0.0, -self.eye[2] / dz, np.nan)
        u = self.eye[0] + s * dirs[:, 0]
        v = self.eye[1] + s * dirs[:, 1]
        with np.errstate(invalid="ignore"):
            cov = (dz < 0.0) & (u >= 0.0) & (u < self.map_w) & (v >= 0.0) & (v < self.map_h)
        idx = np.nonzero(cov)[0]
        d = dirs[idx]
        norm = np.linalg.norm(d, axis=-1)
        u0, v0 = u[idx], v[idx]
        tri = np.where(v0 * self.map_w <= u0 * self.map_h, 0, 1).astype(np.int64)
        pos, st = self.triangles()
        frames = tangent_frames(pos, st, self.map_w, self.map_h)
        return Fragments(mask=cov.reshape(self.image_h, self.image_w),
                         row=(idx // self.image_w).astype(np.int64),
                         col=(idx % self.image_w).astype(np.int64),
                         u0=u0, v0=v0, view=d / norm[:, None], tbn=frames[tri],
                         ray_length=s[idx] * norm, tri=tri)

    def rays(self, frags: Fragments | None = None) -> CameraRays:
        """The contract rays (``model.rays.Rays``) of the covered pixels, with their pixels."""
        f = self.fragments() if frags is None else frags
        du, dv = view_to_tangent(f.tbn, f.view, self.depth_scale)
        return CameraRays(Rays(f.u0.copy(), f.v0.copy(), du, dv), f.row, f.col)

    def tiled_rays(self, tile: int = 8, frags: Fragments | None = None) -> CameraRays:
        """:meth:`rays` in the order a tiled rasteriser emits them: tile x tile pixel blocks in
        row-major block order, row-major inside a block (``tile=1``: plain raster order)."""
        r = self.rays(frags)
        order = tile_order(r.row, r.col, self.image_w, tile)
        x = r.rays
        return CameraRays(Rays(x.u0[order], x.v0[order], x.du[order], x.dv[order]),
                          r.row[order], r.col[order])

    def log2_pb(self, tex_w: int | None = None, tex_h: int | None = None) -> F64:
        """log2(Pb) of triangles 0 and 1 for a texture of tex_w x tex_h (default: the map's)."""
        pos, st = self.triangles()
        return log2_pb(pos, st, self.map_w if tex_w is None else tex_w,
                       self.map_h if tex_h is None else tex_h, self.res_screen)
