# SPDX-License-Identifier: Apache-2.0
"""pidm_top (registers on AXI4-Lite, fragment DMA, dm_pipeline, framebuffer DMA, irq) as a CPU
and a memory see it.

cocotbext-axi's AxiLiteMaster plays the CPU and writes the registers as the C driver (sw/pidm.c)
does: clear and enable the interrupts, the configuration and the triangle table, the frame
descriptor, CTRL.start; then it waits for irq_o, reads INTR_STATE, ERROR, STATUS, PROGRESS and
STATS, and clears INTR_STATE.  Every address and field comes from rtl/top/pidm_regs.rdl
(tb.harness.pidm_regmap); the frame's memory images, register writes and expected framebuffer
from tb.harness.pidm_frame (the model's configuration, fragments and image: model.shade.render,
f24 engine).  One sparse memory serves the four AXI ports (fragments, framebuffer writes,
heights, textures: tb/common/axi_ram.FaultRead / FaultWrite), each with its own random latency
and channel pauses, and flags every access outside the frame's regions.

Cases (followed by a frame that must be exact, bit for bit, in the framebuffer and the status
buffer): frames with the interrupt and by polling; CTRL.soft_reset in the middle of a
frame (busy falls, no frame_done); SLVERR on the fragment buffer, on the height pyramid and on
the texture port (the ERROR flag, INTR_STATE.axi_error and frame_done, busy falls; every pixel
written is the model's or carries the error flag); SLVERR on framebuffer writes (ERROR.fb_write);
bad configurations (FRAG_COUNT 0, an unaligned framebuffer base, a method code out of range, a
MIP level count of 0: ERROR.bad_config, INTR_STATE.axi_error, the frame does not start).

The pyramid builder (pidm_top_pyramid): level 0 of the map in memory and garbage in levels
1..n; the PYR registers programmed as sw/pidm.c's pidm_pyr_build does, CTRL.pyr_start, the
pyr_done interrupt; the pyramid image in memory must equal model.heightmap's byte for byte, and a
frame rendered from it (the image in memory is not rewritten) the model's.  Then a rectangle of
level 0 changes, a dirty rebuild, the image again and a frame without soft reset (the build's end
invalidates the height cache); SLVERR on a build's writes and on its reads (ERROR.pyr_write /
pyr_read, both interrupts, the next build exact); starts refused while the other side is busy
(ERROR.start_refused; the running build or frame is exact); bad PYR configurations.

pidm_top_no_builder (``make test-long``, TB_LONG=1: a second build of pidm_top with PYR_BUILD 0):
PYR.INFO reads 0 present, CTRL.pyr_start sets ERROR.pyr_config and INTR_STATE.axi_error and
nothing else, and a frame is exact.

Environment: SEED.
"""
from __future__ import annotations

import dataclasses
import logging
import os
import random
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge
from cocotbext.axi import AxiLiteBus, AxiLiteMaster, AxiReadBus, AxiWriteBus

from model import camera, heightmap, scenes, shade, texture
from tb.common import report, runner
from tb.common.axi_ram import FaultRead, FaultWrite, set_pauses
from tb.harness import pidm_frame, pidm_regmap

HERE = Path(__file__).resolve().parent
R = pidm_regmap.reg
PIX_W = 24          # pidm_top's default


def seed() -> int:
    s = int(os.environ.get("SEED", random.randrange(1 << 31)))
    cocotb.log.info("SEED=%d", s)
    print(f"pidm_top SEED={s}")
    return s


def make_frame(name: str, size: int, angle: str, image: int, method: str, mip: bool
               ) -> tuple[shade.Frame, camera.Camera]:
    sc = scenes.load_scene(name, size)
    tex = texture.build(sc.texture)
    ntex = texture.build(scenes.encode_normals(sc.normals))
    cam = camera.Camera.for_view(angle, size, size, image, image, depth_scale=sc.depth_scale)
    frame = shade.Frame(pyr=heightmap.build(sc.heights), colour=tex, normals=ntex,
                        depth_scale=sc.depth_scale,
                        log2pb_colour=cam.log2_pb(tex.width, tex.height),
                        log2pb_normal=cam.log2_pb(ntex.width, ntex.height),
                        method=method, engine="f24", mip=mip)
    return frame, cam


