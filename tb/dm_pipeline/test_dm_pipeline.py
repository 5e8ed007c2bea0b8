# SPDX-License-Identifier: Apache-2.0
"""dm_pipeline (fragments -> colours: view unit, traversal + height cache, MIP levels, texture
addresses, texture cache, filter, shading) against model.shade.render_pixels with the f24 engine.

Small scenes through the whole unit with cocotbext-axi RAMs on both AXI ports (random burst
latency and channel pauses), random gaps in the fragment stream and random back-pressure on the
pixel stream: every pixel's rgb, hit, invalid and iteration count must equal the model's, every
pixel id must come back exactly once, and the unit must be idle afterwards.  Resets in the middle
of frames: silent, idle and zeroed afterwards, the next frame exact.
"""
from __future__ import annotations

import logging
import os
import random
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge
from cocotbext.axi import AxiRamRead, AxiReadBus

from model import camera, heightmap, scenes, shade, texture
from tb.harness import pipeline_words
from tb.common import report, runner
from tb.common.tables import write_table

HERE = Path(__file__).resolve().parent


def seed() -> int:
    s = int(os.environ.get("SEED", random.randrange(1 << 31)))
    print(f"dm_pipeline: SEED={s}")
    return s


def pauses(rng: random.Random, p: float):
    while True:
        yield rng.random() < p


class LatencyRam(AxiRamRead):
    """AxiRamRead with a random latency before the first beat of every burst."""

    def __init__(self, *args, rng: random.Random, line_bytes: int, **kwargs):
        super().__init__(*args, **kwargs)
        self.rng = rng
        self.lat = (0, 0)
        self.line_bytes = line_bytes

    async def _read(self, address, length):
        if address % self.line_bytes == 0 and self.lat[1] > 0:
            n = self.rng.randint(*self.lat)
            if n:
                await ClockCycles(self.clock, n)
        return await super()._read(address, length)


def frame_for(name: str, size: int, angle: str, image: int, method: str, mip: bool
              ) -> tuple[shade.Frame, shade.PixelInputs]:
    sc = scenes.load_scene(name, size)
    pyr = heightmap.build(sc.heights)
    tex = texture.build(sc.texture)
    ntex = texture.build(scenes.encode_normals(sc.normals))
    cam = camera.Camera.for_view(angle, size, size, image, image, depth_scale=sc.depth_scale)
    frame = shade.Frame(pyr=pyr, colour=tex, normals=ntex, depth_scale=sc.depth_scale,
                        log2pb_colour=cam.log2_pb(tex.width, tex.height),
                        log2pb_normal=cam.log2_pb(ntex.width, ntex.height),
                        method=method, engine="f24", mip=mip)
    _, inp = shade.pixel_inputs(cam)
    return frame, inp


CASES = [
    # scene, map size, view, image side, method, MIP on, fragment valid p, pixel ready p, latency
    ("bump", 32, "oblique", 20, "park", True, 0.9, 0.8, (0, 20)),
    ("rocks", 32, "grazing", 24, "park-xor", True, 0.6, 0.5, (5, 60)),
    ("four-shapes", 32, "front", 16, "oh", False, 1.0, 1.0, (20, 20)),
    # pixels taken 1 clock in 10: the out FIFO fills and its credit must hold the hits back
    ("bump", 32, "front", 16, "park", True, 1.0, 0.1, (0, 20)),
]


STATS = ("cycles", "pixels", "iters", "h_hits", "h_misses", "h_bytes", "t_requests",
         "t_quad_hits", "t_line_misses", "t_texel_hits", "t_bytes")


async def start(dut, rng: random.Random) -> tuple[LatencyRam, LatencyRam]:
    """Clock, the two AXI RAMs (never reset: the memory holds every frame), a reset."""
    clk = dut.clk_i
    cocotb.start_soon(Clock(clk, 10, unit="ns").start())
    hram = LatencyRam(AxiReadBus.from_prefix(dut, "m_axi_h"), clk, reset=None, rng=rng,
                      line_bytes=32, size=1 << 32)
    tram = LatencyRam(AxiReadBus.from_prefix(dut, "m_axi_t"), clk, reset=None, rng=rng,
                      line_bytes=32, size=1 << 32)
    for r in (hram, tram):
        r.log.setLevel(logging.ERROR)
    dut.rst_ni.value = 0
    dut.frag_valid_i.value = 0
    dut.px_ready_i.value = 0
    dut.tt_we_i.value = 0
    dut.lvt_we_i.value = 0
    dut.clr_stats_i.value = 0
    await ClockCycles(clk, 4)
    await FallingEdge(clk)
    dut.rst_ni.value = 1
    return hram, tram


