# SPDX-License-Identifier: Apache-2.0
"""model/scenes.py and model/camera.py: scenes, the pinhole camera, rays and MIP set-up."""
from __future__ import annotations

import numpy as np
import pytest

from model import camera as cam_mod
from model import scenes
from model.camera import VIEWS, Camera, log2_pb, mip_lod, view_to_tangent

SIZES = [(37, 61), (61, 37), 256, (2, 2), 1, (5, 200)]
ANGLES = tuple(VIEWS)


# ------------------------------------------------------------------------------------- scenes


def test_scene_names() -> None:
    assert scenes.SCENES == ("rocks", "stones", "four-shapes", "saints", "wall", "bump", "dent")
    with pytest.raises(ValueError, match="valid scenes: rocks, stones"):
        scenes.height("marble", 8)
    with pytest.raises(ValueError):
        scenes.height("bump", 0)
    with pytest.raises(ValueError):
        scenes.height("bump", (4, 5, 6))


@pytest.mark.parametrize("name", scenes.SCENES)
@pytest.mark.parametrize("size", SIZES, ids=str)
def test_height_range_shape_determinism(name: str, size: int | tuple[int, int]) -> None:
    shape = (size, size) if isinstance(size, int) else size
    h = scenes.height(name, size)
    assert h.shape == shape and h.dtype == np.float64
    assert np.all(np.isfinite(h)) and h.min() >= 0.0 and h.max() <= 1.0
    assert np.array_equal(h, scenes.height(name, size))
    if min(shape) >= 37:
        assert h.std() > 0.02, "a scene is not flat"


@pytest.mark.parametrize("name", scenes.SCENES)
def test_nonsquare_is_centred_crop(name: str) -> None:
    """Resolution-independent coordinates: a (40, 64) map is rows 12..51 of the 64 x 64 one."""
    full = scenes.height(name, 64)
    np.testing.assert_allclose(scenes.height(name, (40, 64)), full[12:52], atol=1e-9)
    np.testing.assert_allclose(scenes.height(name, (64, 22)), full[:, 21:43], atol=1e-9)


@pytest.mark.parametrize("name", scenes.SCENES)
def test_texture_and_load_scene(name: str) -> None:
    t = scenes.texture(name, (37, 61))
    assert t.shape == (37, 61, 3) and t.dtype == np.float32
    assert t.min() >= 0.0 and t.max() <= 1.0
    assert np.array_equal(t, scenes.texture(name, (37, 61)))
    assert t.std() > 0.02
    sc = scenes.load_scene(name, (48, 80))
    assert (sc.height, sc.width) == (48, 80)
    assert sc.depth_scale == pytest.approx(0.08 * 80)
    np.testing.assert_array_equal(sc.heights, scenes.height(name, (48, 80)))
    np.testing.assert_array_equal(sc.texture, scenes.texture(name, (48, 80)))
    np.testing.assert_array_equal(sc.normals, scenes.normal_map(sc.heights, sc.depth_scale))
    n = sc.normals
    assert n.shape == (48, 80, 3) and n.dtype == np.float32
    np.testing.assert_allclose(np.linalg.norm(n, axis=-1), 1.0, atol=1e-6)
    assert np.all(n[..., 2] > 0.0)


