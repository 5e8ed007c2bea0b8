# SPDX-License-Identifier: Apache-2.0
"""pipe_delay (a delay of N enabled clocks, a RAM line from RAM_MIN clocks on) against a list model.

Every clock the test drives a random W-bit value and a random clock enable (in bursts of
varying density, with runs of stalls long enough to hold the line for more than N clocks), and
checks q_o against the value presented N enabled edges earlier (once N enabled edges have
passed since the reset), and that q_o holds while en_i is 0 (a synchronous-read RAM line reads
ahead: its read register must keep the word through a stall).  Mid-run the reset is asserted
for a few clocks with the enable random: the line needs N enabled edges again afterwards and is
checked from then on.  Built as a RAM line (N = 2, the shortest; 16, one LUT RAM deep; 67, the
shade unit's longest colour lane) and as registers (N = 5 below RAM_MIN; 67 with RAM_MIN = 0).
"""
from __future__ import annotations

import os
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import clock_reset, fp_unit, report, runner

W = 16


@cocotb.test()
async def pipe_delay_random(dut):
    rng = np.random.default_rng(fp_unit.seed())
    n_del = int(os.environ["N"])
    await clock_reset.start_and_reset(dut, ["en_i", "d_i"])
    clocks = 20000
    p_en = rng.choice([0.05, 0.3, 0.7, 1.0], clocks // 64 + 1).repeat(64)[:clocks]
    en = rng.random(clocks) < p_en
    data = rng.integers(0, 1 << W, clocks)
    reset_at = clocks // 2
    hist: list[int] = []     # values taken on enabled edges since the last reset
    bad = checked = held = 0
    msgs: list[str] = []
    last = None
    for k in range(clocks):
        rst = reset_at <= k < reset_at + 3
        dut.rst_ni.value = int(not rst)
        dut.en_i.value = int(en[k])
        dut.d_i.value = int(data[k])
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        if rst:
            hist = []        # the line's contents before the reset are not checked
            last = None
            continue
        got = int(dut.q_o.value)
        if en[k]:
            hist.append(int(data[k]))
            if len(hist) >= n_del:
                exp = hist[-n_del]
                checked += 1
                if got != exp:
                    bad += 1
                    if len(msgs) < 10:
                        msgs.append(f"clock {k}: q_o {got:#x}, expected {exp:#x}")
        elif last is not None and len(hist) >= n_del:
            held += 1
            if got != last:
                bad += 1
                if len(msgs) < 10:
                    msgs.append(f"clock {k} (stalled): q_o {got:#x}, held {last:#x}")
        last = got
    report.record(dut._name, f"RTL vs delay model (N {n_del}, RAM_MIN {os.environ['RAM_MIN']})",
                  checked + held, bad)
    dut._log.info("VECTORS pipe_delay N=%d: %d enabled clocks checked, %d stalled clocks held, "
                  "%d mismatches", n_del, checked, held, bad)
    assert checked > clocks // 4 and held > clocks // 8, (checked, held)
    if msgs:
        raise AssertionError("\n".join(msgs))


@pytest.mark.parametrize("n,ram_min", [(2, 2), (16, 8), (67, 8), (5, 8), (67, 0)])
def test_pipe_delay(n: int, ram_min: int) -> None:
    runner.run("pipe_delay", "test_pipe_delay", Path(__file__).parent,
               parameters={"W": W, "N": n, "RAM_MIN": ram_min},
               extra_env={"N": str(n), "RAM_MIN": str(ram_min)})
