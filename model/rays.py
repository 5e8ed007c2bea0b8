# SPDX-License-Identifier: Apache-2.0
"""Rays and trace results shared by every method and engine.

A ray enters the displacement volume at depth t = 0 at (u0, v0) (level-0 texel units) and moves
(du, dv) texels per unit of depth: position(t) = (u0 + du t, v0 + dv t), depth(t) = t, t in [0, 1].
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]


@dataclass
class Rays:
    """N rays as four float64 arrays."""

    u0: F64
    v0: F64
    du: F64
    dv: F64

    @classmethod
    def from_array(cls, a: npt.ArrayLike) -> "Rays":
        """From an (N, 4) float64 array of u0, v0, du, dv (the RAYS.npy format)."""
        arr = np.asarray(a, dtype=np.float64)
        if arr.ndim != 2 or arr.shape[1] != 4:
            raise ValueError(f"rays must have shape (N, 4), got {arr.shape}")
        return cls(*(np.ascontiguousarray(arr[:, i]) for i in range(4)))

    def __len__(self) -> int:
        return int(self.u0.shape[0])

    def subset(self, idx: npt.ArrayLike) -> "Rays":
        return Rays(self.u0[idx], self.v0[idx], self.du[idx], self.dv[idx])

    def invalid(self, width: int, height: int) -> npt.NDArray[np.bool_]:
        """Rays with a NaN or infinite number, or starting outside [0, W) x [0, H)."""
        finite = (np.isfinite(self.u0) & np.isfinite(self.v0) & np.isfinite(self.du) &
                  np.isfinite(self.dv))
        with np.errstate(invalid="ignore"):
            inside = (self.u0 >= 0) & (self.u0 < width) & (self.v0 >= 0) & (self.v0 < height)
        return ~(finite & inside)


@dataclass
class TraceResult:
    """Per-ray answers: t, u, v are NaN where there is no hit."""

    t: F64
    u: F64
    v: F64
    hit: npt.NDArray[np.bool_]
    invalid: npt.NDArray[np.bool_]
    iterations: npt.NDArray[np.int64]

    @classmethod
    def empty(cls, n: int) -> "TraceResult":
        nan = np.full(n, np.nan)
        return cls(nan.copy(), nan.copy(), nan.copy(), np.zeros(n, bool), np.zeros(n, bool),
                   np.zeros(n, np.int64))

    def as_npz_dict(self) -> dict[str, np.ndarray]:
        return {"t": self.t, "u": self.u, "v": self.v, "hit": self.hit, "invalid": self.invalid,
                "iterations": self.iterations}
