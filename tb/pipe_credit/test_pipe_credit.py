# SPDX-License-Identifier: Apache-2.0
"""pipe_credit (the controller that keeps FIFO #0 from overflowing) against a clock-accurate model.

The wrapper ``pipe_credit_tb`` puts the credit counter where dm_pipeline does: in front of a
unit that cannot stall (LAT clocks) with a DEPTH-entry FIFO behind it whose fill counts against
the limit.  Every clock the test drives a random input (valid bursts and gaps) and random output
back-pressure, and compares in_ready, out_valid, out_data, the in-flight count and the FIFO fill
with the model.  Each item carries a sequence number: it must come out once, in order.  The
assertions bound into the FIFO, the counter and the delay line (rtl/**/*_assert.sv: overflow,
underflow, admission without room, the limit, data order) are on.  Phases:
random, full throughput (always valid, always ready: the model gives the rate), and a stalled
output (the credit must stop admission with the FIFO exactly full, never over).  The three
(DEPTH, LAT) of CASES are built once, side by side, in ``pipe_credit_tb`` (one arrangement each,
own ports and reset, a shared clock) and run at once in one simulation, each with its own random
stream from the printed seed, its own model and checks; a failure names the configuration.
"""
from __future__ import annotations

from collections import deque
from pathlib import Path

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import cases, clock_reset, fp_unit, report, runner

#: (DEPTH, LAT) of the arrangements g_case[0 ..] of pipe_credit_tb (the wrapper's table):
#: dm_pipeline's FIFO #0 depth (F0_DEPTH = 16) behind a shorter latency; a FIFO shallower than
#: the latency (the credit throttles, as for FIFO #0 behind view_calc, pipe_pkg::VIEW_CALC_LAT =
#: 21); the smallest case.
CASES = [(16, 14), (4, 11), (2, 1)]


class CreditModel:
    """pipe_credit + a LAT-clock delay line + a first-word-fall-through FIFO, clock by clock."""

    def __init__(self, depth: int, lat: int) -> None:
        self.depth = depth
        self.cnt = 0
        self.line: list[int | None] = [None] * lat   # [0] entered last clock
        self.fifo: deque[int] = deque()

    def outputs(self) -> dict[str, int]:
        return {"in_ready_o": int(self.cnt + len(self.fifo) < self.depth),
                "out_valid_o": int(bool(self.fifo)),
                "count_o": self.cnt, "fifo_count_o": len(self.fifo)}

    def clock(self, in_valid: int, in_data: int, out_ready: int) -> tuple[bool, int | None]:
        """One rising edge; returns (input taken, item read out or None)."""
        take = bool(in_valid) and self.cnt + len(self.fifo) < self.depth
        out = self.fifo[0] if self.fifo and out_ready else None
        arriving = self.line[-1]
        self.cnt += int(take) - int(arriving is not None)
        self.line = [in_data if take else None] + self.line[:-1]
        if out is not None:
            self.fifo.popleft()
        if arriving is not None:
            self.fifo.append(arriving)
        return take, out


@cocotb.test()
async def pipe_credit_random(dut):
    """Every arrangement of pipe_credit_tb at once (:func:`check_credit` each)."""
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    rngs = cases.streams(len(CASES))
    await cases.check_all([(f"pipe_credit DEPTH {depth}, LAT {lat}",
                            check_credit(dut, i, depth, lat, rngs[i]))
                           for i, (depth, lat) in enumerate(CASES)])


