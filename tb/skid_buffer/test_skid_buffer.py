# SPDX-License-Identifier: Apache-2.0
"""skid_buffer (the register slice in front of the texture cache) against a model, both modes.

Both modes (REG_OUT 0 and 1) are built once, side by side, in the wrapper ``skid_buffer_tb``
(one instance each, own ports and reset, a shared clock) and run at once in one simulation, each
with its own random stream from the printed seed, its own model and checks; a failure names the
mode.  What each instance goes through:

The producer is a queue, as the request FIFOs in front of the slice in dm_pipeline: item k
arrives at a random clock (bursts and gaps) and the producer offers the queue's head until the
slice takes it.  The consumer's ready_i is random.  Every clock the test compares valid_o, data_o
and ready_o with a clock-accurate model of the slice (ready_o a register: it must not follow
ready_i), and each item given on with the next number in order.  With REG_OUT 0 it also compares
the offers with the same queue and the same ready_i without the slice: the consumer must see
the same offers in the same clocks.  Phases: random; full rate (always valid, always ready: one
item a clock); a stalled consumer (the slice fills and holds, nothing lost); a reset while the
slice is full.
The bound assertions (rtl/common/skid_buffer_assert.sv) are on.
"""
from __future__ import annotations

from collections import deque
from pathlib import Path

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import cases, clock_reset, fp_unit, report, runner

W = 16
#: REG_OUT of the instances g_case[0], g_case[1] of skid_buffer_tb (the wrapper's table).
REG_OUTS = [0, 1]


class SliceModel:
    """skid_buffer clock by clock: the skid register, and with REG_OUT the output register."""

    def __init__(self, reg_out: bool) -> None:
        self.reg_out = reg_out
        self.reset()

    def reset(self) -> None:
        self.full = False
        self.skid = 0
        self.out_v = False
        self.out = 0

    def outputs(self, valid_i: bool, data_i: int) -> tuple[int, int | None, int]:
        """(valid_o, data_o or None, ready_o) in the current clock."""
        if self.reg_out:
            return int(self.out_v), (self.out if self.out_v else None), int(not self.full)
        if self.full:
            return 1, self.skid, 0
        return int(valid_i), (data_i if valid_i else None), 1

    def clock(self, valid_i: bool, data_i: int, ready_i: bool) -> None:
        if self.reg_out:
            if not self.out_v or ready_i:
                self.out_v = self.full or valid_i
                self.out = self.skid if self.full else data_i
                self.full = False
            elif valid_i and not self.full:
                self.full, self.skid = True, data_i
        elif self.full:
            self.full = not ready_i
        elif valid_i and not ready_i:
            self.full, self.skid = True, data_i


@cocotb.test()
async def skid_buffer_random(dut):
    """Both instances of skid_buffer_tb at once (:func:`check_slice` each)."""
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    rngs = cases.streams(len(REG_OUTS))
    await cases.check_all([(f"skid_buffer REG_OUT {r}", check_slice(dut, i, r, rngs[i]))
                           for i, r in enumerate(REG_OUTS)])


