# SPDX-License-Identifier: Apache-2.0
"""pyr_build: the hardware max-mipmap builder against model.heightmap, bit for bit.

The memory is cocotbext-axi's AxiRamRead / AxiRamWrite on one store (reset with the builder),
with random pauses on every channel (ar, r, aw, w, b) unless a test measures clocks.  Level 0 is
placed at the source base with its padding (columns >= W, rows >= H) full of random bytes (the
builder must take it as zero); levels 1..n start as random bytes.  After a build every byte of
levels 1..n must equal Pyramid.memory_image(), and every other byte (level 0, the gaps between
levels, guard bands around the image) must be unchanged.

Tests: full rebuilds of 1x1, 1xN, Nx1, odd and non-square sizes, 256x256, unorm8 and unorm16;
dirty-rectangle rebuilds (the old pyramid in memory, level 0 changed inside a random rectangle)
against the model's pyramid of the new map; AXI read and write errors (reported in err_code_o,
the build ends, the next build is exact); resets in the middle of builds; configuration errors;
clock counts: a full rebuild of 256x256 unorm8 within 1.25x the bus bound (model.pyramid_bus) and a
32x32 dirty rectangle on 1024x1024 under 5% of the full rebuild's bound (measured, printed,
asserted).  ``test_pyr_build_big`` (TB_LONG=1 or PYR_BIG=1) also builds 1024x1024 in full and
holds the dirty rebuild to 5% of that build's measured clocks.

Environment: SEED, WAVES=1, PYR_CFG (set by the pytest functions), PYR_BIG=1 (the big test).
"""
from __future__ import annotations

import json
import os
import random
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge
from cocotbext.axi import AxiBus, AxiRamRead, AxiRamWrite

from model import heightmap, pyramid_bus
from tb.common import report, runner

PYR_BASE = 0x4000_0000
#: The pyramid's base is PYR_BASE plus one of these per build (64-byte aligned: rows and bursts
#: then meet 4 KiB boundaries at other places).
PYR_SHIFTS = (0, 0x40, 0xFC0)
SRC_BASE = 0x2000_0040      # a separate level 0 (64-byte aligned, not 4 KiB aligned)
GUARD = 256                 # bytes checked untouched before and after the image

CONFIGS = {
    "default": {"AXI_DATA_W": 64, "MAX_LG": 10, "BURST": 16},
    "bus32": {"AXI_DATA_W": 32, "MAX_LG": 8, "BURST": 4},
    "bus128": {"AXI_DATA_W": 128, "MAX_LG": 9, "BURST": 8},
}


def config() -> dict[str, int]:
    return json.loads(os.environ.get("PYR_CFG", json.dumps(CONFIGS["default"])))


def seed() -> int:
    s = int(os.environ.get("SEED", random.randrange(1 << 31)))
    cocotb.log.info("SEED=%d", s)
    return s


def pauses(rng: random.Random, p: float):
    while True:
        yield rng.random() < p


def overlaps(ranges: list[tuple[int, int]], lo: int, hi: int) -> bool:
    return any(a < hi and lo < b for a, b in ranges)


class ErrRamRead(AxiRamRead):
    """AxiRamRead answering SLVERR for beats touching ``err_ranges`` ([lo, hi) byte ranges)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.err_ranges: list[tuple[int, int]] = []
        self.beats = 0

    async def _read(self, address, length):
        self.beats += 1
        if overlaps(self.err_ranges, address, address + length):
            raise IOError("injected SLVERR")
        return await super()._read(address, length)


class ErrRamWrite(AxiRamWrite):
    """AxiRamWrite answering SLVERR for bursts with a beat touching ``err_ranges``."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.err_ranges: list[tuple[int, int]] = []
        self.beats = 0

    async def _write(self, address, data):
        self.beats += 1
        if overlaps(self.err_ranges, address, address + len(data)):
            raise IOError("injected SLVERR")
        return await super()._write(address, data)