async def check_credit(dut, i: int, depth: int, lat: int, rng: np.random.Generator) -> list[str]:
    """Drive and check ``dut.g_case[i]`` (the arrangement with DEPTH ``depth``, LAT ``lat``) as
    the module docstring says; return the failure messages (none: it passed)."""
    inst = dut.g_case[i]
    if mism := cases.param_mismatches(inst, {"DEPTH": depth, "LAT": lat}):
        return mism
    await clock_reset.reset(inst, ["in_valid_i", "out_ready_i", "in_data_i"], cycles=3,
                            clk=dut.clk_i)
    model = CreditModel(depth, lat)
    n = fp_unit.vectors(fp_unit.VECTORS_COMPOSITE)
    # phase per clock: 0 random, 1 always valid + ready (throughput), 2 output stalled
    phase = np.zeros(n, dtype=np.int64)
    phase[n // 2: n // 2 + n // 8] = 1
    phase[n // 2 + n // 8: n // 2 + n // 8 + 4 * (depth + lat)] = 2
    p_valid = rng.uniform(0.2, 1.0, n // 64 + 1).repeat(64)[:n]   # bursts of varying density
    p_ready = rng.uniform(0.1, 1.0, n // 64 + 1).repeat(64)[:n]
    valid = np.where(phase == 0, rng.random(n) < p_valid, True)
    ready = np.where(phase == 0, rng.random(n) < p_ready, phase == 1)
    seq_in = seq_out = 0
    bad = 0
    msgs: list[str] = []
    taken_full = 0
    stalled_full = True
    for k in range(n):
        inst.in_valid_i.value = int(valid[k])
        inst.in_data_i.value = seq_in & 0xFFFF
        inst.out_ready_i.value = int(ready[k])
        exp = model.outputs()
        got = {name: int(getattr(inst, name).value) for name in exp}
        if exp["out_valid_o"]:
            exp["out_data_o"] = model.fifo[0] & 0xFFFF
            got["out_data_o"] = int(inst.out_data_o.value)
        if got != exp:
            bad += 1
            if len(msgs) < 10:
                msgs.append(f"clock {k} (phase {phase[k]}): got {got} expected {exp}")
        take, out = model.clock(int(valid[k]), seq_in & 0xFFFF, int(ready[k]))
        if take:
            seq_in += 1
            taken_full += int(phase[k] == 1)
        if out is not None:
            if out != seq_out & 0xFFFF:
                bad += 1
                msgs.append(f"clock {k}: item {out} out, expected {seq_out & 0xFFFF}")
            seq_out += 1
        if phase[k] == 2 and k + 1 < n and phase[k + 1] != 2:
            stalled_full = model.cnt == 0 and len(model.fifo) == depth
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
    # drain
    inst.in_valid_i.value = 0
    inst.out_ready_i.value = 1
    for _ in range(lat + depth + 4):
        _, out = model.clock(0, 0, 1)
        if out is not None:
            seq_out += 1
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
    if int(inst.out_valid_o.value) or int(inst.count_o.value):
        bad += 1
        msgs.append("not empty after draining")
    if seq_out != seq_in:
        bad += 1
        msgs.append(f"{seq_in} items in, {seq_out} out")
    if not stalled_full:
        bad += 1
        msgs.append("with the output stalled the FIFO did not end exactly full with nothing in "
                    "flight")
    rate = taken_full / max(1, int(np.count_nonzero(phase == 1)))
    report.record("pipe_credit_tb", f"RTL vs credit model (DEPTH {depth}, LAT {lat})", n, bad)
    dut._log.info("VECTORS pipe_credit DEPTH=%d LAT=%d: %d clocks, %d items, %d mismatches; "
                  "admission rate with output always ready %.3f (expected min(1, DEPTH/(LAT+1)) "
                  "= %.3f)", depth, lat, n, seq_in, bad, rate, min(1.0, depth / (lat + 1)))
    return msgs


def test_pipe_credit() -> None:
    """Build pipe_credit_tb (every arrangement of CASES) once and run :func:`pipe_credit_random`
    (20,000 clocks per arrangement)."""
    here = Path(__file__).parent
    runner.run("pipe_credit_tb", "test_pipe_credit", here, rtl_top="pipe_credit",
               extra_sources=[str(here / "pipe_credit_tb.sv")], extra_env={"VECTORS": "20000"})
