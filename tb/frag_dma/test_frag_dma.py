# SPDX-License-Identifier: Apache-2.0
"""frag_dma (fragment records over an AXI4 read master -> dm_pipeline's fragment stream).

The records (rtl/top/pidm_pkg.sv: 64 bytes, 16 little-endian words) are random 32-bit words in
a cocotbext-axi memory (tb/common/axi_ram.FaultRead) with random latency and random pauses on
AR and R; the fragment stream has random ready back-pressure.  Checked per frame: the records
come out in memory order, each field equal to its bits of the record (f24 words [23:0], the
triangle id word 3 [TRI_W-1:0], the pixel id word 3 [8 +: PIX_W]), exactly ``count`` of them;
done_o once, busy_o falls, sent_o = count; every read inside the buffer (bursts never cross 4 KiB:
the memory model asserts it and the bound checker too); ARCACHE / ARPROT / ARBURST / ARSIZE as
parameterised.  Frames: counts 0, 1, around a burst and a 4 KiB page, bases just before a page
boundary, random ones.

Error cases: a range of the buffer answers SLVERR (err_o; the records delivered are a prefix of
the good records before the first bad one; the port drains: busy_o falls; the next frame exact);
abort_i at a random clock (a prefix; busy_o falls; the next frame exact).

The three (DATA_W, MAX_BURST, FIFO_RECS) of CASES are built once, side by side, in the wrapper
``frag_dma_tb`` (one instance each, own ports, reset and memory model, a shared clock) and run at
once in one simulation, each with its own random stream from the printed seed and its own
checks; a failure names the configuration.

Environment: SEED, FRAG_FRAMES (random frames, default 24).
"""
from __future__ import annotations

import logging
import os
import random
from pathlib import Path

from typing import Any, Callable, Coroutine

import cocotb
from cocotb.triggers import ClockCycles, FallingEdge
from cocotbext.axi import AxiReadBus

from tb.common import cases, report, runner
from tb.common.axi_ram import FaultRead, set_pauses

HERE = Path(__file__).resolve().parent
REC = 64
BASE = 0x2000_0000
#: (DATA_W, MAX_BURST, FIFO_RECS) of the instances g_case[0 ..] of frag_dma_tb (the wrapper's
#: table): the default; a narrow bus with short bursts and a small FIFO; a wide bus with long
#: bursts.
CASES = [(64, 4, 8), (32, 2, 4), (128, 8, 8)]
#: ARCACHE and ARPROT of every instance (not the defaults, so that the bus shows them).
ARCACHE, ARPROT = 0b0010, 0b010