class Sys:
    """The DUT with its CPU and memory."""

    def __init__(self, dut, rng: random.Random) -> None:
        self.dut = dut
        self.rng = rng
        clk = dut.clk_i
        cocotb.start_soon(Clock(clk, 10, unit="ns").start())
        self.cpu = AxiLiteMaster(AxiLiteBus.from_prefix(dut, "s_axil"), clk, dut.rst_ni,
                                 reset_active_level=False)
        self.f = FaultRead(AxiReadBus.from_prefix(dut, "m_axi_f"), clk, reset=None, rng=rng,
                           size=1 << 32)
        mem = self.f.mem
        self.h = FaultRead(AxiReadBus.from_prefix(dut, "m_axi_h"), clk, reset=None, rng=rng,
                           mem=mem)
        self.t = FaultRead(AxiReadBus.from_prefix(dut, "m_axi_t"), clk, reset=None, rng=rng,
                           mem=mem)
        self.w = FaultWrite(AxiWriteBus.from_prefix(dut, "m_axi_w"), clk, reset=None, rng=rng,
                            mem=mem)
        self.ports = (self.f, self.h, self.t, self.w)
        for p in self.ports + (self.cpu.write_if, self.cpu.read_if):
            p.log.setLevel(logging.CRITICAL)

    async def reset(self) -> None:
        d = self.dut
        d.rst_ni.value = 0
        await ClockCycles(d.clk_i, 5)
        await FallingEdge(d.clk_i)
        d.rst_ni.value = 1
        await ClockCycles(d.clk_i, 5)

    async def wr(self, path: str, value: int) -> None:
        await self.cpu.write_dword(R(path).addr, value)

    async def rd(self, path: str) -> int:
        return await self.cpu.read_dword(R(path).addr)

    async def rd_fields(self, path: str) -> dict[str, int]:
        return R(path).fields_of(await self.rd(path))

    def traffic(self, p: float, lat: tuple[int, int], lat_p: float) -> None:
        for port in self.ports:
            set_pauses(port, self.rng, p)
            port.lat, port.lat_p = lat, lat_p

    def load(self, packed: pidm_frame.PackedFrame, keep: tuple[str, ...] = ()) -> None:
        """The frame's regions into memory (but those named in ``keep``); every port may touch
        only them."""
        for r in packed.regions:
            if r.name not in keep:
                self.f.write(r.base, r.data)
        spans = [(r.base, r.base + len(r.data)) for r in packed.regions]
        for port in self.ports:
            port.regions = spans
            port.err_ranges = []
            port.outside.clear()

    async def program(self, packed: pidm_frame.PackedFrame) -> None:
        """The driver's sequence up to (not including) CTRL.start."""
        st = R("INTR_STATE")
        await self.wr("INTR_STATE", st.value(frame_done=1, axi_error=1))
        await self.wr("INTR_ENABLE", R("INTR_ENABLE").value(frame_done=1, axi_error=1))
        await self.wr("ERROR", (1 << 32) - 1)
        for addr, val in packed.config + packed.frame_writes:
            await self.cpu.write_dword(addr, val)
        await self.wr("CTRL", R("CTRL").value(clear_stats=1))

    async def start(self, packed: pidm_frame.PackedFrame) -> None:
        await self.cpu.write_dword(*packed.start)

    async def wait_irq(self, max_clocks: int) -> int:
        """Clocks until irq_o (AssertionError after max_clocks)."""
        for c in range(max_clocks):
            if int(self.dut.irq_o.value):
                return c
            await FallingEdge(self.dut.clk_i)
        raise AssertionError(f"no interrupt in {max_clocks} clocks; STATUS "
                             f"{await self.rd_fields('STATUS')}, PROGRESS "
                             f"{await self.rd('PROGRESS')}")

    async def wait_idle(self, max_polls: int = 2000) -> int:
        """Poll STATUS.busy until 0; polls taken."""
        for k in range(max_polls):
            if not (await self.rd_fields("STATUS"))["busy"]:
                return k
        raise AssertionError(f"STATUS.busy still 1 after {max_polls} polls")

    async def ack(self) -> dict[str, int]:
        """INTR_STATE read and cleared (the interrupt handler); irq_o must fall."""
        st = await self.rd("INTR_STATE")
        await self.wr("INTR_STATE", st)
        await ClockCycles(self.dut.clk_i, 2)
        assert not int(self.dut.irq_o.value), "irq_o stays high after INTR_STATE was cleared"
        return R("INTR_STATE").fields_of(st)

    def outside(self) -> list[int]:
        return [a for p in self.ports for a in p.outside]