class Harness:
    def __init__(self, dut, rng: random.Random):
        self.dut, self.rng, self.cfg = dut, rng, config()
        self.bus_bytes = self.cfg["AXI_DATA_W"] // 8
        self.max_lg = self.cfg["MAX_LG"]
        cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
        dut.rst_ni.value = 0
        dut.start_i.value = 0
        bus = AxiBus.from_prefix(dut, "m_axi")
        self.wr = ErrRamWrite(bus.write, dut.clk_i, dut.rst_ni, reset_active_level=False,
                              size=1 << 32)
        self.rd = ErrRamRead(bus.read, dut.clk_i, dut.rst_ni, reset_active_level=False,
                             mem=self.wr.mem)
        self.mem = self.wr
        self.checked = 0
        self.bad = 0
        self.pyr_base = PYR_BASE

    def set_pauses(self, p: float) -> None:
        for ch in (self.rd.ar_channel, self.rd.r_channel, self.wr.aw_channel, self.wr.w_channel,
                   self.wr.b_channel):
            if p > 0:
                ch.set_pause_generator(pauses(random.Random(self.rng.randrange(1 << 30)), p))
            else:
                ch.clear_pause_generator()
                ch.pause = False   # clearing the generator leaves the last pause standing

    async def reset(self, clocks: int = 3) -> None:
        self.dut.rst_ni.value = 0
        self.dut.start_i.value = 0
        for _ in range(clocks):
            await RisingEdge(self.dut.clk_i)
        self.dut.rst_ni.value = 1
        await RisingEdge(self.dut.clk_i)

    # ---- memory ----
    def place(self, pyr: heightmap.Pyramid, sep: bool, old: heightmap.Pyramid | None) -> int:
        """Choose the pyramid's base (self.pyr_base); level 0 of ``pyr`` at SRC_BASE (``sep``) or
        at the pyramid's base (as in Pyramid.memory_image), its padding random; the image's levels
        1..n random, or those of ``old`` (a dirty rebuild); guard bands random.  Returns level 0's
        address."""
        rng = self.rng
        self.pyr_base = PYR_BASE + rng.choice(PYR_SHIFTS)
        src_base = SRC_BASE if sep else self.pyr_base
        img = pyr.memory_image()
        bpt = pyr.bits // 8
        n_side = pyr.size
        lv0 = np.frombuffer(rng.randbytes(n_side * n_side * bpt), dtype="<u1" if bpt == 1 else "<u2")
        lv0 = lv0.reshape(n_side, n_side).copy()
        lv0[:pyr.height, :pyr.width] = pyr.codes
        self.mem.write(self.pyr_base - GUARD, rng.randbytes(len(img) + 2 * GUARD))
        if old is not None:
            oimg = old.memory_image()
            off1 = old.level_offsets()[1] if old.n else len(oimg)
            self.mem.write(self.pyr_base + off1, oimg[off1:])
        self.mem.write(src_base, lv0.astype(lv0.dtype.newbyteorder("<")).tobytes())
        return src_base

    def snapshot(self, pyr: heightmap.Pyramid) -> bytes:
        """The image's bytes with the guard bands, as they are now."""
        return self.mem.read(self.pyr_base - GUARD, len(pyr.memory_image()) + 2 * GUARD)

    def check(self, pyr: heightmap.Pyramid, before: bytes, what: str) -> int:
        """Levels 1..n against the model's image, everything else unchanged; returns mismatches."""
        img = pyr.memory_image()
        offs = pyr.level_offsets()
        bpt = pyr.bits // 8
        got = self.mem.read(self.pyr_base - GUARD, len(img) + 2 * GUARD)
        want = bytearray(before)
        for k in range(1, pyr.n + 1):
            lo, hi = offs[k], offs[k] + (pyr.size >> k) ** 2 * bpt
            want[GUARD + lo:GUARD + hi] = img[lo:hi]
        bad = sum(a != b for a, b in zip(got, want)) if got != bytes(want) else 0
        if bad:
            first = next(i for i in range(len(got)) if got[i] != want[i]) - GUARD
            lvl = max((k for k in range(pyr.n + 1) if offs[k] <= first), default=0)
            cocotb.log.error("%s: %d bytes differ, first at image offset %d (level %d)",
                             what, bad, first, lvl)
        self.checked += len(got)
        self.bad += bad
        return bad

    # ---- one build ----
    def drive(self, pyr: heightmap.Pyramid, src_base: int, rect=None,
              pyr_base: int | None = None) -> None:
        d = self.dut
        offs = pyr.level_offsets()
        packed = 0
        for k, o in enumerate(offs[:self.max_lg + 1]):
            packed |= o << (32 * k)
        d.cfg_src_base_i.value = src_base
        d.cfg_pyr_base_i.value = self.pyr_base if pyr_base is None else pyr_base
        d.cfg_level_off_i.value = packed
        d.cfg_width_i.value = pyr.width
        d.cfg_height_i.value = pyr.height
        d.cfg_bits16_i.value = int(pyr.bits == 16)
        x0, y0, x1, y1 = rect if rect is not None else (0, 0, pyr.width - 1, pyr.height - 1)
        d.dirty_x0_i.value, d.dirty_y0_i.value = x0, y0
        d.dirty_x1_i.value, d.dirty_y1_i.value = x1, y1

    async def build(self, pyr: heightmap.Pyramid, src_base: int, rect=None,
                    limit: int | None = None, **kw) -> tuple[int, int]:
        """Start a build and wait for done_o; returns (clocks, err_code).  Fails on a hang."""
        d = self.dut
        self.drive(pyr, src_base, rect, **kw)
        bound = pyramid_bus.full_rebuild(pyr.width, pyr.height, pyr.bits,
                                         self.cfg["AXI_DATA_W"]).clocks
        limit = limit or 40 * bound + 20000
        d.start_i.value = 1
        await RisingEdge(d.clk_i)
        d.start_i.value = 0
        clocks = 0
        while True:
            await RisingEdge(d.clk_i)
            clocks += 1
            if int(d.done_o.value):
                break
            assert int(d.busy_o.value) == 1, "busy_o fell before done_o"
            assert clocks < limit, f"no done_o after {limit} clocks (a hang)"
        err = int(d.err_code_o.value)
        assert int(d.err_o.value) == int(err != 0)
        await RisingEdge(d.clk_i)
        assert int(d.busy_o.value) == 0 and int(d.done_o.value) == 0
        return clocks, err

    async def full(self, pyr: heightmap.Pyramid, what: str, separate_src: bool | None = None
                   ) -> int:
        """A full rebuild from a random start; checks it; returns the clocks."""
        sep = self.rng.random() < 0.5 if separate_src is None else separate_src
        src = self.place(pyr, sep, None)
        before = self.snapshot(pyr)
        clocks, err = await self.build(pyr, src)
        assert err == 0, f"{what}: err_code {err}"
        assert self.check(pyr, before, what) == 0, what
        return clocks