def test_normal_map_analytic() -> None:
    flat = scenes.normal_map(np.full((3, 4), 0.5), 10.0)
    np.testing.assert_array_equal(flat, np.broadcast_to([0, 0, 1], (3, 4, 3)))
    # a ramp rising along u by 0.01 per texel at depth 50 texels: dz/du = 0.5 in the interior
    ramp = np.tile(np.arange(6) * 0.01, (4, 1))
    n = scenes.normal_map(ramp, 50.0)
    exp = np.array([-0.5, 0.0, 1.0]) / np.sqrt(1.25)
    np.testing.assert_allclose(n[:, 1:-1], np.broadcast_to(exp, (4, 4, 3)), atol=1e-6)
    # border texels use half the one-sided difference (edge replication)
    exp_b = np.array([-0.25, 0.0, 1.0]) / np.sqrt(1.0625)
    np.testing.assert_allclose(n[:, 0], np.broadcast_to(exp_b, (4, 3)), atol=1e-6)
    # along v (rows)
    nv = scenes.normal_map(ramp.T, 50.0)
    np.testing.assert_allclose(nv[1:-1, :], np.broadcast_to(exp[[1, 0, 2]], (4, 4, 3)), atol=1e-6)
    assert scenes.normal_map(np.zeros((1, 1)), 3.0).shape == (1, 1, 3)


def test_normal_encoding_roundtrip() -> None:
    n = scenes.load_scene("stones", 64).normals
    code = scenes.encode_normals(n)
    assert code.dtype == np.uint8 and code.shape == n.shape
    np.testing.assert_array_equal(scenes.encode_normals([[0.0, 0.0, 1.0], [-1.0, 1.0, 0.0]]),
                                  [[128, 128, 255], [0, 255, 128]])
    back = scenes.decode_normals(code)
    np.testing.assert_allclose(np.linalg.norm(back, axis=-1), 1.0, atol=1e-6)
    assert np.abs(back - n).max() < 2.0 / 255.0 * 2


# ------------------------------------------------------------------------------------- camera


@pytest.fixture(scope="module", params=[(256, 256, 160, 120), (200, 120, 96, 128)],
                ids=["square", "nonsquare"])
def setup(request: pytest.FixtureRequest) -> tuple[int, int, int, int]:
    return request.param


def test_depth_rule_and_view_names() -> None:
    assert cam_mod.depth_scale(256, 256) == pytest.approx(20.48)
    assert cam_mod.depth_scale(100, 300) == pytest.approx(24.0)
    assert cam_mod.elevation("front") == 80.0 and cam_mod.elevation("grazing") == 15.0
    assert cam_mod.elevation(30) == 30.0
    with pytest.raises(ValueError, match="front, oblique, grazing"):
        Camera.for_view("sideways", 8, 8, 8, 8)
    for bad in (0.0, -5.0, 95.0):
        with pytest.raises(ValueError):
            Camera.for_view(bad, 8, 8, 8, 8)
    with pytest.raises(ValueError):
        Camera.for_view("front", 8, 0, 8, 8)


@pytest.mark.parametrize("angle", ANGLES)
def test_fragments(angle: str, setup: tuple[int, int, int, int]) -> None:
    mw, mh, iw, ih = setup
    cam = Camera.for_view(angle, mw, mh, iw, ih)
    f = cam.fragments()
    n = len(f)
    assert f.mask.shape == (ih, iw) and n == int(f.mask.sum()) > 0.05 * iw * ih
    assert np.array_equal(f.mask[f.row, f.col], np.ones(n, bool))
    assert np.all(np.diff(f.row * iw + f.col) > 0), "row-major order"
    assert np.all((f.u0 >= 0) & (f.u0 < mw) & (f.v0 >= 0) & (f.v0 < mh))
    np.testing.assert_allclose(np.linalg.norm(f.view, axis=-1), 1.0, atol=1e-12)
    assert np.all(f.view[:, 2] < 0.0)
    assert np.all(f.ray_length > 0.0) and np.all(np.isfinite(f.ray_length))
    entry = cam.eye + f.ray_length[:, None] * f.view
    np.testing.assert_allclose(entry[:, 0], f.u0, atol=1e-9 * mw)
    np.testing.assert_allclose(entry[:, 1], f.v0, atol=1e-9 * mh)
    np.testing.assert_allclose(entry[:, 2], 0.0, atol=1e-9 * mw)
    assert f.tbn.shape == (n, 3, 3)
    np.testing.assert_allclose(f.tbn, np.broadcast_to(np.eye(3), (n, 3, 3)), atol=1e-15)
    assert set(np.unique(f.tri)) == {0, 1}
    assert np.array_equal(f.tri == 0, f.v0 * mw <= f.u0 * mh)
    # framing: the quad fills the image up to the margin on its tighter axis, centred
    rows, cols = np.nonzero(f.mask)
    fill = max((cols.max() - cols.min() + 1) / iw, (rows.max() - rows.min() + 1) / ih)
    assert 0.95 <= fill <= 1.0
    assert abs((cols.max() + cols.min() + 1) / 2 - iw / 2) <= 2
    assert abs((rows.max() + rows.min() + 1) / 2 - ih / 2) <= 2