class Tb:
    """One instance ``g_case[i]`` of frag_dma_tb (``dut``: its scope) with DATA_W ``data_w``, on
    the shared clock ``clk``, with its own memory model on its m_axi_* signals and its own random
    generator."""

    def __init__(self, dut, clk, rng: random.Random, data_w: int, name: str) -> None:
        self.dut = dut
        self.clk = clk
        self.rng = rng
        self.log = cases.logger(name)
        self.pix_w = 24                            # frag_dma's defaults
        self.tri_w = 4
        self.data_w = data_w
        self.ram = FaultRead(AxiReadBus.from_prefix(dut, "m_axi"), clk, reset=None,
                             rng=rng, size=1 << 32)
        self.ram.log.setLevel(logging.ERROR)

    async def reset(self) -> None:
        d = self.dut
        d.rst_ni.value = 0
        d.start_i.value = 0
        d.abort_i.value = 0
        d.base_i.value = 0
        d.count_i.value = 0
        d.frag_ready_i.value = 0
        await ClockCycles(self.clk, 4)
        await FallingEdge(self.clk)
        d.rst_ni.value = 1
        await FallingEdge(self.clk)

    def expect(self, words: list[int]) -> tuple[int, ...]:
        """The fragment-port values of one record (16 words)."""
        m24 = 0xFFFFFF
        tbn = sum((words[4 + i] & m24) << (24 * i) for i in range(9))
        view = sum((words[13 + i] & m24) << (24 * i) for i in range(3))
        return ((words[3] >> 8) & ((1 << self.pix_w) - 1), words[0] & m24, words[1] & m24,
                words[2] & m24, words[3] & ((1 << self.tri_w) - 1), tbn, view)

    def got(self) -> tuple[int, ...]:
        d = self.dut
        return tuple(int(s.value) for s in (d.frag_id_o, d.frag_u0_o, d.frag_v0_o, d.frag_pl0_o,
                                            d.frag_tri_o, d.frag_tbn_o, d.frag_view_o))

    def place(self, base: int, n: int) -> list[list[int]]:
        """Random records at ``base``; the memory's allowed region is exactly the buffer."""
        recs = [[self.rng.getrandbits(32) for _ in range(16)] for _ in range(n)]
        buf = b"".join(w.to_bytes(4, "little") for r in recs for w in r)
        self.ram.write(base, buf)
        self.ram.regions = [(base, base + len(buf))]
        return recs

    async def frame(self, base: int, recs: list[list[int]], ready_p: float,
                    abort_at: int | None = None, max_clocks: int = 200_000
                    ) -> tuple[list[tuple[int, ...]], int, int, int]:
        """Run one frame; (fragments out, clocks, done pulses, err_o at the end)."""
        d = self.dut
        d.base_i.value = base
        d.count_i.value = len(recs)
        d.start_i.value = 1
        await FallingEdge(self.clk)
        d.start_i.value = 0
        d.base_i.value = self.rng.getrandbits(32)       # only sampled at start_i
        d.count_i.value = self.rng.getrandbits(8)
        out: list[tuple[int, ...]] = []
        dones = 0
        cyc = 0
        cache, prot = ARCACHE, ARPROT
        while True:
            if not int(d.busy_o.value):
                break
            if cyc >= max_clocks:
                st = {k: int(getattr(d.u_dut, k).value) for k in (
                    "m_axi_arvalid", "inflight_q", "f_count", "asm_cnt_q", "left_q",
                    "out_valid_q", "stop_q", "err_q")}
                raise AssertionError(f"frag_dma hangs: {len(out)} of {len(recs)} from {base:#x} "
                                     f"after {cyc} clocks; {st}")
            if abort_at is not None and cyc == abort_at:
                d.abort_i.value = 1
            rdy = int(self.rng.random() < ready_p)
            d.frag_ready_i.value = rdy
            if rdy and int(d.frag_valid_o.value):
                out.append(self.got())
            if int(d.m_axi_arvalid.value):
                assert int(d.m_axi_arcache.value) == cache and int(d.m_axi_arprot.value) == prot
                assert int(d.m_axi_arburst.value) == 1
                assert 1 << int(d.m_axi_arsize.value) == self.data_w // 8
            dones += int(d.done_o.value)
            await FallingEdge(self.clk)
            cyc += 1
        d.abort_i.value = 0
        d.frag_ready_i.value = 0
        err = int(d.err_o.value)
        # Quiet afterwards: nothing offered, nothing requested.
        for _ in range(20):
            assert not int(d.frag_valid_o.value) and not int(d.m_axi_arvalid.value)
            await FallingEdge(self.clk)
        return out, cyc, dones, err


def counts(rng: random.Random, n: int) -> list[tuple[int, int]]:
    """(base, count) of the frames: directed edges, then random ones."""
    page = 4096
    fr = [(BASE, 0), (BASE, 1), (BASE, 4), (BASE, 5), (BASE + page - REC, 3),
          (BASE + page - 3 * REC, 70), (BASE, 64), (BASE, 65), (BASE + 7 * REC, 200)]
    for _ in range(n):
        fr.append((BASE + rng.randrange(0, 1 << 16) * REC, rng.randrange(1, 160)))
    return fr


Check = Callable[[Tb], Coroutine[Any, Any, None]]


async def each_case(dut, check: Check) -> None:
    """Start the clock, then reset every instance of frag_dma_tb and run ``check`` on it (all at
    once, each with its own memory model and random generator: :func:`cases.randoms`); fail
    naming every configuration whose check failed."""
    def name(case: tuple[int, int, int]) -> str:
        return f"frag_dma DATA_W {case[0]}, MAX_BURST {case[1]}, FIFO_RECS {case[2]}"

    async def one(inst, case: tuple[int, int, int], rng: random.Random) -> None:
        mism = cases.param_mismatches(dut, {"ARCACHE": ARCACHE, "ARPROT": ARPROT})
        assert not mism, "\n".join(mism)
        tb = Tb(inst, dut.clk_i, rng, case[0], name(case))
        await tb.reset()
        await check(tb)

    await cases.run_each(dut, CASES, name, one,
                         lambda c: {"DATA_W": c[0], "MAX_BURST": c[1], "FIFO_RECS": c[2]},
                         cases.randoms)


@cocotb.test()
async def frag_dma_frames(dut):
    """Random frames (:func:`frames`) on every instance."""
    await each_case(dut, frames)


