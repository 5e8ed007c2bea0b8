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
The five are built once, side by side, in the wrapper ``pipe_delay_tb`` (one instance each, own
ports and reset, a shared clock) and run at once in one simulation, each with its own random
stream from the printed seed and its own checks; a failure names the configuration.
"""
from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import cases, clock_reset, report, runner

W = 16
#: (N, RAM_MIN) of the instances g_case[0 ..] of pipe_delay_tb (the wrapper's table).
CASES = [(2, 2), (16, 8), (67, 8), (5, 8), (67, 0)]


@cocotb.test()
async def pipe_delay_random(dut):
    """Every instance of pipe_delay_tb at once (:func:`check_line` each)."""
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    rngs = cases.streams(len(CASES))
    await cases.check_all([(f"pipe_delay N {n}, RAM_MIN {ram_min}",
                            check_line(dut, i, n, ram_min, rngs[i]))
                           for i, (n, ram_min) in enumerate(CASES)])


async def check_line(dut, i: int, n_del: int, ram_min: int,
                     rng: np.random.Generator) -> list[str]:
    """Drive and check ``dut.g_case[i]`` (pipe_delay with N ``n_del``, RAM_MIN ``ram_min``) as
    the module docstring says; return the failure messages (none: it passed)."""
    inst = dut.g_case[i]
    if mism := cases.param_mismatches(inst, {"N": n_del, "RAM_MIN": ram_min}):
        return mism
    await clock_reset.reset(inst, ["en_i", "d_i"], clk=dut.clk_i)
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
        inst.rst_ni.value = int(not rst)
        inst.en_i.value = int(en[k])
        inst.d_i.value = int(data[k])
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
        if rst:
            hist = []        # the line's contents before the reset are not checked
            last = None
            continue
        got = int(inst.q_o.value)
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
    report.record("pipe_delay", f"RTL vs delay model (N {n_del}, RAM_MIN {ram_min})",
                  checked + held, bad)
    dut._log.info("VECTORS pipe_delay N=%d: %d enabled clocks checked, %d stalled clocks held, "
                  "%d mismatches", n_del, checked, held, bad)
    if not (checked > clocks // 4 and held > clocks // 8):
        msgs.append(f"too few clocks checked: {checked} enabled (more than {clocks // 4} "
                    f"expected), {held} stalled (more than {clocks // 8})")
    return msgs


def test_pipe_delay() -> None:
    """Build pipe_delay_tb (every configuration of CASES) once and run :func:`pipe_delay_random`."""
    here = Path(__file__).parent
    runner.run("pipe_delay_tb", "test_pipe_delay", here, parameters={"W": W},
               rtl_top="pipe_delay", extra_sources=[str(here / "pipe_delay_tb.sv")])
