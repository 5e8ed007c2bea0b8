# SPDX-License-Identifier: Apache-2.0
"""tri_table against a clock-accurate Python model of its two memories.

Every word is written first; then every clock a random write (any address, also triangle ids
at or beyond TRIS, which must be ignored) and a random read with a random read enable (also ids
beyond TRIS, which read +0), a fifth of the reads at the address being written on the same edge
(the old word is read).  After every edge both read registers must equal the model's.  Runs
with TRIS = 16 (the default), 5 (ids 5..7 out of range) and 1.
"""
from __future__ import annotations

import os
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from model import f24_vectors as vec
from tb.common import fp_unit, report, runner


@cocotb.test()
async def tri_table_random(dut):
    rng = np.random.default_rng(fp_unit.seed())
    tri_w = len(dut.raddr_i)
    tris = int(os.environ["TRIS"])  # the build's parameter (set by the pytest function)
    ids = 1 << tri_w
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    mem = np.zeros((tris, 2), dtype=np.int64)
    dut.we_i.value = 0
    dut.re_i.value = 0
    await FallingEdge(dut.clk_i)
    for a in rng.permutation(2 * tris):  # every word, in random order
        mem[a >> 1, a & 1] = int(vec.rand_bits(rng, 1)[0])
        dut.we_i.value = 1
        dut.waddr_i.value = int(a)
        dut.wdata_i.value = int(mem[a >> 1, a & 1])
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
    n = fp_unit.vectors(fp_unit.VECTORS_COMPOSITE)
    we = (rng.random(n) < 0.5).tolist()
    re = (rng.random(n) < 0.7).tolist()
    waddr = rng.integers(0, 2 * ids, n).tolist()
    wdata = vec.rand_bits(rng, n).tolist()
    raddr = rng.integers(0, ids, n)
    same = rng.random(n) < 0.2
    raddr = np.where(same, np.array(waddr) >> 1, raddr).tolist()
    out = [0, 0]
    # The read registers hold X until the first read: read once before checking.
    dut.we_i.value = 0
    dut.re_i.value = 1
    dut.raddr_i.value = 0
    await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    out = [int(mem[0, 0]), int(mem[0, 1])]
    bad = reads = 0
    msgs = []
    for k in range(n):
        dut.we_i.value = int(we[k])
        dut.waddr_i.value = waddr[k]
        dut.wdata_i.value = wdata[k]
        dut.re_i.value = int(re[k])
        dut.raddr_i.value = raddr[k]
        await RisingEdge(dut.clk_i)
        if re[k]:  # read first: the old word
            reads += 1
            r = raddr[k]
            out = [int(mem[r, 0]), int(mem[r, 1])] if r < tris else [0, 0]
        if we[k] and (waddr[k] >> 1) < tris:
            mem[waddr[k] >> 1, waddr[k] & 1] = wdata[k]
        await FallingEdge(dut.clk_i)
        got = [int(dut.rdata_colour_o.value), int(dut.rdata_normal_o.value)]
        if got != out:
            bad += 1
            if len(msgs) < 10:
                msgs.append(f"clock {k}: we={we[k]} waddr={waddr[k]} re={re[k]} "
                            f"raddr={raddr[k]}: got {got} expected {out}")
    report.record(dut._name, "RTL vs memory model", n, bad)
    dut._log.info("VECTORS tri_table TRIS=%d: %d clocks (%d reads), %d mismatches", tris, n,
                  reads, bad)
    if msgs:
        raise AssertionError("\n".join(msgs))


@pytest.mark.parametrize("tris", [16, 5, 1])
def test_tri_table(tris: int):
    runner.run("tri_table", "test_tri_table", Path(__file__).parent, parameters={"TRIS": tris},
               extra_env={"TRIS": str(tris)})