async def check_slice(dut, i: int, reg_out: int, rng: np.random.Generator) -> list[str]:
    """Drive and check ``dut.g_case[i]`` (skid_buffer with REG_OUT ``reg_out``) as the module
    docstring says; return the failure messages (none: it passed)."""
    inst = dut.g_case[i]
    if mism := cases.param_mismatches(inst, {"REG_OUT": reg_out}):
        return mism
    await clock_reset.reset(inst, ["valid_i", "ready_i", "data_i"], cycles=3, clk=dut.clk_i)
    n = fp_unit.vectors(fp_unit.VECTORS_COMPOSITE)
    # phase per clock: 0 random, 1 full rate, 2 consumer stalled, 3 reset (one clock)
    phase = np.zeros(n, dtype=np.int64)
    phase[n // 2: n // 2 + n // 8] = 1
    phase[n // 2 + n // 8: n // 2 + n // 8 + 64] = 2
    phase[n // 2 + n // 8 + 64] = 3
    p_arr = rng.uniform(0.1, 1.0, n // 64 + 1).repeat(64)[:n]    # bursts of varying density
    p_rdy = rng.uniform(0.1, 1.0, n // 64 + 1).repeat(64)[:n]
    arrive = np.where(phase == 0, rng.random(n) < p_arr, phase != 3)
    ready = np.where(phase == 0, rng.random(n) < p_rdy, phase == 1)
    src: deque[int] = deque()   # the producer's queue (in front of the slice)
    ref: deque[int] = deque()   # the same queue without the slice
    seq_in = seq_out = 0
    given_full = full_clocks = 0
    bad = 0
    msgs: list[str] = []

    def fail(text: str) -> None:
        nonlocal bad
        bad += 1
        if len(msgs) < 10:
            msgs.append(text)

    model = SliceModel(bool(reg_out))
    for k in range(n):
        if phase[k] == 3:       # reset: the slice and both queues are emptied
            inst.rst_ni.value = 0
            inst.valid_i.value = 0
            inst.ready_i.value = 0
            src.clear()
            ref.clear()
            model.reset()
            await RisingEdge(dut.clk_i)
            await FallingEdge(dut.clk_i)
            inst.rst_ni.value = 1
            seq_out = seq_in
            continue
        inst.valid_i.value = int(bool(src))
        inst.data_i.value = src[0] if src else 0
        inst.ready_i.value = int(ready[k])
        await cocotb.triggers.Timer(1, unit="ns")
        valid_o = int(inst.valid_o.value)
        got = (valid_o, int(inst.data_o.value) if valid_o else None, int(inst.ready_o.value))
        exp = model.outputs(bool(src), src[0] if src else 0)
        if got != exp:
            fail(f"clock {k} (phase {phase[k]}): (valid_o, data_o, ready_o) = {got}, "
                 f"model {exp}")
        if not reg_out and got[:2] != (int(bool(ref)), ref[0] if ref else None):
            fail(f"clock {k} (phase {phase[k]}): (valid_o, data_o) = {got[:2]}, without the "
                 f"slice {(int(bool(ref)), ref[0] if ref else None)}")
        # the edge: the producer's handshake, the consumer's, the reference's
        took_in = bool(src) and bool(got[2])
        gave = bool(got[0]) and bool(ready[k])
        if gave:
            if got[1] != seq_out & 0xFFFF:
                fail(f"clock {k}: item {got[1]} given on, expected {seq_out & 0xFFFF}")
            seq_out += 1
            given_full += int(phase[k] == 1)
        model.clock(bool(src), src[0] if src else 0, bool(ready[k]))
        if took_in:
            src.popleft()
        if ref and ready[k]:
            ref.popleft()
        if arrive[k]:
            src.append(seq_in & 0xFFFF)
            ref.append(seq_in & 0xFFFF)
            seq_in += 1
        full_clocks += int(model.full)
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
    # drain
    inst.ready_i.value = 1
    for _ in range(n // 4):
        if not src and not model.full and not model.out_v:
            break
        inst.valid_i.value = int(bool(src))
        inst.data_i.value = src[0] if src else 0
        await cocotb.triggers.Timer(1, unit="ns")
        if int(inst.valid_o.value):
            if int(inst.data_o.value) != seq_out & 0xFFFF:
                fail(f"drain: item {int(inst.data_o.value)}, expected {seq_out & 0xFFFF}")
            seq_out += 1
        took_in = bool(src) and bool(int(inst.ready_o.value))
        model.clock(bool(src), src[0] if src else 0, True)
        if took_in:
            src.popleft()
        await RisingEdge(dut.clk_i)
        await FallingEdge(dut.clk_i)
    inst.valid_i.value = 0
    await cocotb.triggers.Timer(1, unit="ns")
    if int(inst.valid_o.value) or not int(inst.ready_o.value):
        fail("not empty after draining")
    if seq_out != seq_in:
        fail(f"{seq_in} items in, {seq_out} out")
    n_full = int(np.count_nonzero(phase == 1))
    if given_full < n_full - 2:
        fail(f"full rate: {given_full} items in {n_full} clocks")
    if full_clocks == 0:
        fail("the slice never filled")
    report.record("skid_buffer", f"RTL vs the slice's model (REG_OUT {reg_out})", n, bad)
    dut._log.info("VECTORS skid_buffer REG_OUT=%d: %d clocks, %d items, %d clocks with the skid "
                  "register full, %d items in the %d full-rate clocks, %d mismatches",
                  reg_out, n, seq_in, full_clocks, given_full, n_full, bad)
    return msgs


def test_skid_buffer() -> None:
    """Build skid_buffer_tb (both modes) once and run :func:`skid_buffer_random`."""
    runner.run("skid_buffer_tb", "test_skid_buffer", Path(__file__).parent,
               parameters={"W": W}, rtl_top="skid_buffer",
               extra_sources=[str(Path(__file__).parent / "skid_buffer_tb.sv")])
