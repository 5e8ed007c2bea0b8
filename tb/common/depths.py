# SPDX-License-Identifier: Apache-2.0
"""The float units' depths a block's test builds it at: (ADD_LAT, MUL_LAT) pairs.

The design builds its blocks (view_calc, mip_level, tex_addr, tex_filter, shade_unit,
traverse_setup; traverse_loop takes MUL_LAT alone) with f24_add at LAT ``ADD_LAT`` and f24_mul at
LAT ``MUL_LAT``, by default pipe_pkg's F24_ADD_LAT / F24_MUL_LAT (:data:`DEFAULT`); every block
also takes the paper's depths (2, 1).  ``make test`` runs a block at the design's pair,
``make test-long`` (TB_LONG=1) at every pair of :data:`PAIRS`.  The pair of a build reaches its
cocotb process in the environment variable :data:`ENV`.
"""
from __future__ import annotations

import os
from typing import Any, Callable, Optional

import pytest

from tb.common import runner
from tb.harness import sv_params

#: The pairs the blocks are verified at: the paper's depths and the design's.
PAIRS: tuple[tuple[int, int], ...] = ((2, 1), (3, 2))
#: The design's pair (pipe_pkg's F24_ADD_LAT, F24_MUL_LAT): the blocks' parameter defaults.
DEFAULT: tuple[int, int] = tuple(sv_params.values("pipe_pkg", "F24_ADD_LAT", "F24_MUL_LAT"))
#: Environment variable carrying "ADD_LAT,MUL_LAT" of the build into the cocotb test.
ENV = "F24_DEPTHS"


def cases(pairs: tuple[tuple[int, int], ...] = PAIRS) -> list[Any]:
    """pytest parameters ``add, mul``: the design's pair always, the others under TB_LONG=1."""
    return [pytest.param(a, m, id=f"add{a}-mul{m}",
                         marks=[] if (a, m) == DEFAULT else pytest.mark.skipif(
                             not runner.long_stimulus(),
                             reason="not the design's depths: make test-long (TB_LONG=1)"))
            for a, m in pairs]


def parameters(add: int, mul: int) -> dict[str, int]:
    """The build's parameters: none at the design's pair (the defaults are checked too)."""
    return {} if (add, mul) == DEFAULT else {"ADD_LAT": add, "MUL_LAT": mul}


def env(add: int, mul: int) -> dict[str, str]:
    """The environment that tells the cocotb test the build's pair."""
    return {ENV: f"{add},{mul}"}


def current() -> tuple[int, int]:
    """Inside the cocotb test: the pair the unit under test was built at."""
    val = os.environ.get(ENV)
    if not val:
        return DEFAULT
    add, mul = (int(x) for x in val.split(","))
    return add, mul


def latency(func: str, mirror: Optional[Callable[[int, int], int]] = None,
            const: Optional[str] = None, pkg: str = "pipe_pkg",
            pair: Optional[tuple[int, int]] = None) -> int:
    """Inside the cocotb test: the latency of the unit under test, the package function ``func``
    (for example ``tex_addr_lat``) at the build's pair; checked equal to the test's own
    ``mirror`` of that function when given, and at the design's pair to the package constant
    ``const`` (for example ``TEX_ADDR_LAT``) when given.  ``pair``: the (ADD_LAT, MUL_LAT) of
    the instance under test instead of the build's (several instances of one build)."""
    add, mul = pair or current()
    lat = int(sv_params.call(pkg, func, add, mul))
    if mirror is not None:
        assert lat == mirror(add, mul), (func, add, mul, lat)
    if const is not None and (add, mul) == DEFAULT:
        assert lat == sv_params.value(pkg, const), (func, const, lat)
    return lat