class Scene:
    """A frame, its packing and its expected memory."""

    def __init__(self, case: tuple, fb_base: int = pidm_frame.FB_BASE) -> None:
        name, size, angle, image, method, mip = case
        self.name = f"{name} {size} {angle} {image}px {method} mip={int(mip)}"
        self.frame, self.cam = make_frame(name, size, angle, image, method, mip)
        self.packed = pidm_frame.pack(self.frame, self.cam, pix_w=PIX_W, fb_base=fb_base)
        ref = shade.render(self.frame, self.cam)
        self.exp = pidm_frame.expected_memory(self.packed, ref)
        self.n = self.packed.descriptor["frag_count"]
        self.hits = int(ref.out.hit.sum())

    def words(self, sys_: Sys, region: str) -> np.ndarray:
        r = self.packed.region(region)
        return np.frombuffer(bytes(sys_.f.read(r.base, len(r.data))), dtype="<u4")

    def exp_words(self, region: str) -> np.ndarray:
        return np.frombuffer(self.exp[region], dtype="<u4")

    def init_words(self, region: str) -> np.ndarray:
        return np.frombuffer(self.packed.region(region).data, dtype="<u4")


CLEAN = ("bump", 32, "oblique", 20, "park", True)
#: The errors test's frames: CLEAN under make test-long, a 12 x 12 image of it in make test (the
#: error paths and the recovery do not depend on the frame's size).
ERR_CASE = CLEAN if runner.long_stimulus() else ("bump", 32, "oblique", 12, "park", True)
OTHER = ("rocks", 32, "grazing", 16, "park-xor", True)
FRONT = ("four-shapes", 32, "front", 16, "oh", False)


async def full_frame(s: Sys, sc: Scene, log, irq: bool = True, p: float = 0.3,
                     lat: tuple[int, int] = (1, 30), lat_p: float = 0.1,
                     keep_heights: bool = False) -> int:
    """Program, start, wait (interrupt or polling), check every word; mismatching words.
    ``keep_heights``: the height pyramid in memory is left as it is (built by the hardware)."""
    s.load(sc.packed, keep=("heights",) if keep_heights else ())
    s.traffic(p, lat, lat_p)
    await s.program(sc.packed)
    if not irq:
        await s.wr("INTR_ENABLE", 0)
    t0 = cocotb.utils.get_sim_time("ns")
    await s.start(sc.packed)
    if irq:
        await s.wait_irq(400 * sc.n + 50_000)
        intr = await s.ack()
        assert intr == {"frame_done": 1, "axi_error": 0, "pyr_done": 0}, \
            f"{sc.name}: INTR_STATE {intr}"
    else:
        await s.wait_idle(20 * sc.n + 5000)
        intr = R("INTR_STATE").fields_of(await s.rd("INTR_STATE"))
        assert intr["frame_done"] == 1 and not int(s.dut.irq_o.value)
    clocks = int((cocotb.utils.get_sim_time("ns") - t0) / 10)
    status = await s.rd_fields("STATUS")
    err = await s.rd("ERROR")
    prog = await s.rd("PROGRESS")
    stats = {k: (await s.cpu.read_dword(R(f"STATS.{k}.LO").addr))
             | ((await s.cpu.read_dword(R(f"STATS.{k}.HI").addr)) << 32)
             for k in ("pixels", "cycles", "iters")}
    bad = 0
    for region in sc.exp:
        got, want = sc.words(s, region), sc.exp_words(region)
        bad += int((got != want).sum())
    log.info("%s: %d fragments (%d hits), %d clocks, %d bad words, PROGRESS %d, STATS %s",
             sc.name, sc.n, sc.hits, clocks, bad, prog, stats)
    assert status["busy"] == 0 and err == 0, f"{sc.name}: STATUS {status}, ERROR {err:#x}"
    assert prog == sc.n and stats["pixels"] == sc.n, f"{sc.name}: PROGRESS {prog}, {stats}"
    assert not s.outside(), f"{sc.name}: accesses outside the regions: {s.outside()[:4]}"
    assert bad == 0, f"{sc.name}: {bad} words differ from the model"
    report.record("pidm_top", "framebuffer + status words vs model.shade f24", sc.n, bad)
    return bad


async def soft_reset(s: Sys) -> None:
    await s.wr("CTRL", R("CTRL").value(soft_reset=1))
    await s.wait_idle()


@cocotb.test()
async def pidm_top_frames(dut):
    """Frames through the system: interrupt and polling, three scenes, random traffic."""
    rng = random.Random(seed())
    s = Sys(dut, rng)
    await s.reset()
    hw = await s.rd_fields("HWCFG")
    assert hw["pix_w"] == PIX_W and hw["addr_w"] == 32, f"HWCFG {hw}"
    assert await s.rd("ID") == 0x5049444D
    total = 0
    plan = ((CLEAN, True, 0.3), (CLEAN, False, 0.0), (OTHER, True, 0.5), (FRONT, False, 0.2))
    for k, (case, irq, p) in enumerate(plan):
        if k and case != plan[k - 1][0]:
            await soft_reset(s)           # new textures and pyramid: forget the cached lines
        sc = Scene(case)
        await full_frame(s, sc, dut._log, irq=irq, p=p)
        total += sc.n
    print(f"PIDM_TOP frames: 4 frames, {total} pixels, every framebuffer and status word exact")


