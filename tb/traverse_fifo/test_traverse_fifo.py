# SPDX-License-Identifier: Apache-2.0
"""traverse_fifo (every FIFO of the traverse unit and the pipeline: FIFO #0, FIFO #1, the
request, miss and out FIFOs, the slot free list) against a deque, clock by clock.

Every clock a random write (only when not full: a write needs full_o = 0 even with a read in
the same clock) and a random read (only when not empty), with the write and read probabilities
drifting in bursts so the FIFO runs empty, full and in between.  After every edge rd_data_o
(when not empty), full_o, empty_o and count_o must equal the model's.  The bound assertions
(rtl/traverse/traverse_fifo_assert.sv: overflow, underflow, count, data order) are on.  Three
sizes, each without and with OUT_REG (the head in a register), are built once, side by side, in
the wrapper ``traverse_fifo_tb`` (one instance each, own ports and reset, a shared clock) and run
at once in one simulation, each with its own random stream from the printed seed and its own
checks; a failure names the configuration.
"""
from __future__ import annotations

from collections import deque
from pathlib import Path

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import cases, clock_reset, fp_unit, report, runner

#: (W, DEPTH, OUT_REG) of the instances g_case[0 ..] of traverse_fifo_tb (the wrapper's table):
#: three sizes, each without and with the head in a register (OUT_REG 1, the default of the
#: block-RAM FIFOs: the ports must behave clock for clock as without it).
CASES = [(16, 16, 0), (7, 2, 0), (33, 4, 0), (16, 16, 1), (7, 2, 1), (33, 4, 1)]


@cocotb.test()
async def traverse_fifo_random(dut):
    """Every instance of traverse_fifo_tb at once (:func:`check_fifo` each)."""
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    rngs = cases.streams(len(CASES))
    await cases.check_all([(f"traverse_fifo W {w}, DEPTH {d}, OUT_REG {o}",
                            check_fifo(dut, i, w, d, o, rngs[i]))
                           for i, (w, d, o) in enumerate(CASES)])


async def check_fifo(dut, i: int, width: int, depth: int, out_reg: int,
                     rng: np.random.Generator) -> list[str]:
    """Drive and check ``dut.g_case[i]`` (traverse_fifo with W ``width``, DEPTH ``depth``,
    OUT_REG ``out_reg``) as the module docstring says; return the failure messages (none: it
    passed)."""
    inst = dut.g_case[i]
    if mism := cases.param_mismatches(inst, {"W": width, "DEPTH": depth, "OUT_REG": out_reg}):
        return mism
    await clock_reset.reset(inst, ["wr_i", "rd_i", "wr_data_i"], clk=dut.clk_i)
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
        got = {name: int(getattr(inst, name).value) for name in exp}
        if q:
            exp["rd_data_o"] = q[0]
            got["rd_data_o"] = int(inst.rd_data_o.value)
        if got != exp:
            bad += 1
            if len(msgs) < 10:
                msgs.append(f"clock {k}: got {got} expected {exp}")
        fulls += exp["full_o"]
        empties += exp["empty_o"]
        wr = bool(want_wr[k]) and len(q) < depth
        rd = bool(want_rd[k]) and bool(q)
        inst.wr_i.value = int(wr)
        inst.wr_data_i.value = data[k]
        inst.rd_i.value = int(rd)
        await RisingEdge(dut.clk_i)
        if rd:
            q.popleft()
        if wr:
            q.append(data[k])
        await FallingEdge(dut.clk_i)
    report.record("traverse_fifo", f"RTL vs deque (W {width}, DEPTH {depth})", n, bad)
    dut._log.info("VECTORS traverse_fifo W=%d DEPTH=%d: %d clocks (%d full, %d empty), "
                  "%d mismatches", width, depth, n, fulls, empties, bad)
    if fulls == 0 or empties == 0:
        msgs.append(f"the stimulus never reached full ({fulls}) or empty ({empties})")
    return msgs


def test_traverse_fifo() -> None:
    """Build traverse_fifo_tb (every configuration of CASES) once and run
    :func:`traverse_fifo_random` (20,000 clocks per instance)."""
    here = Path(__file__).parent
    runner.run("traverse_fifo_tb", "test_traverse_fifo", here, rtl_top="traverse_fifo",
               extra_sources=[str(here / "traverse_fifo_tb.sv")], extra_env={"VECTORS": "20000"})