def random_map(rng: random.Random, w: int, h: int, bits: int) -> heightmap.Pyramid:
    """Codes with plateaus and spikes (so that maxima come from every child position)."""
    m = (1 << bits) - 1
    g = np.random.default_rng(rng.randrange(1 << 30))
    a = g.integers(0, m + 1, size=(h, w), dtype=np.int64)
    if rng.random() < 0.5:
        a = a // rng.choice([1, 7, m])  # low maps, some all zero
    return heightmap.build(a.astype(np.uint16), bits)


def fits(cfg: dict[str, int], w: int, h: int) -> bool:
    return max(w, h) <= 1 << cfg["MAX_LG"]


def finish(h: Harness, what: str) -> None:
    report.record("pyr_build", what, h.checked, h.bad)
    assert h.bad == 0


@cocotb.test()
async def full_sizes(dut):
    """Full rebuilds of edge and odd sizes, unorm8 and unorm16, random AXI pauses."""
    rng = random.Random(seed())
    h = Harness(dut, rng)
    await h.reset()
    sizes = [(1, 1), (2, 1), (1, 2), (2, 2), (1, 7), (7, 1), (1, 33), (33, 1), (3, 5), (5, 3),
             (8, 8), (9, 9), (16, 3), (17, 9), (31, 64), (61, 45), (100, 37), (1, 200),
             (129, 2), (64, 64), (256, 256)]
    sizes += [(rng.randint(1, 300), rng.randint(1, 300)) for _ in range(4)]
    for w, hh in sizes:
        if not fits(h.cfg, w, hh):
            continue
        for bits in (8, 16):
            if w * hh > 20000 and bits == 16 and (w, hh) != (256, 256):
                continue
            h.set_pauses(rng.choice([0.0, 0.2, 0.5]))
            pyr = random_map(rng, w, hh, bits)
            clocks = await h.full(pyr, f"{w}x{hh} unorm{bits}")
            b = pyramid_bus.full_rebuild(w, hh, bits, h.cfg["AXI_DATA_W"])
            dut._log.info("%dx%d unorm%d: %d clocks (bound %d)", w, hh, bits, clocks, b.clocks)
    finish(h, "full rebuilds: image bytes")


