# SPDX-License-Identifier: Apache-2.0
"""Writing a table of the RTL through its write port (<port>_we_i, <port>_waddr_i,
<port>_wdata_i): the triangle table (tt), the level tables (lvt), the height level offsets
(hlt)."""
from __future__ import annotations

from collections.abc import Iterable

from cocotb.triggers import FallingEdge


async def write_table(dut, clk, port: str, writes: Iterable[tuple[int, int]]) -> None:
    """One write per clock (inputs set after a falling edge), then <port>_we_i = 0."""
    we, waddr, wdata = (getattr(dut, f"{port}_{s}_i") for s in ("we", "waddr", "wdata"))
    for addr, word in writes:
        we.value = 1
        waddr.value = addr
        wdata.value = word
        await FallingEdge(clk)
    we.value = 0
