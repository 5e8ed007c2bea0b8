# SPDX-License-Identifier: Apache-2.0
"""Start a unit's clock and reset it: the opening every small unit's testbench shares."""
from __future__ import annotations

from typing import Iterable

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge


async def start_and_reset(dut, zero: Iterable[str], cycles: int = 2, period_ns: int = 10) -> None:
    """Start a ``period_ns`` clock on ``clk_i``, drive ``rst_ni`` low and each input named in
    ``zero`` to 0 for ``cycles`` rising edges, and release ``rst_ni`` after the next falling edge
    (so the first clock after the reset is the next rising edge)."""
    cocotb.start_soon(Clock(dut.clk_i, period_ns, unit="ns").start())
    await reset(dut, zero, cycles)


async def reset(unit, zero: Iterable[str], cycles: int = 2, clk=None) -> None:
    """Drive ``unit.rst_ni`` low and each input of ``unit`` named in ``zero`` to 0 for ``cycles``
    rising edges of ``clk`` (default ``unit.clk_i``, which must be running), and release
    ``rst_ni`` after the next falling edge: :func:`start_and_reset` without starting the clock,
    for one of several units in one build that share a clock (e.g. ``dut.g_case[i]`` of a
    testbench wrapper, each with its own reset)."""
    clk = unit.clk_i if clk is None else clk
    unit.rst_ni.value = 0
    for name in zero:
        getattr(unit, name).value = 0
    for _ in range(cycles):
        await RisingEdge(clk)
    await FallingEdge(clk)
    unit.rst_ni.value = 1
