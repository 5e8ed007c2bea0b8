# SPDX-License-Identifier: Apache-2.0
"""axi_read_slice (the AXI4 read port's register slices of the FPGA top) between cocotbext-axi's
read master and its RAM model.

Random bursts (1 to 16 beats of 8 bytes, random addresses and ids, from a printed seed)
are read through the slice, several in flight, and every burst's data is compared with the
memory's.  Phases: no pauses (a lone burst of 16 beats must reach the master in 16 clocks in a
row: a beat a clock through both slices); random pauses on the RAM's AR and R channels and
on the master's R channel (back-pressure both ways).  The bound checks of both skid_buffers are
on.
"""
from __future__ import annotations

import logging
import os
import random
from pathlib import Path

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge
from cocotbext.axi import AxiMasterRead, AxiRamRead, AxiReadBus

from tb.common import clock_reset, report, runner

ID_W, ADDR_W, DATA_W = 4, 32, 64
MEM = 1 << 16


def pauses(rng: random.Random, p: float):
    while True:
        yield rng.random() < p


async def read_all(master: AxiMasterRead, rng: random.Random, image: bytes, n: int,
                   log) -> int:
    """n random bursts, up to 8 in flight; returns the number of bursts with wrong data."""
    bad = 0
    pending = []
    for k in range(n):
        beats = rng.randint(1, 16)
        addr = rng.randrange(0, MEM - 16 * 8, 8)
        ev = master.init_read(addr, beats * 8, arid=rng.randrange(1 << ID_W))
        pending.append((k, addr, beats, ev))
        if len(pending) >= 8 or k == n - 1:
            for kk, a, b, e in pending:
                await e.wait()
                got = bytes(e.data.data)
                if got != image[a:a + 8 * b]:
                    bad += 1
                    if bad <= 10:
                        log.error("burst %d at 0x%x (%d beats): data differs", kk, a, b)
            pending = []
    return bad


@cocotb.test()
async def axi_read_slice_bursts(dut):
    seed = int(os.environ.get("SEED", "1"))
    rng = random.Random(seed)
    dut._log.info("seed %d", seed)
    ram = AxiRamRead(AxiReadBus.from_prefix(dut, "m"), dut.clk_i, dut.rst_ni,
                     reset_active_level=False, size=MEM)
    master = AxiMasterRead(AxiReadBus.from_prefix(dut, "s"), dut.clk_i, dut.rst_ni,
                           reset_active_level=False)
    ram.log.setLevel(logging.ERROR)
    master.log.setLevel(logging.ERROR)
    image = bytes(rng.randrange(256) for _ in range(MEM))
    ram.write(0, image)
    await clock_reset.start_and_reset(dut, [], cycles=4)
    await ClockCycles(dut.clk_i, 2)

    # R handshakes on the master's side, by clock
    beats_at: list[int] = []

    async def watch() -> None:
        clk = 0
        while True:
            await RisingEdge(dut.clk_i)
            clk += 1
            if int(dut.s_rvalid.value) and int(dut.s_rready.value):
                beats_at.append(clk)

    cocotb.start_soon(watch())
    # full rate: one 16-beat burst alone, no pauses: its beats in 16 clocks in a row
    ev = master.init_read(0x100, 16 * 8, arid=3)
    await ev.wait()
    bad = int(bytes(ev.data.data) != image[0x100:0x100 + 128])
    span = beats_at[-1] - beats_at[0] + 1 if beats_at else 0
    assert len(beats_at) == 16 and span == 16, \
        f"a lone 16-beat burst: {len(beats_at)} beats over {span} clocks (want 16 in 16)"
    n_full = 200
    bad += await read_all(master, rng, image, n_full, dut._log)

    # back-pressure both ways: the RAM pauses AR and R, the master pauses R
    ram.ar_channel.set_pause_generator(pauses(random.Random(rng.randrange(1 << 30)), 0.3))
    ram.r_channel.set_pause_generator(pauses(random.Random(rng.randrange(1 << 30)), 0.3))
    master.r_channel.set_pause_generator(pauses(random.Random(rng.randrange(1 << 30)), 0.4))
    n_pause = 300
    bad += await read_all(master, rng, image, n_pause, dut._log)
    await RisingEdge(dut.clk_i)

    report.record("axi_read_slice", "bursts read through the slices vs the memory",
                  1 + n_full + n_pause, bad)
    dut._log.info("VECTORS axi_read_slice: %d bursts, %d with wrong data; a lone 16-beat burst's "
                  "beats in %d clocks", 1 + n_full + n_pause, bad, span)
    assert bad == 0, f"{bad} bursts with wrong data"


def test_axi_read_slice() -> None:
    runner.run("axi_read_slice", "test_axi_read_slice", Path(__file__).parent,
               parameters={"ID_W": ID_W, "ADDR_W": ADDR_W, "DATA_W": DATA_W})
