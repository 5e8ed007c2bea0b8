# SPDX-License-Identifier: Apache-2.0
"""pix_dma (dm_pipeline's pixel stream -> RGBA8 framebuffer + status words over AXI4 writes).

Pixels with random ids (distinct (x, y) of a W x H frame, in random order, as a pipeline
finishes them), colours, flags and iteration counts enter with random valid gaps; the
cocotbext-axi memory (tb/common/axi_ram.FaultWrite) has random latency and random pauses on AW,
W and B.  The buffers are filled with a pattern first.  Checked per frame: after idle_o, every
pixel's RGBA word at fb_base + y * pitch + x * 4 (alpha 0xFF) and, with st_en, its status word
(rtl/top/pidm_pkg.sv: iterations, hit, invalid, error) at st_base + ...; every other byte of both
buffers (and of the row padding) still the pattern; written_o = pixels_o = the pixel count;
err_o = 0; AWCACHE / AWPROT / AWSIZE / AWLEN as parameterised; no write outside the buffers.

Error cases: an SLVERR range inside the framebuffer (err_o; every pixel outside it still
written, idle_o reached); abort_i at a random clock (idle_o reached; the next frame exact).

The three (DATA_W, MAX_OUTST) of CASES are built once, side by side, in the wrapper
``pix_dma_tb`` (one instance each, own ports, reset and memory model, a shared clock) and run at
once in one simulation, each with its own random stream from the printed seed and its own
checks; a failure names the configuration.

Environment: SEED, PIX_FRAMES (random frames, default 10).
"""
from __future__ import annotations

import logging
import os
import random
from pathlib import Path

from typing import Any, Callable, Coroutine

import cocotb
from cocotb.triggers import ClockCycles, FallingEdge
from cocotbext.axi import AxiWriteBus

from tb.common import cases, report, runner
from tb.common.axi_ram import FaultWrite, set_pauses

HERE = Path(__file__).resolve().parent
FILL = 0xA5
#: (DATA_W, MAX_OUTST) of the instances g_case[0 ..] of pix_dma_tb (the wrapper's table): the
#: default, the narrowest bus with the fewest writes in flight, a wide bus.
CASES = [(64, 8), (32, 2), (128, 4)]
#: AWCACHE and AWPROT of every instance (not the defaults, so that the bus shows them).
AWCACHE, AWPROT = 0b0111, 0b001


class Tb:
    """One instance ``g_case[i]`` of pix_dma_tb (``dut``: its scope) on the shared clock ``clk``,
    with its own memory model on its m_axi_* signals and its own random generator."""

    def __init__(self, dut, clk, rng: random.Random, name: str) -> None:
        self.dut = dut
        self.clk = clk
        self.rng = rng
        self.log = cases.logger(name)
        self.ram = FaultWrite(AxiWriteBus.from_prefix(dut, "m_axi"), clk, reset=None,
                              rng=rng, size=1 << 32)
        self.ram.log.setLevel(logging.CRITICAL)

    async def reset(self) -> None:
        d = self.dut
        d.rst_ni.value = 0
        d.start_i.value = 0
        d.abort_i.value = 0
        d.px_valid_i.value = 0
        await ClockCycles(self.clk, 4)
        await FallingEdge(self.clk)
        d.rst_ni.value = 1
        await FallingEdge(self.clk)

    async def start(self, fb: int, st: int, pitch: int, st_en: int, xbits: int) -> None:
        d = self.dut
        d.xbits_i.value = xbits
        d.fb_base_i.value = fb
        d.st_base_i.value = st
        d.pitch_i.value = pitch
        d.st_en_i.value = st_en
        d.start_i.value = 1
        await FallingEdge(self.clk)
        d.start_i.value = 0

    async def stream(self, pixels: list[tuple[int, ...]], valid_p: float,
                     abort_at: int | None = None, max_clocks: int = 100_000) -> int:
        """Offer the pixels; then wait for idle_o.  Returns clocks."""
        d = self.dut
        cache, prot = AWCACHE, AWPROT
        i, cyc, presenting = 0, 0, False
        while True:
            if cyc >= max_clocks:
                raise AssertionError(f"pix_dma hangs: {i} of {len(pixels)} offered, "
                                     f"idle {int(d.idle_o.value)}")
            if abort_at is not None and cyc == abort_at:
                d.abort_i.value = 1
            if not presenting and i < len(pixels) and self.rng.random() < valid_p:
                pid, rgb, hit, inv, err, iters = pixels[i]
                d.px_id_i.value = pid
                d.px_rgb_i.value = rgb
                d.px_hit_i.value = hit
                d.px_invalid_i.value = inv
                d.px_err_i.value = err
                d.px_iters_i.value = iters
                presenting = True
            d.px_valid_i.value = int(presenting)
            # px_ready_o is a register: the handshake at the next edge is known now
            fire = presenting and int(d.px_ready_o.value)
            if int(d.m_axi_awvalid.value):
                assert int(d.m_axi_awcache.value) == cache and int(d.m_axi_awprot.value) == prot
                assert int(d.m_axi_awlen.value) == 0 and int(d.m_axi_awsize.value) == 2
            if i == len(pixels) and not presenting and int(d.idle_o.value):
                break
            await FallingEdge(self.clk)
            cyc += 1
            if fire:
                i += 1
                presenting = False
                d.px_valid_i.value = 0
        d.abort_i.value = 0
        for _ in range(10):       # nothing more
            assert int(d.idle_o.value) and not int(d.m_axi_awvalid.value)
            await FallingEdge(self.clk)
        return cyc