def consistent(sc: Scene, s: Sys, fb_err: tuple[int, int] | None = None
               ) -> tuple[int, int, int]:
    """After a frame an error ended: (pixels written as the model, pixels untouched, pixels
    that are neither and do not carry the error flag).  A pixel whose status word carries
    the error flag may hold any colour, and so may one whose framebuffer word lies in
    ``fb_err`` (a byte range whose writes were answered SLVERR)."""
    fb, st = sc.words(s, "framebuffer"), sc.words(s, "status")
    efb, est = sc.exp_words("framebuffer"), sc.exp_words("status")
    ifb, ist = sc.init_words("framebuffer"), sc.init_words("status")
    err_bit = 1 << pidm_frame.STW_ERR_BIT
    exact = (fb == efb) & (st == est)
    untouched = (fb == ifb) & (st == ist)
    flagged = (st & err_bit) != 0
    if fb_err is not None:
        addr = sc.packed.region("framebuffer").base + 4 * np.arange(len(fb))
        flagged |= (addr >= fb_err[0]) & (addr < fb_err[1])
    bad = ~(exact | untouched | flagged)
    return int(exact.sum()), int((untouched & ~exact).sum()), int(bad.sum())


async def error_frame(s: Sys, sc: Scene, log, port: str, flag: str, region: str,
                      span: tuple[float, float]) -> None:
    """A frame with an SLVERR range on ``port`` over the ``span`` fraction of ``region`` (after
    a soft reset: the caches hold no line of it): ``flag`` set, both interrupts, busy falls,
    the memory consistent; then soft reset."""
    await soft_reset(s)
    s.load(sc.packed)
    s.traffic(0.2, (1, 20), 0.1)
    r = sc.packed.region(region)
    lo = r.base + int(len(r.data) * span[0]) // 64 * 64
    hi = r.base + int(len(r.data) * span[1]) // 64 * 64
    mem = getattr(s, port)
    mem.err_ranges = [(lo, hi)]
    words0 = mem.err_words
    await s.program(sc.packed)
    await s.start(sc.packed)
    await s.wait_irq(400 * sc.n + 50_000)
    await s.wait_idle()
    intr = await s.ack()
    err = R("ERROR").fields_of(await s.rd("ERROR"))
    mem.err_ranges = []
    exact, untouched, bad = consistent(sc, s, (lo, hi) if port == "w" else None)
    hit = mem.err_words - words0
    log.info("%s with SLVERR on %s (%s +%#x .. +%#x, %d words answered SLVERR): ERROR %s, "
             "INTR %s; %d pixels exact, %d untouched, %d wrong", sc.name, port, region,
             lo - r.base, hi - r.base, hit, err, intr, exact, untouched, bad)
    assert hit > 0, "the SLVERR range was never accessed: the case tests nothing"
    assert intr == {"frame_done": 1, "axi_error": 1, "pyr_done": 0}, f"INTR_STATE {intr}"
    assert err[flag] == 1, f"ERROR {err}: {flag} not set"
    assert bad == 0, f"{bad} pixels neither the model's, untouched nor flagged"
    if port != "w":
        assert not s.outside()
    await s.wr("ERROR", (1 << 32) - 1)
    assert await s.rd("ERROR") == 0
    await soft_reset(s)