def random_rect(rng: random.Random, w: int, h: int) -> tuple[int, int, int, int]:
    kind = rng.random()
    if kind < 0.15:
        x = rng.randrange(w)
        y = rng.randrange(h)
        return x, y, x, y                       # one texel
    if kind < 0.25:
        return rng.randrange(w), h - 1, w - 1, h - 1   # a piece of the last row, to the edge
    if kind < 0.35:
        return 0, rng.randrange(h), w - 1, rng.randrange(h)  # whole rows (maybe empty: fixed)
    x0, x1 = sorted((rng.randrange(w), rng.randrange(w)))
    y0, y1 = sorted((rng.randrange(h), rng.randrange(h)))
    return x0, y0, x1, y1


async def dirty_one(h: Harness, w: int, hh: int, bits: int, rect, what: str) -> int:
    rng = h.rng
    old = random_map(rng, w, hh, bits)
    x0, y0, x1, y1 = rect
    new_codes = old.codes.copy()
    patch = random_map(rng, x1 - x0 + 1, y1 - y0 + 1, bits).codes
    if rng.random() < 0.3:
        patch = patch // max(1, (1 << bits) - 1)  # lowering heights: maxima must fall too
    new_codes[y0:y1 + 1, x0:x1 + 1] = patch
    new = heightmap.build(new_codes, bits)
    src = h.place(new, rng.random() < 0.5, old)
    before = h.snapshot(new)
    clocks, err = await h.build(new, src, rect)
    assert err == 0, f"{what}: err_code {err}"
    bad = h.check(new, before, what)
    assert bad == 0, what
    return clocks


@cocotb.test()
async def dirty_random(dut):
    """Dirty rebuilds on random rectangles against the model's pyramid of the new map."""
    rng = random.Random(seed())
    h = Harness(dut, rng)
    await h.reset()
    cases = [(1, 1), (1, 9), (9, 1), (2, 2), (5, 7), (64, 64), (100, 37), (256, 256)]
    cases += [(rng.randint(1, 260), rng.randint(1, 260)) for _ in range(12)]
    n = 0
    for w, hh in cases:
        if not fits(h.cfg, w, hh):
            continue
        for _ in range(2):
            bits = rng.choice([8, 16])
            h.set_pauses(rng.choice([0.0, 0.3]))
            x0, y0, x1, y1 = random_rect(rng, w, hh)
            rect = (x0, min(y0, y1), x1, max(y0, y1))
            clocks = await dirty_one(h, w, hh, bits, rect, f"{w}x{hh} unorm{bits} dirty {rect}")
            dut._log.info("%dx%d unorm%d dirty %s: %d clocks", w, hh, bits, rect, clocks)
            n += 1
    finish(h, "dirty rebuilds: image bytes")


