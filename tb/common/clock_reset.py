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
    dut.rst_ni.value = 0
    for name in zero:
        getattr(dut, name).value = 0
    for _ in range(cycles):
        await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 1