@cocotb.test()
async def pidm_top_errors(dut):
    """AXI errors on each port, soft reset mid-frame, bad configurations; each followed by an
    exact frame."""
    rng = random.Random(seed() + 1)
    s = Sys(dut, rng)
    await s.reset()
    sc = Scene(ERR_CASE)
    log = dut._log
    # soft reset in the middle of frames
    for trial in range(2):
        s.load(sc.packed)
        s.traffic(0.3, (1, 30), 0.1)
        await s.program(sc.packed)
        await s.start(sc.packed)
        cut = rng.randrange(50, 12 * sc.n)
        await ClockCycles(dut.clk_i, cut)
        prog = await s.rd("PROGRESS")
        assert prog < sc.n, f"the frame ended within {cut} clocks: no reset mid-frame"

        await soft_reset(s)
        intr = R("INTR_STATE").fields_of(await s.rd("INTR_STATE"))
        log.info("soft reset %d clocks into the frame (%d pixels written): INTR %s", cut, prog,
                 intr)
        assert intr["frame_done"] == 0 and await s.rd("ERROR") == 0
        await full_frame(s, sc, log)
    # SLVERR on each read port and on the framebuffer writes
    for port, flag, region, span in (("f", "frag_dma", "fragments", (0.5, 0.55)),
                                     ("h", "h_axi", "heights", (0.0, 0.5)),
                                     ("t", "t_axi", "textures", (0.0, 0.5)),
                                     ("w", "fb_write", "framebuffer", (0.4, 0.6))):
        await error_frame(s, sc, log, port, flag, region, span)
        await full_frame(s, sc, log)
    # bad configurations: the frame does not start
    bads = [("FRAME.FRAG_COUNT", R("FRAME.FRAG_COUNT").value(val=0)),
            ("FRAME.FB_BASE.LO", pidm_frame.FB_BASE + 2),
            ("HEIGHT.MODE", R("HEIGHT.MODE").value(method=12)),
            ("SHADE.MIP", R("SHADE.MIP").value(mip_en=1, levels_colour=0, levels_normal=3)),
            ("FRAME.FB_LAYOUT", R("FRAME.FB_LAYOUT").value(xbits=PIX_W + 1))]
    for path, val in bads:
        s.load(sc.packed)
        await s.program(sc.packed)
        await s.wr(path, val)
        await s.start(sc.packed)
        await ClockCycles(dut.clk_i, 20)
        assert int(dut.irq_o.value), f"bad {path}: no interrupt"
        status = await s.rd_fields("STATUS")
        intr = await s.ack()
        err = R("ERROR").fields_of(await s.rd("ERROR"))
        log.info("bad %s = %#x: ERROR %s, INTR %s, STATUS %s", path, val, err, intr, status)
        assert err == {**{k: 0 for k in err}, "bad_config": 1}, f"bad {path}: ERROR {err}"
        assert intr == {"frame_done": 0, "axi_error": 1, "pyr_done": 0} and status["busy"] == 0
        assert (sc.words(s, "framebuffer") == sc.init_words("framebuffer")).all(), \
            f"bad {path}: the framebuffer was written"
    await full_frame(s, sc, log)    # the configuration written whole again: exact
    print("PIDM_TOP errors: 2 soft resets mid-frame, SLVERR on the fragment, height, texture "
          "and framebuffer ports, 5 bad configurations; every following frame exact")


# ---- the pyramid builder -----------------------------------------------------------------------

class PyrScene(Scene):
    """A scene whose level 0 is ``codes`` (unorm8) instead of the scene's own heights."""

    def __init__(self, case: tuple, codes: np.ndarray) -> None:
        name, size, angle, image, method, mip = case
        self.name = f"{name} {size} {angle} {image}px {method} mip={int(mip)} (changed level 0)"
        frame, self.cam = make_frame(name, size, angle, image, method, mip)
        self.frame = dataclasses.replace(frame, pyr=heightmap.build(codes.astype(np.uint16)))
        self.packed = pidm_frame.pack(self.frame, self.cam, pix_w=PIX_W)
        ref = shade.render(self.frame, self.cam)
        self.exp = pidm_frame.expected_memory(self.packed, ref)
        self.n = self.packed.descriptor["frag_count"]
        self.hits = int(ref.out.hit.sum())


def level0_bytes(pyr: heightmap.Pyramid) -> bytes:
    """Level 0 as it sits in the pyramid image (the padded square, pitch N codes)."""
    return pyr.memory_image()[:pyr.level_offsets()[1]] if pyr.n else pyr.memory_image()


async def pyr_program(s: Sys, pyr: heightmap.Pyramid, base: int,
                      rect: tuple[int, int, int, int] | None = None) -> None:
    """The PYR registers as sw/pidm.c's pidm_pyr_build writes them (level 0 at ``base``, the
    pyramid image at ``base``), the interrupts cleared and enabled; not the start."""
    w, h = pyr.width, pyr.height
    x0, y0, x1, y1 = rect if rect is not None else (0, 0, w - 1, h - 1)
    await s.wr("PYR.FORMAT", R("PYR.FORMAT").value(bits16=int(pyr.bits == 16)))
    await s.wr("PYR.SIZE", R("PYR.SIZE").value(width=w, height=h))
    for reg in ("PYR.SRC_BASE", "PYR.PYR_BASE"):
        await s.wr(f"{reg}.LO", base & 0xFFFFFFFF)
        await s.wr(f"{reg}.HI", base >> 32)
    await s.wr("PYR.DIRTY0", R("PYR.DIRTY0").value(x0=x0, y0=y0))
    await s.wr("PYR.DIRTY1", R("PYR.DIRTY1").value(x1=x1, y1=y1))
    for k, off in enumerate(pyr.level_offsets()):
        await s.wr(f"PYR.LEVEL_OFF[{k}]", off)
    await s.wr("INTR_STATE", R("INTR_STATE").value(frame_done=1, axi_error=1, pyr_done=1))
    await s.wr("INTR_ENABLE", R("INTR_ENABLE").value(frame_done=1, axi_error=1, pyr_done=1))