@cocotb.test()
async def dirty_clocks_1024(dut):
    """A 32x32 dirty rectangle on 1024x1024 unorm8 (64-bit bus, no added latency): its clocks under
    5% of the full rebuild's bus bound (a full rebuild takes at least that bound)."""
    rng = random.Random(seed())
    h = Harness(dut, rng)
    if not fits(h.cfg, 1024, 1024):
        return
    await h.reset()
    bound = pyramid_bus.full_rebuild(1024, 1024, 8, h.cfg["AXI_DATA_W"]).clocks
    worst = 0
    for i in range(3):
        x0 = rng.randrange(1024 - 32) if i else 0
        y0 = rng.randrange(1024 - 32) if i else 0
        rect = (x0, y0, x0 + 31, y0 + 31)
        clocks = await dirty_one(h, 1024, 1024, 8, rect, f"1024x1024 dirty {rect}")
        worst = max(worst, clocks)
        dut._log.info("1024x1024 unorm8 dirty 32x32 at (%d, %d): %d clocks = %.2f%% of the full "
                      "rebuild's bound %d", x0, y0, clocks, 100 * clocks / bound, bound)
        print(f"pyr_build: dirty 32x32 on 1024x1024 at ({x0}, {y0}): {clocks} clocks, "
              f"{100 * clocks / bound:.2f}% of the full bound {bound}")
    assert worst < 0.05 * bound, f"dirty rebuild {worst} clocks >= 5% of {bound}"
    finish(h, "dirty 1024: image bytes")


@cocotb.test()
async def full_clocks_256(dut):
    """Full rebuild of 256x256 unorm8, no added latency: within 1.25x of the bus bound."""
    rng = random.Random(seed())
    h = Harness(dut, rng)
    await h.reset()
    for bits in (8, 16):
        b = pyramid_bus.full_rebuild(256, 256, bits, h.cfg["AXI_DATA_W"])
        pyr = random_map(rng, 256, 256, bits)
        clocks = await h.full(pyr, f"256x256 unorm{bits}", separate_src=False)
        print(f"pyr_build: 256x256 unorm{bits}, {h.cfg['AXI_DATA_W']}-bit bus: {clocks} clocks, "
              f"bound {b.clocks} (read {b.bytes_read} B, written {b.bytes_written} B), "
              f"{clocks / b.clocks:.3f}x")
        dut._log.info("256x256 unorm%d: %d clocks, bound %d, %.3fx", bits, clocks, b.clocks,
                      clocks / b.clocks)
        assert clocks <= 1.25 * b.clocks, f"{clocks} clocks > 1.25 x {b.clocks}"
    finish(h, "256x256 timing builds: image bytes")