async def load_frame(dut, rng: random.Random, hram: LatencyRam, tram: LatencyRam, ci: int,
                     case: tuple) -> tuple[shade.Frame, shade.PixelInputs]:
    """Frame ``case`` (a CASES row) at fresh addresses (index ci: the caches are not flushed
    between frames), the configuration ports and the triangle table written, settled."""
    clk = dut.clk_i
    name, size, angle, image, method, mip_on, vp, rp, lat = case
    frame, inp = frame_for(name, size, angle, image, method, mip_on)
    off = ci << 24
    cfg = pipeline_words.config(frame, pipeline_words.HEIGHT_BASE + off,
                                pipeline_words.COLOUR_BASE + off, pipeline_words.NORMAL_BASE + off)
    hram.write(cfg.height[0], cfg.height[1])
    for base, img in cfg.textures:
        tram.write(base, img)
    hram.lat = tram.lat = lat
    for r in (hram, tram):
        r.ar_channel.set_pause_generator(pauses(rng, 0.2))
        r.r_channel.set_pause_generator(pauses(rng, 0.2))
    await FallingEdge(clk)
    for port, val in cfg.ports.items():
        getattr(dut, port).value = val
    await write_table(dut, clk, "tt", cfg.tri_writes)
    await write_table(dut, clk, "lvt", cfg.lvt_writes)
    await ClockCycles(clk, 140)   # configuration settles; the free list fills after reset
    await FallingEdge(clk)
    return frame, inp


async def stream(dut, rng: random.Random, name: str, inp: shade.PixelInputs, vp: float,
                 rp: float, stop: int | None = None) -> tuple[dict[int, tuple], int, int]:
    """Fragments in (id = index, valid with probability vp), pixels out (ready with
    probability rp) until every pixel is back, or for ``stop`` clocks; (pixels by id, clocks,
    fragments sent)."""
    clk = dut.clk_i
    words = pipeline_words.fragment_words(inp)
    n = len(inp.u0)
    got: dict[int, tuple] = {}
    nxt, presenting, cyc = 0, False, 0
    while len(got) < n and (stop is None or cyc < stop):
        cyc += 1
        if cyc >= 400 * n + 20000:
            state = {k: int(getattr(dut, k).value) for k in (
                "live_q", "vc_cnt_q", "req_cnt_q", "hit_cnt_q", "init_q", "rq_sel_q",
                "rq_c_empty", "rq_n_empty", "tc_req_ready", "miss_empty", "out_empty",
                "o_valid_q", "t_idle", "f0_empty", "res_valid", "res_ready", "res_hit")}
            raise AssertionError(f"{name}: timeout, {len(got)} of {n} pixels; {state}")
        # At a falling edge: the outputs hold until the next rising edge and do not depend
        # on this clock's inputs (frag_ready_o on frag_valid_i, px_valid_o on px_ready_i),
        # so both handshakes of that edge are known as the inputs are written.
        if not presenting and nxt < n and rng.random() < vp:
            for k, arr in words.items():
                getattr(dut, k).value = int(arr[nxt])
            presenting = True
        dut.frag_valid_i.value = int(presenting)
        if presenting and int(dut.frag_ready_o.value):
            nxt += 1
            presenting = False
        ready = rng.random() < rp
        dut.px_ready_i.value = int(ready)
        if ready and int(dut.px_valid_o.value):
            pid = int(dut.px_id_o.value)
            assert pid not in got, f"{name}: pixel {pid} returned twice"
            rgb = int(dut.px_rgb_o.value)
            got[pid] = ((rgb & 255, (rgb >> 8) & 255, (rgb >> 16) & 255),
                        int(dut.px_hit_o.value), int(dut.px_invalid_o.value),
                        int(dut.px_iters_o.value), int(dut.px_err_o.value))
        await FallingEdge(clk)
    dut.frag_valid_i.value = 0
    return got, cyc, nxt


async def whole_frame(dut, rng: random.Random, frame: shade.Frame, inp: shade.PixelInputs,
                      case: tuple) -> int:
    """One frame through the unit; every pixel against model.shade.render_pixels; pixels."""
    clk = dut.clk_i
    name, _, angle, _, method, mip_on, vp, rp, _ = case
    ref = shade.render_pixels(frame, inp)
    n = len(inp.u0)
    got, cyc, _ = await stream(dut, rng, name, inp, vp, rp)
    dut.px_ready_i.value = 1
    await ClockCycles(clk, 200)
    await FallingEdge(clk)
    assert int(dut.px_valid_o.value) == 0, f"{name}: an extra pixel"
    assert int(dut.idle_o.value) == 1, f"{name}: not idle after the frame"
    bad = []
    for i in range(n):
        rgb, hit, inv, iters, err = got[i]
        want = (tuple(int(c) for c in ref.rgb[i]), int(ref.hit[i]), int(ref.invalid[i]),
                int(ref.iterations[i]), 0)
        if (rgb, hit, inv, iters, err) != want:
            bad.append((i, (rgb, hit, inv, iters, err), want))
    msg = (f"{name} {angle} {method} mip={int(mip_on)}: {n} pixels, {int(ref.hit.sum())} hits, "
           f"{cyc} clocks, {len(bad)} mismatches")
    dut._log.info(msg)
    print(msg)
    report.record("dm_pipeline", "pixels vs model.shade f24", n, len(bad))
    assert not bad, f"{name}: first mismatches (pixel, rtl, model): {bad[:5]}"
    return n