async def pyr_build(s: Sys, pyr: heightmap.Pyramid, base: int, log,
                    rect: tuple[int, int, int, int] | None = None
                    ) -> tuple[int, dict[str, int], dict[str, int], dict[str, int]]:
    """Program, CTRL.pyr_start, wait for the interrupt: (clocks, INTR_STATE, ERROR, STATUS)."""
    await pyr_program(s, pyr, base, rect)
    t0 = cocotb.utils.get_sim_time("ns")
    await s.wr("CTRL", R("CTRL").value(pyr_start=1))
    await s.wait_irq(40 * pyr.size * pyr.size + 5000)
    clocks = int((cocotb.utils.get_sim_time("ns") - t0) / 10)
    await s.wait_idle()
    intr = await s.ack()
    err = R("ERROR").fields_of(await s.rd("ERROR"))
    status = await s.rd_fields("STATUS")
    log.info("pyramid %dx%d rect %s: %d clocks, INTR %s, STATUS %s", pyr.width, pyr.height,
             rect, clocks, intr, status)
    return clocks, intr, err, status


def image_diff(s: Sys, pyr: heightmap.Pyramid, base: int) -> int:
    """Bytes of the pyramid image in memory that differ from the model's."""
    want = np.frombuffer(pyr.memory_image(), dtype=np.uint8)
    got = np.frombuffer(bytes(s.f.read(base, len(want))), dtype=np.uint8)
    return int((got != want).sum())


def spoil_levels(s: Sys, pyr: heightmap.Pyramid, base: int, rng: random.Random) -> None:
    """Random bytes over the codes of levels 1..n in the image (the builder must overwrite them
    all; it does not write the padding between a level's end and the next 64-byte offset)."""
    bpt = pyr.bits // 8
    for k, off in enumerate(pyr.level_offsets()[1:], start=1):
        side = pyr.size >> k
        s.f.write(base + off, bytes(rng.randrange(256) for _ in range(side * side * bpt)))


NO_ERR = {"pyr_done": 1, "axi_error": 0, "frame_done": 0}
ERR_INTR = {"pyr_done": 1, "axi_error": 1, "frame_done": 0}


