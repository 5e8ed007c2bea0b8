# SPDX-License-Identifier: Apache-2.0
"""Every method on every scene at every view angle (camera rays, small sizes)."""
from __future__ import annotations

import numpy as np
import pytest

from model import approx, camera, heightmap, scenes, traverse
from reference_walk import walk
from tb.common import report


@pytest.mark.parametrize("scene", scenes.SCENES)
def test_every_method_on_scene(scene: str) -> None:
    sc = scenes.load_scene(scene, 64)
    pyr = heightmap.build(sc.heights)
    for angle in ("front", "oblique", "grazing"):
        rays = camera.Camera.for_view(angle, 64, 64, 40, 40).rays().rays
        for engine in ("f64", "f24"):
            ref = walk(pyr, rays, engine)
            for m in traverse.EXACT_METHODS:
                res = traverse.trace(pyr, rays, m, engine)
                same_t = (res.t == ref.t) | (np.isnan(res.t) & np.isnan(ref.t))
                bad = int((~same_t | (res.hit != ref.hit)).sum())
                report.record("model.traverse", f"scene rays vs walk ({engine})", len(rays), bad)
                assert bad == 0, (scene, angle, engine, m)
        exact = traverse.trace(pyr, rays, "park", "f64")
        for name, fn in approx.APPROX_METHODS.items():
            params = {"depth_scale": sc.depth_scale} if name in ("parallax", "parallax-iter",
                                                                  "distance") else {}
            r = fn(pyr, rays, **params)
            ok = r.hit & exact.hit
            assert np.all((r.t[r.hit] >= 0) & (r.t[r.hit] <= 1)), (scene, angle, name)
            assert r.hit.mean() > 0.5 and (r.iterations[r.hit] >= 1).all(), (scene, angle, name)
            assert np.isfinite(r.u[ok]).all() and np.isfinite(r.v[ok]).all()