@cocotb.test()
async def pipeline_bit_exact(dut):
    rng = random.Random(seed())
    hram, tram = await start(dut, rng)
    total = 0
    for ci, case in enumerate(CASES):
        frame, inp = await load_frame(dut, rng, hram, tram, ci, case)
        assert int(dut.idle_o.value) == 1
        total += await whole_frame(dut, rng, frame, inp, case)
    dut._log.info("VECTORS dm_pipeline: %d pixels, 0 mismatches", total)


@cocotb.test()
async def pipeline_reset_mid_frame(dut):
    """Resets of 1 to 5 clocks in the middle of frames (fragments in every unit, height and
    texture reads outstanding, pixels held by back-pressure): afterwards no pixel comes out
    (the beats of the old reads still arrive and must be dropped), the unit is idle once its
    free list has refilled, every counter is zero, and the next frame is exact."""
    rng = random.Random(seed() + 1)
    hram, tram = await start(dut, rng)
    clk = dut.clk_i
    cut = ("rocks", 32, "grazing", 24, "park", True, 0.9, 0.3, (5, 60))
    after = ("bump", 32, "oblique", 20, "park-xor", True, 0.9, 0.8, (0, 40))
    in_flight = []
    total = 0
    for trial in range(3):
        frame, inp = await load_frame(dut, rng, hram, tram, 2 * trial, cut)
        got, _, sent = await stream(dut, rng, cut[0], inp, cut[6], cut[7],
                                    stop=rng.randint(60, 600))
        in_flight.append(sent - len(got))
        dut.rst_ni.value = 0
        dut.px_ready_i.value = 1
        await ClockCycles(clk, rng.randint(1, 5))
        await FallingEdge(clk)
        dut.rst_ni.value = 1
        for c in range(400):          # the free list refills; stale R beats arrive meanwhile
            await FallingEdge(clk)
            assert int(dut.px_valid_o.value) == 0, f"trial {trial}: a pixel {c} clocks after reset"
        assert int(dut.idle_o.value) == 1, f"trial {trial}: not idle 400 clocks after reset"
        st = {k: int(getattr(dut, f"stat_{k}_o").value) for k in STATS}
        assert all(v == 0 for v in st.values()), f"trial {trial}: counters after reset {st}"
        dut.px_ready_i.value = 0
        frame, inp = await load_frame(dut, rng, hram, tram, 2 * trial + 1, after)
        total += await whole_frame(dut, rng, frame, inp, after)
    assert max(in_flight) > 0, f"no reset hit fragments in flight: {in_flight}"
    msg = (f"dm_pipeline reset mid-frame: 3 resets with {in_flight} fragments in flight; idle, "
           f"zeroed and silent after each, the next frames exact ({total} pixels)")
    dut._log.info(msg)
    print(msg)


@pytest.mark.skipif(not runner.long_stimulus(),
                    reason="one ring: make test-long (TB_LONG=1); make test runs two rings here, "
                           "one ring in tests/test_rtl_pipeline.py and tb/pidm_top")
def test_dm_pipeline():
    # runner.LARGE_MODEL_OPT: the whole pipeline is one 12 MB model function, which GCC takes
    # about 110 s over at -O1.
    # OUT_DEPTH below SLOTS: the out FIFO's credit binds under pixel back-pressure (with
    # OUT_DEPTH >= SLOTS it never could, and admitting hits without it went unnoticed).
    runner.run("dm_pipeline", "test_dm_pipeline", HERE, parameters={"SLOTS": 32, "OUT_DEPTH": 16},
               opt=runner.LARGE_MODEL_OPT)


def test_dm_pipeline_two_rings():
    """Every frame and the resets in the middle of frames with two traverse rings (N_RINGS 2:
    rays dealt to two traverse systems, each with its own height cache, their reads merged onto
    the one height port).  The one-ring build of these tests (test_dm_pipeline) runs under
    ``make test-long`` only, to bound ``make test``'s time (a build of the pipeline is most of a
    run): with one ring the pipeline is checked in make test by the harness's frames
    (tests/test_rtl_pipeline.py, random AXI latency, the RTL's assertions on) and inside the
    system top (tb/pidm_top, cocotbext-axi memories)."""
    runner.run("dm_pipeline", "test_dm_pipeline", HERE,
               parameters={"SLOTS": 32, "OUT_DEPTH": 16, "N_RINGS": 2, "H_SETS": 128},
               opt=runner.LARGE_MODEL_OPT)
