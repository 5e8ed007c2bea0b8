# SPDX-License-Identifier: Apache-2.0
"""circ_queue (rtl/common: the caches' AR queue, free list of MSHRs, request FIFO and output
buffer) against a deque, clock by clock.

Every clock random pushes on the NPUSH lanes (within the room left after this clock's pops),
early writes on lanes that do not push (only into entries that are free), and a random number
of pops (at most the count), with the probabilities drifting in bursts so that the queue runs
empty, full and in between.  Before every edge count_o and rdata_o[k] (k < min(NPOP, count),
with ASYNC_RD) must equal the model's; after every edge peek_o (with PEEK > 0) must be entry
PEEK of the queue as it is then, while the queue holds more than PEEK entries.  With INIT_SEQ
the queue starts full of 0 .. DEPTH - 1.  The nine configurations of CASES are built once, side
by side, in the wrapper ``circ_queue_tb`` (one instance each, own ports and reset, a shared
clock) and run at once in one simulation, each with its own random stream from the printed seed
and its own checks; a failure names the configuration.
"""
from __future__ import annotations

from collections import deque
from pathlib import Path

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from tb.common import cases, clock_reset, fp_unit, report, runner

#: (WIDTH, DEPTH, NPUSH, NPOP, INIT_SEQ, ASYNC_RD, PEEK) of the instances g_case[0 ..] of
#: circ_queue_tb (the wrapper's table): the AR queues (tex_cache: 4 lanes, height_cache: 1), the
#: free list of MSHRs, the request FIFO, the output buffer, and odd depths.
CASES = [(4, 16, 4, 1, 0, 1, 0), (2, 4, 1, 1, 0, 1, 0), (4, 16, 1, 4, 1, 1, 0),
         (37, 8, 1, 1, 0, 0, 2), (13, 4, 1, 1, 0, 1, 0), (5, 5, 3, 2, 0, 1, 0),
         (3, 1, 1, 1, 0, 1, 0), (6, 7, 1, 3, 1, 1, 1), (9, 3, 1, 1, 0, 1, 2)]
#: The names of CASES's columns: circ_queue's parameters.
PARAMS = ("WIDTH", "DEPTH", "NPUSH", "NPOP", "INIT_SEQ", "ASYNC_RD", "PEEK")


def _lanes(sig, n: int, width: int) -> list[int]:
    v = int(sig.value)
    return [(v >> (k * width)) & ((1 << width) - 1) for k in range(n)]


@cocotb.test()
async def circ_queue_random(dut):
    """Every instance of circ_queue_tb at once (:func:`check_queue` each)."""
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    rngs = cases.streams(len(CASES))
    await cases.check_all([("circ_queue " + ", ".join(f"{k} {v}" for k, v in zip(PARAMS, case)),
                            check_queue(dut, i, case, rngs[i]))
                           for i, case in enumerate(CASES)])


async def check_queue(dut, i: int, case: tuple[int, ...], rng: np.random.Generator) -> list[str]:
    """Drive and check ``dut.g_case[i]`` (circ_queue with the parameters ``case``, a row of
    CASES) as the module docstring says; return the failure messages (none: it passed)."""
    inst = dut.g_case[i]
    if mism := cases.param_mismatches(inst, dict(zip(PARAMS, case))):
        return mism
    width, depth, npush, npop, init_seq, async_rd, peek = case
    await clock_reset.reset(inst, ["push_i", "wr_i", "wdata_i", "pop_n_i"], clk=dut.clk_i)
    q: deque[int] = deque(range(depth) if init_seq else [])
    n = fp_unit.vectors()
    p_push = rng.uniform(0.0, 1.0, n // 32 + 1).repeat(32)[:n]
    p_pop = rng.uniform(0.0, 1.0, n // 32 + 1).repeat(32)[:n]
    bad = fulls = empties = peeks = 0
    msgs: list[str] = []

    def check(what: str, got: int, exp: int, k: int) -> None:
        nonlocal bad
        if got != exp:
            bad += 1
            if len(msgs) < 10:
                msgs.append(f"clock {k}: {what} {got:#x}, expected {exp:#x}")

    for k in range(n):
        await Timer(1, unit="ns")
        check("count_o", int(inst.count_o.value), len(q), k)
        if async_rd:
            rd = _lanes(inst.rdata_o, npop, width)
            for j in range(min(npop, len(q))):
                check(f"rdata_o[{j}]", rd[j], q[j], k)
        fulls += len(q) == depth
        empties += not q
        pops = int(min(rng.binomial(npop, p_pop[k]), len(q)))
        room = depth - len(q) + pops
        push, wr, data = [0] * npush, [0] * npush, [0] * npush
        m = 0  # pushes on the lanes below
        pushed: list[int] = []
        for lane in range(npush):
            data[lane] = int(rng.integers(0, 1 << width))
            if m < room and rng.random() < p_push[k]:
                push[lane] = wr[lane] = 1
                pushed.append(data[lane])
                m += 1
            elif m < depth - len(q) and rng.random() < 0.3:
                wr[lane] = 1  # an early write into a free entry: must not show in the queue
        inst.push_i.value = sum(b << j for j, b in enumerate(push))
        inst.wr_i.value = sum(b << j for j, b in enumerate(wr))
        inst.wdata_i.value = sum(d << (j * width) for j, d in enumerate(data))
        inst.pop_n_i.value = pops
        await RisingEdge(dut.clk_i)
        for _ in range(pops):
            q.popleft()
        q.extend(pushed)
        await FallingEdge(dut.clk_i)
        if peek and len(q) > peek:
            peeks += 1
            check("peek_o", int(inst.peek_o.value), q[peek], k)
    report.record("circ_queue", f"RTL vs deque (W {width}, DEPTH {depth}, NPUSH {npush}, "
                                f"NPOP {npop}, INIT_SEQ {init_seq}, ASYNC_RD {async_rd}, "
                                f"PEEK {peek})", n, bad)
    dut._log.info("VECTORS circ_queue W=%d DEPTH=%d NPUSH=%d NPOP=%d: %d clocks (%d full, "
                  "%d empty, %d peeks), %d mismatches", width, depth, npush, npop, n, fulls,
                  empties, peeks, bad)
    if fulls == 0 or empties == 0 or (peek and peeks == 0):
        msgs.append(f"the stimulus never reached full ({fulls}), empty ({empties}) or a peek "
                    f"({peeks})")
    return msgs


def test_circ_queue() -> None:
    """Build circ_queue_tb (every configuration of CASES) once and run :func:`circ_queue_random`
    (20,000 clocks per instance)."""
    here = Path(__file__).parent
    runner.run("circ_queue_tb", "test_circ_queue", here, rtl_top="circ_queue",
               extra_sources=[str(here / "circ_queue_tb.sv")], extra_env={"VECTORS": "20000"})
