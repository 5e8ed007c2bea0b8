# SPDX-License-Identifier: Apache-2.0
"""traverse_fifo (every FIFO of the traverse unit and the pipeline: FIFO #0, FIFO #1, the
request, miss and out FIFOs, the slot free list) against a deque, clock by clock.

Every clock a random write (only when not full: a write needs full_o = 0 even with a read in
the same clock) and a random read (only when not empty), with the write and read probabilities drifting in bursts so the FIFO runs
empty, full and in between.  After every edge rd_data_o (when not empty), full_o, empty_o and
count_o must equal the model's.  The bound assertions (rtl/traverse/traverse_fifo_assert.sv:
overflow, underflow, count, data order) are on.
"""
from __future__ import annotations

import os
from collections import deque
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import clock_reset, fp_unit, report, runner


@cocotb.test()
async def traverse_fifo_random(dut):
    rng = np.random.default_rng(fp_unit.seed())
    depth, width = int(os.environ["DEPTH"]), int(os.environ["W"])
    await clock_reset.start_and_reset(dut, ["wr_i", "rd_i", "wr_data_i"])
    n = fp_unit.vectors()
    p_wr = rng.uniform(0.0, 1.0, n // 32 + 1).repeat(32)[:n]
    p_rd = rng.uniform(0.0, 1.0, n // 32 + 1).repeat(32)[:n]
    want_wr = rng.random(n) < p_wr
    want_rd = rng.random(n) < p_rd
    data = rng.integers(0, 1 << width, n, dtype=np.uint64).tolist()
    q: deque[int] = deque()
    bad = fulls = empties = 0
    msgs: list[str] = []
    for k in range(n):
        exp = {"full_o": int(len(q) == depth), "empty_o": int(not q), "count_o": len(q)}
        got = {name: int(getattr(dut, name).value) for name in exp}
        if q:
            exp["rd_data_o"] = q[0]
            got["rd_data_o"] = int(dut.rd_data_o.value)
        if got != exp:
            bad += 1
            if len(msgs) < 10:
                msgs.append(f"clock {k}: got {got} expected {exp}")
        fulls += exp["full_o"]
        empties += exp["empty_o"]
        wr = bool(want_wr[k]) and len(q) < depth
        rd = bool(want_rd[k]) and bool(q)
        dut.wr_i.value = int(wr)
        dut.wr_data_i.value = data[k]
        dut.rd_i.value = int(rd)
        await RisingEdge(dut.clk_i)
        if rd:
            q.popleft()
        if wr:
            q.append(data[k])
        await FallingEdge(dut.clk_i)
    report.record(dut._name, f"RTL vs deque (W {width}, DEPTH {depth})", n, bad)
    dut._log.info("VECTORS traverse_fifo W=%d DEPTH=%d: %d clocks (%d full, %d empty), "
                  "%d mismatches", width, depth, n, fulls, empties, bad)
    if fulls == 0 or empties == 0:
        msgs.append(f"the stimulus never reached full ({fulls}) or empty ({empties})")
    if msgs:
        raise AssertionError("\n".join(msgs))


@pytest.mark.parametrize("width,depth,out_reg", [(16, 16, 0), (7, 2, 0), (33, 4, 0),
                                                 (16, 16, 1), (7, 2, 1), (33, 4, 1)])
def test_traverse_fifo(width: int, depth: int, out_reg: int):
    # out_reg 1: the head in a register (the default of the block-RAM FIFOs); the ports must
    # behave clock for clock as without it
    runner.run("traverse_fifo", "test_traverse_fifo", Path(__file__).parent,
               parameters={"W": width, "DEPTH": depth, "OUT_REG": out_reg},
               extra_env={"W": str(width), "DEPTH": str(depth), "VECTORS": "20000"})
