# SPDX-License-Identifier: Apache-2.0
"""Glue between the golden model and the traverse unit (``rtl/traverse/traverse_unit.sv``).

The unit computes exactly :func:`model.traverse.trace` with the ``f24`` engine.  This module turns a
:class:`~model.heightmap.Pyramid` and a method name into the unit's configuration inputs, rays into
the f24 words of its ray stream, and model results into the words the unit returns, so that a
testbench (or the full pipeline's) compares bit patterns only.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from model import f24
from model.heightmap import Pyramid
from model.rays import Rays, TraceResult
from model.traverse import EXACT_METHODS, METHOD_CODES, METHODS, iteration_cap

from . import sv_params

#: Limits of the configuration ports, read from rtl/traverse/traverse_pkg.sv: level offsets held
#: (root level n <= MAX_LEVELS - 1, maps up to 32768 x 32768), map width / height bits, iteration
#: counter and cap bits, byte address bits.
MAX_LEVELS, DIM_W, ITER_W, ADDR_W = sv_params.values("traverse_pkg", "MAX_LEVELS", "DIM_W",
                                                     "ITER_W", "ADDR_W")
#: Clocks from a lookup request to its response (traverse_pkg::LOOKUP_LAT).
LOOKUP_LAT = sv_params.value("traverse_pkg", "LOOKUP_LAT")
#: Stages of the loop ring (one ray slot each; traverse_pkg::LOOP_DEPTH) and of the setup pipeline
#: (traverse_pkg::SETUP_LAT: the pipelined divider's f24_pkg::F24_DIV_LAT clocks, then 13 more).
LOOP_DEPTH = sv_params.value("traverse_pkg", "LOOP_DEPTH")
SETUP_DEPTH = sv_params.value("traverse_pkg", "SETUP_LAT")


#: What ``traverse_pkg::decode_method`` implements for each method code, in the fields of
#: :class:`model.traverse.Method`: (start_level, descent, descent_levels, level_up, clip).  The
#: descent levels matter only for "multi" and "xor".
RTL_METHODS: dict[str, tuple[bool, str, int, str, bool]] = {
    "oh": (False, "one", 2, "none", False),
    "tevs": (False, "one", 2, "tevs", False),
    "drobot": (False, "one", 2, "drobot", False),
    "start-level": (True, "one", 2, "none", False),
    "multi-down": (False, "multi", 2, "none", False),
    "selective": (False, "one", 2, "selective", False),
    "coherent": (False, "one", 2, "coherent", False),
    "park": (True, "multi", 2, "selective", False),
    "park-gpu": (True, "multi", 2, "coherent", False),
    "park-xor": (True, "xor", 3, "selective", True),
}


def method_differences() -> list[str]:
    """Where the RTL's method table differs from model.traverse.METHODS (empty: none)."""
    out = []
    if tuple(RTL_METHODS) != EXACT_METHODS:
        out.append(f"method codes: RTL {tuple(RTL_METHODS)} vs model {EXACT_METHODS}")
    for name, m in METHODS.items():
        lv = m.descent_levels if m.descent != "one" else 2
        want = (m.start_level, m.descent, lv, m.level_up, m.clip)
        if RTL_METHODS.get(name) != want:
            out.append(f"{name}: RTL {RTL_METHODS.get(name)} vs model {want}")
        if m.descent != "one" and not 1 <= m.descent_levels <= 3:
            out.append(f"{name}: descent_levels {m.descent_levels} does not fit the RTL's 2 bits")
    return out


@dataclass(frozen=True)
class Config:
    """The values of the unit's ``cfg_*`` inputs."""

    method: int
    width: int
    height: int
    root_level: int
    bits16: int
    base: int
    level_off: int      # packed: level k's byte offset in bits [32k + 31 : 32k]
    root_code: int
    iter_cap: int

    def ports(self) -> dict[str, int]:
        """Port name -> value (the level offsets are a table: :meth:`hlt_writes`)."""
        return {"cfg_method_i": self.method, "cfg_width_i": self.width,
                "cfg_height_i": self.height, "cfg_root_level_i": self.root_level,
                "cfg_bits16_i": self.bits16, "cfg_base_i": self.base,
                "cfg_root_code_i": self.root_code, "cfg_iter_cap_i": self.iter_cap}

    def hlt_writes(self) -> list[tuple[int, int]]:
        """The writes (hlt_waddr_i, hlt_wdata_i) of the unit's level-offset table: every level
        0 .. MAX_LEVELS - 1 (0 past the root)."""
        return [(k, (self.level_off >> (32 * k)) & 0xFFFFFFFF) for k in range(MAX_LEVELS)]


def config(pyr: Pyramid, method: str, base: int = 0, align: int = 64) -> Config:
    """The configuration for tracing ``pyr`` (stored at byte address ``base``) with ``method``."""
    if pyr.n >= MAX_LEVELS:
        raise ValueError(f"the unit holds {MAX_LEVELS} levels; this pyramid has {pyr.n + 1}")
    cap = iteration_cap(pyr)
    if cap >= 1 << ITER_W:
        raise ValueError(f"iteration cap {cap} does not fit {ITER_W} bits")
    if not 0 <= base < 1 << ADDR_W:
        raise ValueError("base address out of range")
    offs = pyr.level_offsets(align)
    packed = 0
    for k, o in enumerate(offs):
        packed |= (o & 0xFFFFFFFF) << (32 * k)
    return Config(method=METHOD_CODES[method], width=pyr.width, height=pyr.height,
                  root_level=pyr.n, bits16=int(pyr.bits == 16), base=base, level_off=packed,
                  root_code=int(pyr.levels[pyr.n][0, 0]), iter_cap=cap)


def ray_words(rays: Rays) -> tuple[npt.NDArray[np.uint32], ...]:
    """u0, v0, du, dv as f24 words: exactly the model's quantisation ``ar.r()`` of the rays."""
    return tuple(f24.from_float(np.asarray(x, dtype=np.float64))
                 for x in (rays.u0, rays.v0, rays.du, rays.dv))


@dataclass
class ExpectedWords:
    """What the unit must return per ray (t, u, v words are meaningful where hit)."""

    t: npt.NDArray[np.uint32]
    u: npt.NDArray[np.uint32]
    v: npt.NDArray[np.uint32]
    hit: npt.NDArray[np.bool_]
    invalid: npt.NDArray[np.bool_]
    iterations: npt.NDArray[np.int64]


def expected_words(res: TraceResult) -> ExpectedWords:
    """Model results as unit words (the model's f24 values convert exactly)."""
    with np.errstate(invalid="ignore"):
        return ExpectedWords(t=f24.from_float(res.t), u=f24.from_float(res.u),
                             v=f24.from_float(res.v), hit=res.hit.copy(),
                             invalid=res.invalid.copy(), iterations=res.iterations.copy())
