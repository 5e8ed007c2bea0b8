# SPDX-License-Identifier: Apache-2.0
"""Stimulus of the traversal tests shared by the model tests (tests/test_traverse.py,
tests/test_rtl_engine.py) and the cocotb tests of traverse_unit and traverse_system: random rays
with the awkward cases mixed in, and height fields of three kinds."""
from __future__ import annotations

import numpy as np

from model.rays import Rays


def adversarial_rays(rng: np.random.Generator, w: int, h: int, n: int) -> Rays:
    """Random rays with every awkward case mixed in."""
    u0 = rng.uniform(0, w, n)
    v0 = rng.uniform(0, h, n)
    ang = rng.uniform(0, 2 * np.pi, n)
    length = rng.choice([0.0, 0.3, 2.0, max(w, h) / 4, max(w, h) * 3], n) * rng.random(n)
    du, dv = length * np.cos(ang), length * np.sin(ang)
    q = n // 16
    u0[:q] = np.floor(u0[:q])                      # starts on a vertical texel edge
    v0[q:2 * q] = np.floor(v0[q:2 * q])            # on a horizontal edge
    u0[2 * q:3 * q] = np.floor(u0[2 * q:3 * q])    # on a corner
    v0[2 * q:3 * q] = np.floor(v0[2 * q:3 * q])
    du[3 * q:4 * q] = 0                            # axis-parallel
    dv[4 * q:5 * q] = 0
    du[5 * q:6 * q] = dv[5 * q:6 * q] = 0          # vertical
    dv[6 * q:7 * q] = du[6 * q:7 * q]              # diagonal: through corners
    u0[6 * q:7 * q] = np.floor(u0[6 * q:7 * q])
    v0[6 * q:7 * q] = np.floor(v0[6 * q:7 * q])
    dv[7 * q:8 * q] = -du[7 * q:8 * q]
    u0[7 * q:8 * q] = np.floor(u0[7 * q:8 * q])
    v0[7 * q:8 * q] = np.floor(v0[7 * q:8 * q])
    du[8 * q:9 * q] = np.round(du[8 * q:9 * q])    # integer slopes: lands on edges at t = 1
    dv[8 * q:9 * q] = np.round(dv[8 * q:9 * q])
    g = slice(9 * q, 10 * q)                       # grazing: several times the map size
    du[g] = rng.choice([-1, 1], q) * rng.uniform(1, 5) * max(w, h)
    dv[g] = rng.uniform(-1, 1, q) * max(w, h)
    u0[10 * q:10 * q + 4] = [0.0, 0.0, float(w) - 1e-9, 0.5]  # edges of the map
    du[10 * q:10 * q + 4] = [-1.0, 1.0, 1.0, -0.5]
    # Invalid rays: NaN / Inf fields, starts outside.
    bad = slice(n - 8, n)
    u0[bad] = [np.nan, -0.5, float(w), 0.5, 0.5, 0.5, 0.5, np.inf]
    v0[bad] = [0.5, 0.5, 0.5, float(h) + 1, np.nan, 0.5, 0.5, 0.5]
    du[bad] = [1, 1, 1, 1, 1, np.inf, 1, 1]
    dv[bad] = [1, 1, 1, 1, 1, 1, -np.inf, 1]
    return Rays(u0, v0, du, dv)


def height_field(rng: np.random.Generator, h: int, w: int, kind: int) -> np.ndarray:
    """An h x w height field in [0, 1]: kind 0 rough (mostly low), 1 flat (ties on every
    plane), 2 sparse spikes (long empty runs)."""
    if kind == 0:
        return rng.random((h, w)) ** 3                    # rough, mostly low
    if kind == 1:
        return np.full((h, w), 0.5)                       # flat: ties on every plane
    return (rng.random((h, w)) < 0.05).astype(float)      # sparse spikes (long empty runs)
