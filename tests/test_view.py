# SPDX-License-Identifier: Apache-2.0
"""model/view.py: the view-calculation unit's op sequence."""
from __future__ import annotations

import numpy as np
import pytest

from model import camera, f24, view
from model.arith import ENGINES


def random_frames(rng: np.random.Generator, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Random orthonormal TBNs and unit view vectors, most pointing into the surface."""
    q, _ = np.linalg.qr(rng.normal(size=(n, 3, 3)))
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    return q, v


def test_f64_matches_camera(rng: np.random.Generator) -> None:
    tbn, v = random_frames(rng, 5000)
    out = view.view_calc(ENGINES["f64"], tbn, v, 20.48)
    du, dv = camera.view_to_tangent(tbn, v, 20.48)
    ok = ~np.isnan(du)
    assert np.array_equal(ok, ~np.isnan(out.du)) and 0.3 < ok.mean() < 0.7
    np.testing.assert_allclose(out.du[ok], du[ok], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(out.dv[ok], dv[ok], rtol=1e-9, atol=1e-9)
    down = -np.einsum("nj,nj->n", tbn[:, :, 2], v)
    np.testing.assert_allclose(out.seg[ok], 20.48 / down[ok], rtol=1e-12)


def test_f24_is_the_op_sequence(rng: np.random.Generator) -> None:
    """Every step rounded to f24 in the documented order (f24.add/mul/div on bit patterns)."""
    tbn, v = random_frames(rng, 4000)
    out = view.view_calc(ENGINES["f24"], tbn, v, 20.48)
    V = [f24.from_float(v[:, i]) for i in range(3)]

    def dot(c: int) -> np.ndarray:
        m = [f24.from_float(tbn[:, i, c]) for i in range(3)]
        return f24.add(f24.add(f24.mul(m[0], V[0]), f24.mul(m[1], V[1])), f24.mul(m[2], V[2]))

    x, y, z = dot(0), dot(1), dot(2)
    down = z ^ np.uint32(0x800000)
    k = f24.div(f24.from_float(np.full(len(v), 20.48)), down)
    ok = f24.to_float(down) > 0
    for got, want in ((out.du, f24.mul(x, k)), (out.dv, f24.mul(y, k)), (out.seg, k)):
        assert np.array_equal(f24.from_float(got[ok]), want[ok])
        assert np.isnan(got[~ok]).all()


@pytest.mark.parametrize("engine", ["f64", "f24"])
def test_unusable_views_are_nan(engine: str) -> None:
    eye = np.eye(3)
    tbn = np.stack([eye, eye, eye, np.zeros((3, 3)), eye, eye])
    v = np.array([[0.3, 0.1, 0.5], [0.6, 0.8, 0.0], [np.nan, 0, -1], [0, 0, -1], [0, 0, -1],
                  [0.6, 0.0, -0.8]])
    out = view.view_calc(ENGINES[engine], tbn, v, 8.0)
    assert np.isnan(out.du[:4]).all() and np.isnan(out.dv[:4]).all() and np.isnan(out.seg[:4]).all()
    assert out.du[4] == 0.0 and out.dv[4] == 0.0 and out.seg[4] == 8.0
    assert out.du[5] == pytest.approx(6.0, rel=1e-4) and out.seg[5] == pytest.approx(10.0, rel=1e-4)
    with pytest.raises(ValueError):
        view.view_calc(ENGINES[engine], eye, v, 8.0)