def make_pixels(rng: random.Random, w: int, h: int, n: int, xbits: int
                ) -> list[tuple[int, ...]]:
    cells = rng.sample(range(w * h), n)
    out = []
    for c in cells:
        y, x = divmod(c, w)
        out.append(((y << xbits) | x, rng.getrandbits(24), rng.getrandbits(1),
                    rng.getrandbits(1), rng.getrandbits(1), rng.getrandbits(16)))
    return out


def expect_words(px: tuple[int, ...]) -> tuple[int, int]:
    _, rgb, hit, inv, err, iters = px
    return ((0xFF << 24) | rgb,
            (err << 18) | (inv << 17) | (hit << 16) | iters)


def check(tb: Tb, fb: int, st: int, pitch: int, h: int, st_en: int, xbits: int,
          pixels: list[tuple[int, ...]], skip: set[int] = frozenset()) -> int:
    """Mismatching 32-bit words in both buffers (pixels whose address is in ``skip``, a set of
    framebuffer word addresses answered SLVERR, may hold anything)."""
    size = pitch * h
    want_fb = bytearray([FILL]) * size
    want_st = bytearray([FILL]) * size
    for px in pixels:
        y, x = px[0] >> xbits, px[0] & ((1 << xbits) - 1)
        off = y * pitch + 4 * x
        c, s = expect_words(px)
        want_fb[off:off + 4] = c.to_bytes(4, "little")
        if st_en:
            want_st[off:off + 4] = s.to_bytes(4, "little")
    got_fb = tb.ram.read(fb, size)
    got_st = tb.ram.read(st, size)
    bad = 0
    for off in range(0, size, 4):
        if fb + off not in skip and got_fb[off:off + 4] != want_fb[off:off + 4]:
            bad += 1
        if got_st[off:off + 4] != want_st[off:off + 4]:
            bad += 1
    return bad


async def one_frame(tb: Tb, k: int, w: int, h: int, n: int, st_en: int, log,
                    err_lo: int | None = None, abort_at: int | None = None
                    ) -> tuple[int, int, int]:
    """A frame; (pixels checked, mismatches, clocks)."""
    rng = tb.rng
    d = tb.dut
    pitch = 4 * w + 4 * rng.randrange(0, 4)
    fb = 0x3000_0000 + k * 0x10_0000 + 4 * rng.randrange(0, 64)
    st = fb + 0x8_0000
    size = pitch * h
    tb.ram.write(fb, bytes([FILL]) * size)
    tb.ram.write(st, bytes([FILL]) * size)
    tb.ram.regions = [(fb, fb + size), (st, st + size)]
    set_pauses(tb.ram, rng, rng.choice((0.0, 0.2, 0.5)))
    tb.ram.lat, tb.ram.lat_p = (1, rng.choice((3, 20))), rng.choice((0.0, 0.1, 0.4))
    xbits = rng.randrange(max(w - 1, 1).bit_length(), 13)
    pixels = make_pixels(rng, w, h, n, xbits)
    skip: set[int] = set()
    if err_lo is not None:
        lo = fb + (err_lo % size) // 4 * 4
        tb.ram.err_ranges = [(lo, lo + 4 * rng.randrange(1, 40))]
        skip = {a for a in range(lo, tb.ram.err_ranges[0][1], 4)}
    await tb.start(fb, st, pitch, st_en, xbits)
    cyc = await tb.stream(pixels, rng.choice((1.0, 0.6, 0.2)), abort_at)
    tb.ram.err_ranges = []
    assert not tb.ram.outside, f"writes outside the buffers: {tb.ram.outside[:4]}"
    err = int(d.err_o.value)
    npx, nwr = int(d.pixels_o.value), int(d.written_o.value)
    what = f"frame {k}: {w}x{h} {n} px st_en {st_en} xbits {xbits}"
    if abort_at is not None:
        log.info("%s: abort at %d: %d taken, %d written, %d clocks", what, abort_at, npx, nwr, cyc)
        assert err == 0 and npx == n and nwr <= n
        return 0, 0, cyc
    hit_err = any(fb + (px[0] >> xbits) * pitch + 4 * (px[0] & ((1 << xbits) - 1)) in skip
                  for px in pixels)
    bad = check(tb, fb, st, pitch, h, st_en, xbits, pixels, skip)
    log.info("%s: %d clocks, %d bad words, err %d, written %d", what, cyc, bad, err, nwr)
    assert err == int(hit_err), f"{what}: err_o {err}, a pixel in the SLVERR range: {hit_err}"
    assert npx == n and nwr == n, f"{what}: pixels {npx}, written {nwr} of {n}"
    return n, bad, cyc