async def frames(tb: Tb) -> None:
    """Random frames under latency and back-pressure, bit for bit."""
    rng = tb.rng
    dut = tb.dut
    nframes = int(os.environ.get("FRAG_FRAMES", "24"))
    total = bad = clocks = 0
    for k, (base, n) in enumerate(counts(rng, nframes)):
        p = rng.choice((0.0, 0.2, 0.5))
        set_pauses(tb.ram, rng, p)
        tb.ram.lat, tb.ram.lat_p = (1, rng.choice((2, 10, 30))), rng.choice((0.0, 0.05, 0.3))
        recs = tb.place(base, n)
        ready_p = rng.choice((1.0, 0.7, 0.3))
        out, cyc, dones, err = await tb.frame(base, recs, ready_p)
        exp = [tb.expect(r) for r in recs]
        nbad = sum(a != b for a, b in zip(out, exp)) + abs(len(out) - len(exp))
        msg = (f"frame {k}: base {base:#x} count {n} pauses {p} ready {ready_p}: {len(out)} out, "
               f"{cyc} clocks, {nbad} bad, done {dones}, err {err}")
        tb.log.info(msg)
        assert nbad == 0, msg
        assert dones == 1 and err == 0, msg
        assert int(dut.sent_o.value) == n, msg
        assert not tb.ram.outside, f"{msg}: reads outside the buffer at {tb.ram.outside[:4]}"
        total += n
        bad += nbad
        clocks += cyc
    report.record("frag_dma", "fragment records through AXI vs memory words", total, bad)
    tb.log.info(f"FRAG_DMA frames: {total} records in {clocks} clocks, {bad} mismatches")


@cocotb.test()
async def frag_dma_errors(dut):
    """SLVERR ranges and abort (:func:`errors`) on every instance."""
    await each_case(dut, errors)


async def errors(tb: Tb) -> None:
    """SLVERR ranges and abort: a clean prefix, the port drained, the next frame exact."""
    rng = tb.rng
    dut = tb.dut
    checked = 0
    for k in range(12):
        set_pauses(tb.ram, rng, rng.choice((0.0, 0.3)))
        tb.ram.lat, tb.ram.lat_p = (1, 20), 0.1
        n = rng.randrange(8, 120)
        base = BASE + rng.randrange(0, 1 << 12) * REC
        recs = tb.place(base, n)
        exp = [tb.expect(r) for r in recs]
        if k % 2 == 0:
            first = rng.randrange(0, n)
            lo = base + first * REC + rng.randrange(0, REC)
            tb.ram.err_ranges = [(lo, lo + rng.randrange(1, 3 * REC))]
            out, cyc, dones, err = await tb.frame(base, recs, rng.choice((1.0, 0.5)))
            tb.ram.err_ranges = []
            what = f"SLVERR from record {first}"
            assert err == 1, f"{what}: err_o not set"
            assert len(out) <= first, f"{what}: {len(out)} records delivered"
        else:
            stop = rng.randrange(0, 40 * n)
            out, cyc, dones, err = await tb.frame(base, recs, rng.choice((1.0, 0.5)),
                                                  abort_at=stop)
            what = f"abort at clock {stop}"
            assert err == 0, f"{what}: err_o set"
        assert dones == 1, f"{what}: {dones} done pulses"
        assert out == exp[:len(out)], f"{what}: the records delivered are not a prefix"
        assert int(dut.sent_o.value) == len(out)
        tb.log.info("%s: count %d, %d delivered, %d clocks", what, n, len(out), cyc)
        # The next frame exact.
        base2 = BASE + 0x10_0000 + rng.randrange(0, 1 << 10) * REC
        n2 = rng.randrange(1, 50)
        recs2 = tb.place(base2, n2)
        out2, _, dones2, err2 = await tb.frame(base2, recs2, 0.8)
        assert out2 == [tb.expect(r) for r in recs2] and dones2 == 1 and err2 == 0, \
            f"{what}: the next frame differs"
        assert not tb.ram.outside
        checked += len(out) + n2
    report.record("frag_dma", "records after SLVERR / abort (prefix) and the next frame",
                  checked, 0)
    tb.log.info(f"FRAG_DMA errors: 6 SLVERR frames, 6 aborts, each followed by an exact frame "
                f"({checked} records checked), SLVERR words {tb.ram.err_words}")



def test_frag_dma() -> None:
    """Build frag_dma_tb (every configuration of CASES) once and run the cocotb tests."""
    runner.run("frag_dma_tb", "test_frag_dma", HERE, rtl_top="frag_dma",
               extra_sources=[str(HERE / "frag_dma_tb.sv")])