@cocotb.test()
async def axi_errors(dut):
    """SLVERR on reads of level 0 and on writes of a level: err_code_o reports it, the build ends,
    and the next build (errors off) is exact."""
    rng = random.Random(seed())
    h = Harness(dut, rng)
    await h.reset()
    for trial in range(6):
        w, hh = rng.randint(2, 150), rng.randint(2, 150)
        bits = rng.choice([8, 16])
        h.set_pauses(rng.choice([0.0, 0.3]))
        pyr = random_map(rng, w, hh, bits)
        src = h.place(pyr, False, None)
        offs = pyr.level_offsets()
        kind = trial % 3   # 0 read, 1 write, 2 both
        if kind in (0, 2):
            # a byte of the map itself (the padding is not read)
            lo = src + (rng.randrange(hh) * pyr.size + rng.randrange(w)) * (bits // 8)
            h.rd.err_ranges = [(lo, lo + 1)]
        if kind in (1, 2):
            k = rng.randint(1, pyr.n)
            h.wr.err_ranges = [(src + offs[k], src + offs[k] + 1)]
        rect = None if rng.random() < 0.7 else random_rect(rng, w, hh)
        if rect is not None:
            rect = (rect[0], min(rect[1], rect[3]), rect[2], max(rect[1], rect[3]))
        _, err = await h.build(pyr, src, rect)
        rd_hit = h.rd.err_ranges != []
        wr_hit = h.wr.err_ranges != []
        dut._log.info("errors %s: %dx%d err_code %d", ("read", "write", "both")[kind], w, hh, err)
        # A read error is only seen when the errored bytes are read (a dirty rectangle may miss them).
        if rect is None and kind in (0, 2):
            assert err & 1, f"read error not reported (err_code {err})"
        if kind in (1, 2) and rect is None:
            assert err & 2, f"write error not reported (err_code {err})"
        assert not (err & 4)
        assert (err & 1) == 0 or rd_hit
        h.rd.err_ranges, h.wr.err_ranges = [], []
        await h.full(random_map(rng, w, hh, bits), f"after errors {w}x{hh}")
    finish(h, "builds after AXI errors: image bytes")


@cocotb.test()
async def reset_mid_build(dut):
    """Resets at random points of full and dirty builds (memory reset with the builder): idle
    afterwards, and the next build is exact."""
    rng = random.Random(seed())
    h = Harness(dut, rng)
    await h.reset()
    for trial in range(6):
        w, hh = rng.randint(100, 250), rng.randint(100, 250)
        bits = rng.choice([8, 16])
        h.set_pauses(rng.choice([0.0, 0.3]))
        pyr = random_map(rng, w, hh, bits)
        src = h.place(pyr, trial % 3 == 0, None)
        rect = None if trial % 2 == 0 else (1, 1, w - 2, hh - 2)
        h.drive(pyr, src, rect)
        dut.start_i.value = 1
        await RisingEdge(dut.clk_i)
        dut.start_i.value = 0
        for _ in range(rng.randint(1, 1200)):
            await RisingEdge(dut.clk_i)
        assert int(dut.busy_o.value) == 1, "build ended before the reset"
        await h.reset(rng.randint(1, 4))
        for _ in range(50):
            await RisingEdge(dut.clk_i)
            assert int(dut.busy_o.value) == 0 and int(dut.done_o.value) == 0
            assert int(dut.m_axi_arvalid.value) == 0 and int(dut.m_axi_awvalid.value) == 0
            assert int(dut.m_axi_wvalid.value) == 0
        await h.full(random_map(rng, w, hh, bits), f"after reset {w}x{hh}")
    finish(h, "builds after resets: image bytes")


@cocotb.test()
async def config_errors(dut):
    """Bad configurations end at once with err_code_o[2] and touch no memory."""
    rng = random.Random(seed())
    h = Harness(dut, rng)
    await h.reset()
    pyr = random_map(rng, 40, 30, 8)
    src = h.place(pyr, False, None)
    before = h.snapshot(pyr)
    rd0, wr0 = h.rd.beats, h.wr.beats
    bb = h.bus_bytes
    cases = {
        "x1 >= W": dict(rect=(0, 0, 40, 29)),
        "y1 >= H": dict(rect=(0, 0, 39, 30)),
        "x0 > x1": dict(rect=(5, 0, 4, 29)),
        "unaligned src": dict(src=src + bb // 2),
        "unaligned pyramid": dict(pyr_base=src + bb // 2),
    }
    for what, c in cases.items():
        clocks, err = await h.build(pyr, c.get("src", src), c.get("rect"),
                                    pyr_base=c.get("pyr_base"))
        assert err == 4 and clocks < 10, f"{what}: err_code {err} after {clocks} clocks"
    for wd, ht in ((0, 5), (5, 0), ((1 << h.max_lg) + 1, 3)):
        dut.cfg_width_i.value, dut.cfg_height_i.value = wd, ht
        dut.start_i.value = 1
        await RisingEdge(dut.clk_i)
        dut.start_i.value = 0
        for _ in range(10):
            await RisingEdge(dut.clk_i)
            if int(dut.done_o.value):
                break
        assert int(dut.done_o.value) and int(dut.err_code_o.value) == 4, (wd, ht)
    assert (h.rd.beats, h.wr.beats) == (rd0, wr0), "memory accessed on a configuration error"
    got = h.snapshot(pyr)
    assert got == before, "memory changed on a configuration error"
    await h.full(pyr, "after configuration errors")
    finish(h, "configuration errors")


@cocotb.test()
async def big_1024(dut):
    """1024x1024 unorm8 full rebuild (its clocks against the bound) and a 32x32 dirty rebuild held
    to 5% of the measured full rebuild (run by test_pyr_build_big only)."""
    rng = random.Random(seed())
    h = Harness(dut, rng)
    await h.reset()
    b = pyramid_bus.full_rebuild(1024, 1024, 8, h.cfg["AXI_DATA_W"])
    pyr = random_map(rng, 1024, 1024, 8)
    full = await h.full(pyr, "1024x1024 unorm8", separate_src=False)
    print(f"pyr_build: 1024x1024 unorm8: {full} clocks, bound {b.clocks}, {full / b.clocks:.3f}x")
    x0, y0 = rng.randrange(992), rng.randrange(992)
    rect = (x0, y0, x0 + 31, y0 + 31)
    dirty = await dirty_one(h, 1024, 1024, 8, rect, f"1024 dirty {rect}")
    print(f"pyr_build: 32x32 dirty at ({x0}, {y0}): {dirty} clocks, "
          f"{100 * dirty / full:.2f}% of the full rebuild's {full}")
    assert full <= 1.25 * b.clocks
    assert dirty < 0.05 * full
    finish(h, "1024x1024: image bytes")


def _run(name: str, tests: str | None = None, extra: dict[str, str] | None = None) -> None:
    s = int(os.environ.get("SEED", random.randrange(1, 1 << 31)))
    print(f"pyr_build-{name}: SEED={s}")
    cfg = CONFIGS[name]
    env = {"PYR_CFG": json.dumps(cfg), "SEED": str(s)}
    env.update(extra or {})
    runner.run("pyr_build", "test_pyr_build", Path(__file__).parent, parameters=cfg,
               name=f"pyr_build-{name}", extra_env=env, testcase=tests)


def test_pyr_build():
    """64-bit bus, maps up to 1024x1024: every test but the 1024x1024 full build."""
    _run("default", "full_sizes,dirty_random,dirty_clocks_1024,full_clocks_256,axi_errors,"
                    "reset_mid_build,config_errors")


@pytest.mark.skipif(not runner.long_stimulus(), reason="the 32-bit bus, not the design's default: make test-long (TB_LONG=1)")
def test_pyr_build_bus32():
    """32-bit bus, 4-beat bursts, maps up to 256x256."""
    _run("bus32", "full_sizes,dirty_random,axi_errors,config_errors")


@pytest.mark.skipif(not runner.long_stimulus(), reason="the 128-bit bus, not the design's default: make test-long (TB_LONG=1)")
def test_pyr_build_bus128():
    """128-bit bus, 8-beat bursts, maps up to 512x512."""
    _run("bus128", "full_sizes,dirty_random,reset_mid_build")


@pytest.mark.skipif(not (runner.long_stimulus() or os.environ.get("PYR_BIG") == "1"),
                    reason="1024x1024 full build: TB_LONG=1 (make test-long) or PYR_BIG=1")
def test_pyr_build_big():
    _run("default", "big_1024")


if __name__ == "__main__":
    pytest.main([__file__, "-q", "-s"])