Check = Callable[[Tb], Coroutine[Any, Any, None]]


async def each_case(dut, check: Check) -> None:
    """Start the clock, then reset every instance of pix_dma_tb and run ``check`` on it (all at
    once, each with its own memory model and random generator: :func:`cases.randoms`); fail
    naming every configuration whose check failed."""
    def name(case: tuple[int, int]) -> str:
        return f"pix_dma DATA_W {case[0]}, MAX_OUTST {case[1]}"

    async def one(inst, case: tuple[int, int], rng: random.Random) -> None:
        mism = cases.param_mismatches(dut, {"AWCACHE": AWCACHE, "AWPROT": AWPROT})
        assert not mism, "\n".join(mism)
        tb = Tb(inst, dut.clk_i, rng, name(case))
        await tb.reset()
        await check(tb)

    await cases.run_each(dut, CASES, name, one,
                         lambda c: {"DATA_W": c[0], "MAX_OUTST": c[1]}, cases.randoms)


@cocotb.test()
async def pix_dma_frames(dut):
    """Random frames (:func:`frames`) on every instance."""
    await each_case(dut, frames)


async def frames(tb: Tb) -> None:
    """Random frames under latency and back-pressure, every word of both buffers."""
    rng = tb.rng
    total = bad = clocks = 0
    shapes = [(1, 1, 1), (3, 2, 6), (17, 9, 100), (40, 30, 1200), (64, 4, 256)]
    for _ in range(int(os.environ.get("PIX_FRAMES", "10"))):
        w, h = rng.randrange(1, 80), rng.randrange(1, 40)
        shapes.append((w, h, rng.randrange(1, w * h + 1)))
    for k, (w, h, n) in enumerate(shapes):
        t, b, c = await one_frame(tb, k, w, h, n, st_en=k % 3 != 1, log=tb.log)
        assert b == 0, f"frame {k}: {b} words differ"
        total, bad, clocks = total + t, bad + b, clocks + c
    report.record("pix_dma", "framebuffer and status words vs pixels", total, bad)
    tb.log.info(f"PIX_DMA frames: {len(shapes)} frames, {total} pixels in {clocks} clocks, "
                f"{bad} mismatching words")


@cocotb.test()
async def pix_dma_errors(dut):
    """SLVERR and abort (:func:`errors`) on every instance."""
    await each_case(dut, errors)


async def errors(tb: Tb) -> None:
    """SLVERR in the framebuffer and abort: err_o / idle_o, no hang, the next frame exact."""
    rng = tb.rng
    checked = 0
    for k in range(8):
        w, h = rng.randrange(8, 40), rng.randrange(4, 20)
        n = rng.randrange(w * h // 2, w * h + 1)
        if k % 2 == 0:
            t, b, _ = await one_frame(tb, 2 * k, w, h, n, 1, tb.log,
                                      err_lo=rng.randrange(0, 4 * w * h))
            assert b == 0, f"SLVERR frame {k}: {b} words differ outside the SLVERR range"
            checked += t
        else:
            await one_frame(tb, 2 * k, w, h, n, 1, tb.log, abort_at=rng.randrange(0, 6 * n))
        t, b, _ = await one_frame(tb, 2 * k + 1, w, h, n, 1, tb.log)
        assert b == 0, f"the frame after error case {k}: {b} words differ"
        checked += t
    report.record("pix_dma", "pixels around SLVERR / abort and the next frame", checked, 0)
    tb.log.info(f"PIX_DMA errors: 4 SLVERR frames, 4 aborts, each followed by an exact frame "
                f"({checked} pixels checked), SLVERR words {tb.ram.err_words}")


def test_pix_dma() -> None:
    """Build pix_dma_tb (every configuration of CASES) once and run the cocotb tests."""
    runner.run("pix_dma_tb", "test_pix_dma", HERE, rtl_top="pix_dma",
               extra_sources=[str(HERE / "pix_dma_tb.sv")])