@cocotb.test()
async def pidm_top_pyramid(dut):
    """The pyramid builder through the registers: full and dirty builds against the model,
    frames rendered from the built pyramid, AXI errors, refused starts, bad configurations."""
    rng = random.Random(seed() + 2)
    s = Sys(dut, rng)
    await s.reset()
    log = dut._log
    info = await s.rd_fields("PYR.INFO")
    assert info == {"present": 1, "max_lg": 10}, f"PYR.INFO {info}"
    assert R("VERSION").fields_of(await s.rd("VERSION")) == {"minor": 2, "major": 1}
    sc = Scene(CLEAN)
    pyr = sc.frame.pyr
    hreg = sc.packed.region("heights")
    base = hreg.base
    assert hreg.data == pyr.memory_image(), "the frame's height region is not the model's image"
    # 1. full build over garbage, then a frame from the built pyramid
    s.load(sc.packed)
    spoil_levels(s, pyr, base, rng)
    s.traffic(0.3, (1, 20), 0.1)
    assert image_diff(s, pyr, base) > 0
    clocks, intr, err, status = await pyr_build(s, pyr, base, log)
    bad = image_diff(s, pyr, base)
    assert intr == NO_ERR and not any(err.values()), f"INTR {intr}, ERROR {err}"
    assert status["pyr_done"] == 1 and status["pyr_err_code"] == 0 and status["pyr_busy"] == 0
    assert bad == 0, f"full build: {bad} bytes of the pyramid image differ from the model"
    assert not s.outside(), f"accesses outside the regions: {s.outside()[:4]}"
    report.record("pidm_top", "pyramid image (full build) vs model.heightmap",
                  len(pyr.memory_image()), bad)
    await full_frame(s, sc, log, keep_heights=True)
    # 2. a rectangle of level 0 changes: dirty rebuild, then a frame without soft reset
    codes = pyr.levels[0][:pyr.height, :pyr.width].astype(np.int64).copy()
    for trial in range(2):
        w, h = pyr.width, pyr.height
        x0, y0 = rng.randrange(w), rng.randrange(h)
        x1, y1 = rng.randrange(x0, min(w, x0 + 12)), rng.randrange(y0, min(h, y0 + 12))
        codes[y0:y1 + 1, x0:x1 + 1] = [[rng.choice((0, 255, rng.randrange(256)))
                                       for _ in range(x1 - x0 + 1)] for _ in range(y1 - y0 + 1)]
        nsc = PyrScene(CLEAN, codes)
        npyr = nsc.frame.pyr
        assert nsc.packed.region("heights").base == base
        s.f.write(base, level0_bytes(npyr))
        clocks, intr, err, status = await pyr_build(s, npyr, base, log, (x0, y0, x1, y1))
        bad = image_diff(s, npyr, base)
        assert intr == NO_ERR and not any(err.values()), f"INTR {intr}, ERROR {err}"
        assert bad == 0, f"dirty build ({x0},{y0})-({x1},{y1}): {bad} bytes differ from the model"
        report.record("pidm_top", "pyramid image (dirty build) vs model.heightmap",
                      len(npyr.memory_image()), bad)
        pyr = npyr
    await full_frame(s, nsc, log, keep_heights=True)   # no soft reset since the last frame
    # 3. SLVERR on the build's writes (a level) and on its reads (level 0)
    offs = pyr.level_offsets()
    for port, flag, code, (lo, hi) in (("w", "pyr_write", 2, (base + offs[1], base + offs[2])),
                                       ("h", "pyr_read", 1, (base, base + offs[1] // 2))):
        spoil_levels(s, pyr, base, rng)
        mem = getattr(s, port)
        words0 = mem.err_words
        mem.err_ranges = [(lo, hi)]
        clocks, intr, err, status = await pyr_build(s, pyr, base, log)
        mem.err_ranges = []
        assert mem.err_words > words0, f"SLVERR on {port}: the range was never accessed"
        assert intr == ERR_INTR, f"SLVERR on {port}: INTR {intr}"
        assert err == {**{k: 0 for k in err}, flag: 1}, f"SLVERR on {port}: ERROR {err}"
        assert status["pyr_err_code"] == code and status["pyr_busy"] == 0, f"STATUS {status}"
        await s.wr("ERROR", (1 << 32) - 1)
        clocks, intr, err, status = await pyr_build(s, pyr, base, log)
        bad = image_diff(s, pyr, base)
        assert intr == NO_ERR and not any(err.values()) and status["pyr_err_code"] == 0
        assert bad == 0, f"the build after SLVERR on {port}: {bad} bytes differ"
    # 4. starts refused while the other side is busy
    spoil_levels(s, pyr, base, rng)
    s.load(nsc.packed, keep=("heights",))
    await s.program(nsc.packed)
    await pyr_program(s, pyr, base)
    await s.wr("CTRL", R("CTRL").value(pyr_start=1))
    await s.start(nsc.packed)                        # a frame start during the build
    await s.wait_irq(40 * pyr.size * pyr.size + 5000)
    await s.wait_idle()
    intr = await s.ack()
    err = R("ERROR").fields_of(await s.rd("ERROR"))
    status = await s.rd_fields("STATUS")
    assert err == {**{k: 0 for k in err}, "start_refused": 1}, f"frame start in a build: {err}"
    assert intr["axi_error"] == 1 and intr["frame_done"] == 0, f"INTR {intr}"
    if not intr["pyr_done"]:                          # the refusal's interrupt came first
        await s.wait_irq(40 * pyr.size * pyr.size + 5000)
        intr = await s.ack()
        assert intr["pyr_done"] == 1, f"INTR {intr}"
    await s.wait_idle()
    assert (await s.rd_fields("STATUS"))["pyr_done"] == 1
    assert (nsc.words(s, "framebuffer") == nsc.init_words("framebuffer")).all(), \
        "a frame started during the build"
    assert image_diff(s, pyr, base) == 0, "the build with a refused frame start is not exact"
    await s.wr("ERROR", (1 << 32) - 1)
    # a build start during a frame: refused, the frame exact
    s.load(nsc.packed, keep=("heights",))
    s.traffic(0.3, (1, 20), 0.1)
    await s.program(nsc.packed)
    await s.start(nsc.packed)
    await s.wr("CTRL", R("CTRL").value(pyr_start=1))
    err = R("ERROR").fields_of(await s.rd("ERROR"))
    assert err == {**{k: 0 for k in err}, "start_refused": 1}, f"build start in a frame: {err}"
    await s.wait_idle(20 * nsc.n + 5000)
    await s.ack()
    bad = sum(int((nsc.words(s, r) != nsc.exp_words(r)).sum()) for r in nsc.exp)
    assert bad == 0, f"the frame with a refused build start: {bad} words differ"
    assert (await s.rd_fields("STATUS"))["pyr_done"] == 1
    await s.wr("ERROR", (1 << 32) - 1)
    # 5. bad configurations: a size beyond 2^PYR_MAX_LG (refused by pidm_top: no build, no
    # pyr_done) and an unaligned pyramid base (refused by pyr_build: pyr_done, err_code[2])
    await pyr_program(s, pyr, base)
    await s.wr("PYR.SIZE", R("PYR.SIZE").value(width=2048, height=4))
    await s.wr("CTRL", R("CTRL").value(pyr_start=1))
    await ClockCycles(dut.clk_i, 10)
    intr = await s.ack()
    err = R("ERROR").fields_of(await s.rd("ERROR"))
    status = await s.rd_fields("STATUS")
    assert intr == {"pyr_done": 0, "axi_error": 1, "frame_done": 0}, f"INTR {intr}"
    assert err == {**{k: 0 for k in err}, "pyr_config": 1} and status["pyr_busy"] == 0
    await s.wr("ERROR", (1 << 32) - 1)
    spoil_levels(s, pyr, base, rng)
    before = bytes(s.f.read(base, len(pyr.memory_image())))
    await pyr_program(s, pyr, base + 4)
    await s.wr("CTRL", R("CTRL").value(pyr_start=1))
    await s.wait_irq(200)
    await s.wait_idle()
    intr = await s.ack()
    err = R("ERROR").fields_of(await s.rd("ERROR"))
    status = await s.rd_fields("STATUS")
    assert intr == ERR_INTR, f"unaligned base: INTR {intr}"
    assert err == {**{k: 0 for k in err}, "pyr_config": 1} and status["pyr_err_code"] == 4, \
        f"unaligned base: ERROR {err}, STATUS {status}"
    assert bytes(s.f.read(base, len(before))) == before, "a refused build wrote memory"
    await s.wr("ERROR", (1 << 32) - 1)
    # the next build exact
    clocks, intr, err, status = await pyr_build(s, pyr, base, log)
    assert intr == NO_ERR and image_diff(s, pyr, base) == 0
    print("PIDM_TOP pyramid: a full and 2 dirty builds exact, frames from the built pyramids "
          "exact, SLVERR on the build's writes and reads, 2 refused starts, 2 bad "
          "configurations; every following build and frame exact")


NO_BUILDER = os.environ.get("PIDM_NO_BUILDER") == "1"


@cocotb.test(skip=not NO_BUILDER)
async def pidm_top_no_builder(dut):
    """PYR_BUILD = 0: a pyramid start is refused with ERROR.pyr_config; frames work."""
    rng = random.Random(seed() + 3)
    s = Sys(dut, rng)
    await s.reset()
    info = await s.rd_fields("PYR.INFO")
    assert info == {"present": 0, "max_lg": 10}, f"PYR.INFO {info}"
    sc = Scene(CLEAN)
    s.load(sc.packed)
    await pyr_program(s, sc.frame.pyr, sc.packed.region("heights").base)
    await s.wr("CTRL", R("CTRL").value(pyr_start=1))
    await ClockCycles(dut.clk_i, 10)
    intr = await s.ack()
    err = R("ERROR").fields_of(await s.rd("ERROR"))
    status = await s.rd_fields("STATUS")
    assert intr == {"frame_done": 0, "axi_error": 1, "pyr_done": 0}, f"INTR {intr}"
    assert err == {**{k: 0 for k in err}, "pyr_config": 1}, f"ERROR {err}"
    assert status["pyr_busy"] == 0 and status["pyr_done"] == 0 and status["busy"] == 0
    await s.wr("ERROR", (1 << 32) - 1)
    await full_frame(s, sc, dut._log)
    print("PIDM_TOP no builder: pyramid start refused (pyr_config), the frame exact")


def test_pidm_top() -> None:
    runner.run("pidm_top", "test_pidm_top", HERE, opt=runner.LARGE_MODEL_OPT)


@pytest.mark.skipif(not runner.long_stimulus(), reason="a second pidm_top build: TB_LONG=1")
def test_pidm_top_no_builder() -> None:
    runner.run("pidm_top", "test_pidm_top", HERE, parameters={"PYR_BUILD": 0},
               opt=runner.LARGE_MODEL_OPT,
               extra_env={"PIDM_NO_BUILDER": "1"}, testcase="pidm_top_no_builder")