@pytest.mark.parametrize("angle", ANGLES)
def test_rays(angle: str, setup: tuple[int, int, int, int]) -> None:
    mw, mh, iw, ih = setup
    cam = Camera.for_view(angle, mw, mh, iw, ih)
    f = cam.fragments()
    rays, row, col = cam.rays()
    d = cam.depth_scale
    assert len(rays) == len(f) and np.array_equal(row, f.row) and np.array_equal(col, f.col)
    assert not rays.invalid(mw, mh).any()
    for a in (rays.u0, rays.v0, rays.du, rays.dv):
        assert a.dtype == np.float64 and np.all(np.isfinite(a))
    # the view-calculation model gives exactly the camera's rays
    du, dv = view_to_tangent(f.tbn, f.view, d)
    assert np.array_equal(du, rays.du) and np.array_equal(dv, rays.dv)
    # (du, dv) = horizontal / vertical travel of the view vector, times the depth
    np.testing.assert_allclose(rays.du, f.view[:, 0] / -f.view[:, 2] * d, rtol=1e-12)
    np.testing.assert_allclose(rays.dv, f.view[:, 1] / -f.view[:, 2] * d, rtol=1e-12)
    slope = np.hypot(rays.du, rays.dv) / d
    if angle == "front":
        assert slope.max() < 0.6 and np.median(slope) < 0.3
    if angle == "grazing":
        assert slope.min() > 2.0
    # the pixel nearest the principal point looks along the optical axis: the view's elevation
    k = np.argmin(np.hypot(f.col + 0.5 - cam.cx, f.row + 0.5 - cam.cy))
    e = np.radians(VIEWS[angle])
    assert slope[k] == pytest.approx(1.0 / np.tan(e), rel=0.03)
    # azimuth 30 degrees: not axis-parallel, the eye beyond the v = H edge
    assert rays.dv[k] < 0.0 and rays.du[k] < 0.0
    assert rays.du[k] / rays.dv[k] == pytest.approx(np.tan(np.radians(30.0)), rel=0.05)


def test_slopes_grow_towards_grazing() -> None:
    med = []
    for angle in ANGLES:
        r = Camera.for_view(angle, 128, 128, 64, 48).rays().rays
        med.append(float(np.median(np.hypot(r.du, r.dv))))
    assert med[0] < med[1] < med[2]


def test_image_not_mirrored() -> None:
    """Image axes map onto (u, v) with a positive determinant: the render reads like the map."""
    for angle in ANGLES:
        cam = Camera.for_view(angle, 64, 64, 80, 60)
        u, v = _uv_image(cam)
        ju = np.gradient(u, axis=1), np.gradient(u, axis=0)
        jv = np.gradient(v, axis=1), np.gradient(v, axis=0)
        det = ju[0] * jv[1] - ju[1] * jv[0]
        assert np.nanmin(det) > 0.0
    front = Camera.for_view(90.0, 64, 64, 80, 60, azimuth_deg=0.0)
    u, v = _uv_image(front)
    assert np.nanmean(np.diff(u, axis=1)) > 0 and np.nanmean(np.diff(v, axis=0)) > 0


def test_view_to_tangent_general_frames(rng: np.random.Generator) -> None:
    """Rotating the frame and the view together changes nothing; an upward view is invalid."""
    cam = Camera.for_view("oblique", 64, 64, 40, 30)
    f = cam.fragments()
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    du0, dv0 = view_to_tangent(f.tbn, f.view, 7.0)
    du1, dv1 = view_to_tangent(q @ f.tbn, f.view @ q.T, 7.0)
    np.testing.assert_allclose(du1, du0, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(dv1, dv0, rtol=1e-9, atol=1e-9)
    du, dv = view_to_tangent(np.eye(3)[None].repeat(3, 0),
                             np.array([[0.3, 0.1, 0.5], [0.3, 0.1, 0.0], [0.0, 0.0, -2.0]]), 4.0)
    assert np.isnan(du[:2]).all() and np.isnan(dv[:2]).all()
    assert du[2] == 0.0 and dv[2] == 0.0


def test_tangent_frames_of_a_tilted_triangle() -> None:
    pos = np.array([[[0, 0, 0], [2, 0, 2], [0, 3, 0]]], float)
    st = np.array([[[0, 0], [1, 0], [0, 1]]], float)
    tbn = cam_mod.tangent_frames(pos, st, 4, 6)
    np.testing.assert_allclose(tbn[0].T @ tbn[0], np.eye(3), atol=1e-12)
    np.testing.assert_allclose(tbn[0][:, 0], np.array([1, 0, 1]) / np.sqrt(2), atol=1e-12)
    np.testing.assert_allclose(tbn[0][:, 1], [0, 1, 0], atol=1e-12)
    np.testing.assert_allclose(tbn[0][:, 2], np.array([-1, 0, 1]) / np.sqrt(2), atol=1e-12)


# ------------------------------------------------------------------------------- MIP set-up


def test_log2_pb_hand_example() -> None:
    # world area 2, (s, t) area 1/2 of a 4 x 4 texture: T_XN = 8; RES_screen 16: T_XS = 1/2
    pos = np.array([[[0, 0, 0], [2, 0, 0], [0, 2, 0]]], float)
    st = np.array([[[0, 0], [1, 0], [0, 1]]], float)
    assert log2_pb(pos, st, 4, 4, 16.0)[0] == pytest.approx(0.5 * np.log2(2 / 0.5))


@pytest.mark.parametrize("angle", ANGLES)
def test_log2_pb_invariants(angle: str) -> None:
    cam = Camera.for_view(angle, 256, 256, 160, 120)
    lp = cam.log2_pb()
    assert lp.shape == (2,) and np.all(np.isfinite(lp)) and lp[0] == pytest.approx(lp[1])
    assert cam.log2_pb(512, 512) == pytest.approx(lp - 1.0, abs=1e-12)   # finer texture: lod + 1
    assert cam.log2_pb(128, 128) == pytest.approx(lp + 1.0, abs=1e-12)
    assert cam.log2_pb(512, 256) == pytest.approx(lp - 0.5, abs=1e-12)
    big = Camera.for_view(angle, 256, 256, 320, 240)                     # twice the pixels
    assert big.log2_pb() == pytest.approx(lp + 1.0, abs=1e-9)


@pytest.mark.parametrize("angle", ["front", "oblique"])
def test_lod_matches_pixel_footprint(angle: str) -> None:
    """Eq. (2) is the texel-per-pixel log2 of a pixel facing the eye on the optical axis.

    The true footprint (from the image-to-texture Jacobian) differs only by the obliquity terms
    the paper neglects: cos^3(off-axis angle) / cos(incidence angle).
    """
    cam = Camera.for_view(angle, 256, 256, 160, 120)
    f = cam.fragments()
    u, v = _uv_image(cam)
    det = (np.gradient(u, axis=1) * np.gradient(v, axis=0)
           - np.gradient(u, axis=0) * np.gradient(v, axis=1))
    measured = 0.5 * np.log2(np.abs(det[f.row, f.col]))
    lod = mip_lod(f.ray_length, cam.log2_pb()[f.tri])
    cos_axis = f.view @ cam.forward
    cos_inc = -f.view[:, 2]
    expected = lod + 0.5 * np.log2(cos_axis ** 3 / cos_inc)
    ok = np.isfinite(measured)
    assert ok.sum() > 0.5 * len(f)
    np.testing.assert_allclose(measured[ok], expected[ok], atol=2e-3)


def _uv_image(cam: Camera) -> tuple[np.ndarray, np.ndarray]:
    """(u, v) where every pixel's ray meets z = 0 (NaN off the quad), image-shaped."""
    u = np.full((cam.image_h, cam.image_w), np.nan)
    v = u.copy()
    f = cam.fragments()
    u[f.row, f.col] = f.u0
    v[f.row, f.col] = f.v0
    return u, v


def test_tile_order() -> None:
    """tile_order: every pixel once, blocks in row-major order, row-major inside a block."""
    from model.camera import Camera, tile_order

    rows, cols = np.divmod(np.arange(6 * 10), 10)
    o = tile_order(rows, cols, 10, 4)
    assert sorted(o.tolist()) == list(range(60))
    first = list(zip(rows[o][:6].tolist(), cols[o][:6].tolist()))
    assert first == [(0, 0), (0, 1), (0, 2), (0, 3), (1, 0), (1, 1)]
    blocks = (rows[o] // 4) * 3 + cols[o] // 4
    assert np.all(np.diff(blocks) >= 0)
    assert np.array_equal(tile_order(rows, cols, 10, 1), np.arange(60))
    cam = Camera.for_view("oblique", 16, 16, 12, 12)
    a, b = cam.rays(), cam.tiled_rays(4)
    assert sorted(zip(b.row.tolist(), b.col.tolist())) == sorted(zip(a.row.tolist(), a.col.tolist()))
    key = {(r, c): i for i, (r, c) in enumerate(zip(a.row.tolist(), a.col.tolist()))}
    idx = np.array([key[(r, c)] for r, c in zip(b.row.tolist(), b.col.tolist())])
    assert np.array_equal(b.rays.du, a.rays.du[idx]) and np.array_equal(b.rays.u0, a.rays.u0[idx])
    with pytest.raises(ValueError):
        tile_order(rows, cols, 10, 0)


def test_tile_order_morton() -> None:
    """tile_order(blocks="morton"): every pixel once, each block's pixels together (row-major
    inside), the blocks along the Z-order curve of (block row, block column)."""
    from model.camera import tile_order

    rows, cols = np.divmod(np.arange(20 * 36), 36)
    o = tile_order(rows, cols, 36, 4, blocks="morton")
    assert sorted(o.tolist()) == list(range(20 * 36))
    br, bc = rows[o] // 4, cols[o] // 4
    starts = np.flatnonzero(np.r_[True, (np.diff(br) != 0) | (np.diff(bc) != 0)])
    assert len(starts) == 5 * 9                     # each block visited once, all its pixels
    seq = list(zip(br[starts].tolist(), bc[starts].tolist()))
    assert seq[:8] == [(0, 0), (0, 1), (1, 0), (1, 1), (0, 2), (0, 3), (1, 2), (1, 3)]

    def z(r: int, c: int) -> int:                   # the curve, bit by bit
        return sum((((r >> k) & 1) << (2 * k + 1)) | (((c >> k) & 1) << (2 * k))
                   for k in range(8))
    assert [z(r, c) for r, c in seq] == sorted(z(r, c) for r, c in seq)
    first = list(zip(rows[o][:5].tolist(), cols[o][:5].tolist()))
    assert first == [(0, 0), (0, 1), (0, 2), (0, 3), (1, 0)]
    with pytest.raises(ValueError):
        tile_order(rows, cols, 36, 4, blocks="hilbert")
