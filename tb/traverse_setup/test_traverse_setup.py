# SPDX-License-Identifier: Apache-2.0
"""traverse_setup against the first mode of model.traverse._trace (setup, t0, locate, start_node),
bit for bit, at the float units' depths (ADD_LAT, MUL_LAT) of tb/common/depths.py: the package
defaults (3, 2), and under make test-long the paper's (2, 1).

Harness (tb_traverse_setup.sv): traverse_setup alone, its configuration from a method code and a
map's size, root level and root code.  For every map (1x1 .. 100x128, unorm8 and unorm16, rough /
flat / spiky heights: the root code sets the clip policy's start time) and the methods that set
its two policies (oh: neither; park: start level; park-xor: start level and clip), random and
adversarial rays (tb.common.traverse_stimulus: texel edges and corners, axis-parallel, vertical,
grazing, NaN / Inf and outside starts) enter whenever in_ready_o allows, with random gaps.  Every
ray must come out once, exactly setup_lat(ADD_LAT, MUL_LAT) clocks after it entered (the
package's function, mirrored here and checked against traverse_pkg::SETUP_LAT at the package's
defaults), with busy_o = the rays inside, and its record must be the model's: u0, v0, t (= t0),
done and invalid for every ray; du, dv, 1/du, 1/dv, the directions, t_map, the start level and
the start cell for every valid ray (the fields an invalid ray's record leaves undefined are
not compared); the loop's state fields zero.

Environment: SEED, SETUP_RAYS (rays per map and method, default 200), WAVES=1; ADD_LAT and
MUL_LAT are set by the pytest function for the build it runs.
"""
from __future__ import annotations

import os
import random
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge

from model import f24, heightmap, traverse
from model.arith import ENGINES
from model.rays import Rays
from tb.common import depths, report, runner
from tb.common.traverse_stimulus import adversarial_rays, height_field
from tb.harness import sv_params, traverse_words

HERE = Path(__file__).resolve().parent

#: (height, width, unorm bits, height-field kind)
MAPS = [(1, 1, 8, 0), (2, 2, 8, 1), (7, 5, 16, 0), (16, 16, 8, 2), (37, 61, 8, 0),
        (17, 64, 16, 1), (64, 64, 16, 1), (100, 128, 16, 2)]
#: Methods that cover the first mode's policies: neither, start level, start level + clip.
METHODS = ("oh", "park", "park-xor")
FIELDS = ("u0", "v0", "du", "dv", "inv_du", "inv_dv", "sx", "sy", "t_map", "k", "cx", "cy", "t",
          "done", "invalid", "rest")


def setup_lat(add_lat: int, mul_lat: int) -> int:
    """traverse_pkg::setup_lat: the divider, then the first mode's stages, whose shared units'
    second operations start setup_gap stages after their first (add_lat + mul_lat + 3 rounded up
    to 2 mod 4)."""
    n = add_lat + mul_lat + 3
    gap = n + (6 - n % 4) % 4
    return sv_params.value("f24_pkg", "F24_DIV_LAT") + mul_lat + 6 + gap


def seed() -> int:
    s = int(os.environ.get("SEED", random.randrange(1 << 31)))
    cocotb.log.info("SEED=%d", s)
    return s


def expected(pyr: heightmap.Pyramid, rays: Rays, method: str) -> dict[str, np.ndarray]:
    """The record the first mode of model.traverse._trace (f24 engine) gives each ray, as unit
    words; ``valid`` marks the rays whose per-ray constants and start node are defined."""
    ar = ENGINES["f24"]
    m = traverse.METHODS[method]
    nr = len(rays.u0)
    with np.errstate(all="ignore"):
        invalid, S = traverse.setup(pyr, rays, ar)
        vidx = np.nonzero(~invalid)[0]
        nv = len(vidx)
        one1 = np.ones(1)
        t0_1 = np.zeros(1)
        if m.clip:
            h_root = ar.from_unorm(np.array([pyr.levels[pyr.n][0, 0]]), pyr.bits)
            t0_1 = np.maximum(t0_1, ar.sub(one1, h_root))
        t0 = np.broadcast_to(t0_1, (nv,))
        one = np.ones(nv)
        zero_i = np.zeros(nv, dtype=np.int64)
        gone = S.t_map <= t0
        lo0, hi0 = zero_i, zero_i + (pyr.size - 1)
        c0x = traverse.locate(ar, S.u0, S.du, S.inv_du, S.sx, t0, zero_i, lo0 - 1, hi0 + 1)
        c0y = traverse.locate(ar, S.v0, S.dv, S.inv_dv, S.sy, t0, zero_i, lo0 - 1, hi0 + 1)
        ex = ey = None
        if m.start_level:
            t_end = np.minimum(one, S.t_map) if m.clip else one
            ex = ar.to_index(np.where(S.sx != 0, traverse.position(ar, S.u0, S.du, t_end), S.u0))
            ey = ar.to_index(np.where(S.sy != 0, traverse.position(ar, S.v0, S.dv, t_end), S.v0))
        outside, k, cx, cy = traverse.start_node(c0x, c0y, ex, ey, pyr.width, pyr.height, pyr.n,
                                                 m.start_level)
    u0w, v0w, _, _ = traverse_words.ray_words(rays)
    exp = {name: np.zeros(nr, dtype=np.int64) for name in FIELDS}
    exp["u0"][:], exp["v0"][:] = u0w, v0w
    exp["t"][:] = int(f24.from_float(t0_1)[0])
    exp["invalid"][:] = invalid
    exp["done"][:] = 1
    exp["done"][vidx] = gone | outside
    for name, val in (("du", S.du), ("dv", S.dv), ("inv_du", S.inv_du), ("inv_dv", S.inv_dv),
                      ("t_map", S.t_map)):
        exp[name][vidx] = f24.from_float(val)
    # directions {mv, neg}: neg (du's sign) is compared only where the axis moves
    exp["sx"][vidx] = np.where(S.sx != 0, 2 + (S.sx < 0), 0)
    exp["sy"][vidx] = np.where(S.sy != 0, 2 + (S.sy < 0), 0)
    exp["k"][vidx], exp["cx"][vidx], exp["cy"][vidx] = k, cx & 0xFFFF, cy & 0xFFFF
    exp["valid"] = ~invalid
    return exp


def compare(name: str, got: dict[int, dict[str, int]], exp: dict[str, np.ndarray], log) -> int:
    """Mismatching rays (the first ten logged)."""
    bad = []
    for i in range(len(exp["u0"])):
        if i not in got:
            bad.append(f"ray {i}: no record")
            continue
        g = got[i]
        fields = FIELDS if exp["valid"][i] else ("u0", "v0", "t", "done", "invalid", "rest")
        why = []
        for f in fields:
            gv, ev = g[f], int(exp[f][i])
            if f in ("sx", "sy") and not ev & 2:
                gv &= 2           # no motion on the axis: its sign bit is not part of the record
            if gv != ev:
                why.append(f"{f} 0x{gv:x} != 0x{ev:x}")
        if why:
            bad.append(f"ray {i}: " + ", ".join(why))
    for b in bad[:10]:
        log.error("%s: %s", name, b)
    return len(bad)


class Harness:
    def __init__(self, dut, lat: int):
        self.dut = dut
        self.clk = dut.clk_i
        self.lat = lat

    async def reset(self) -> None:
        d = self.dut
        cocotb.start_soon(Clock(self.clk, 10, unit="ns").start())
        d.rst_ni.value = 0
        d.in_valid_i.value = 0
        d.idle_i.value = 1
        await ClockCycles(self.clk, 4)
        await FallingEdge(self.clk)
        d.rst_ni.value = 1

    async def configure(self, cfg: traverse_words.Config, idle_clocks: int) -> None:
        """Set the configuration while idle and stay idle ``idle_clocks`` (the start time)."""
        d = self.dut
        await FallingEdge(self.clk)
        d.idle_i.value = 1
        d.cfg_method_i.value = cfg.method
        d.cfg_width_i.value = cfg.width
        d.cfg_height_i.value = cfg.height
        d.cfg_root_level_i.value = cfg.root_level
        d.cfg_bits16_i.value = cfg.bits16
        d.cfg_root_code_i.value = cfg.root_code
        await ClockCycles(self.clk, idle_clocks)
        await FallingEdge(self.clk)

    async def run(self, words, rng: np.random.Generator, valid_p: float
                  ) -> tuple[dict[int, dict[str, int]], list[str]]:
        """Stream the rays (id = index) in while in_ready_o allows; collect the records.  Returns
        {id: record} and the protocol errors (latency, busy_o, duplicates)."""
        d = self.dut
        u0, v0, du, dv = ([int(x) for x in w] for w in words)
        n = len(u0)
        got: dict[int, dict[str, int]] = {}
        t_in: dict[int, int] = {}
        errs: list[str] = []
        nxt = cyc = 0
        d.idle_i.value = 0
        limit = int(4 * n / valid_p) + 20 * n + 4 * self.lat + 100
        while len(got) < n:
            if cyc > limit:
                errs.append(f"timeout: {len(got)} of {n} records after {cyc} clocks")
                break
            # the state after the last rising edge
            busy = int(d.busy_o.value)
            if busy != len(t_in) - len(got):
                errs.append(f"clock {cyc}: busy_o {busy}, {len(t_in) - len(got)} rays inside")
            if int(d.out_valid_o.value):
                rid = int(d.out_id_o.value)
                if rid in got or rid not in t_in:
                    errs.append(f"clock {cyc}: record of ray {rid} unexpected")
                elif cyc - t_in[rid] != self.lat:
                    errs.append(f"ray {rid}: out {cyc - t_in[rid]} clocks after in, "
                                f"not {self.lat}")
                got[rid] = {f: int(getattr(d, f"out_{f}_o").value) for f in FIELDS}
            fire = nxt < n and int(d.in_ready_o.value) and rng.random() < valid_p
            if fire:
                d.in_id_i.value = nxt
                d.in_u0_i.value = u0[nxt]
                d.in_v0_i.value = v0[nxt]
                d.in_du_i.value = du[nxt]
                d.in_dv_i.value = dv[nxt]
                t_in[nxt] = cyc
                nxt += 1
            d.in_valid_i.value = int(fire)
            await RisingEdge(self.clk)
            cyc += 1
            await FallingEdge(self.clk)
        d.in_valid_i.value = 0
        d.idle_i.value = 1
        return got, errs


@cocotb.test()
async def setup_bit_exact(dut):
    add_lat, mul_lat = depths.current()
    lat = setup_lat(add_lat, mul_lat)
    dut._log.info("ADD_LAT=%d MUL_LAT=%d: SETUP latency %d", add_lat, mul_lat, lat)
    rng = np.random.default_rng(seed())
    nrays = int(os.environ.get("SETUP_RAYS", "200"))
    h = Harness(dut, lat)
    await h.reset()
    total = mism = 0
    failures = []
    for case, (hh, ww, bits, kind) in enumerate(MAPS):
        pyr = heightmap.build(height_field(rng, hh, ww, kind), bits)
        rays = adversarial_rays(rng, ww, hh, nrays)
        words = traverse_words.ray_words(rays)
        for mi, method in enumerate(METHODS):
            # the start time takes 1 + MUL_LAT + ADD_LAT idle clocks (operand registers, [B],
            # [P]), and 3 + ADD_LAT after a change of the configuration (H_root's two
            # registers, the operand register, [P])
            await h.configure(traverse_words.config(pyr, method), 2 + max(mul_lat, 2) + add_lat)
            valid_p = [1.0, 0.6, 0.3][(case + mi) % 3]
            got, errs = await h.run(words, rng, valid_p)
            exp = expected(pyr, rays, method)
            name = f"{hh}x{ww} u{bits} kind{kind} {method} valid_p={valid_p}"
            nbad = compare(name, got, exp, dut._log)
            for e in errs[:10]:
                dut._log.error("%s: %s", name, e)
            ngone = int(np.count_nonzero(exp["done"].astype(bool) & exp["valid"]))
            dut._log.info("%-45s %4d rays (%d invalid, %d done), %d mismatches, %d errors", name,
                          len(rays.u0), int(np.count_nonzero(~exp["valid"])), ngone, nbad,
                          len(errs))
            total += len(rays.u0)
            mism += nbad + len(errs)
            if nbad or errs:
                failures.append(name)
    report.record("traverse_setup", f"ray records vs model f24 (ADD_LAT {add_lat}, MUL_LAT "
                  f"{mul_lat})", total, mism)
    dut._log.info("VECTORS traverse_setup: %d rays, %d mismatches", total, mism)
    assert not failures, f"mismatches in: {failures}"


@cocotb.test()
async def setup_idle_gaps(dut):
    """Rays after idle stretches of 0 .. T0_WAIT + 2 clocks with the clip policy (park-xor) and a
    root below 1 (t0 > 0): the start time must not take the last ray's operations that the
    shared adder and multiplier still deliver in the first idle clocks."""
    add_lat, mul_lat = depths.current()
    lat = setup_lat(add_lat, mul_lat)
    rng = np.random.default_rng(seed())
    h = Harness(dut, lat)
    await h.reset()
    hh, ww, bits = 16, 16, 8
    pyr = heightmap.build(0.6 * rng.random((hh, ww)), bits)  # H_root <= 0.6: t0 >= 0.4
    await h.configure(traverse_words.config(pyr, "park-xor"), 2 + max(mul_lat, 2) + add_lat)
    t0_wait = 1 + mul_lat + add_lat
    total = mism = 0
    for gap in [None] + list(range(t0_wait + 3)):
        # (None: the first batch, after the configuration's wait, leaves ray operations in the
        # units; then each batch after `gap` idle clocks: run() leaves idle_i = 1)
        if gap:
            await ClockCycles(h.clk, gap)
            await FallingEdge(h.clk)
        rays = adversarial_rays(rng, ww, hh, 24)
        got, errs = await h.run(traverse_words.ray_words(rays), rng, 1.0)
        exp = expected(pyr, rays, "park-xor")
        name = "after the configuration" if gap is None else f"after {gap} idle clocks"
        nbad = compare(name, got, exp, dut._log)
        for e in errs[:10]:
            dut._log.error("%s: %s", name, e)
        dut._log.info("%s: %d rays, %d mismatches, %d errors", name, len(rays.u0), nbad,
                      len(errs))
        total += len(rays.u0)
        mism += nbad + len(errs)
    report.record("traverse_setup", f"rays after short idle gaps (ADD_LAT {add_lat}, MUL_LAT "
                  f"{mul_lat})", total, mism)
    assert mism == 0, f"{mism} mismatching rays after short idle gaps"


def test_setup_lat_mirror() -> None:
    """The Python mirror of traverse_pkg::setup_lat: the package's function at both depths, and
    SETUP_LAT at the package defaults."""
    add, mul = sv_params.values("pipe_pkg", "F24_ADD_LAT", "F24_MUL_LAT")
    assert setup_lat(add, mul) == sv_params.value("traverse_pkg", "SETUP_LAT")
    for a, m in depths.PAIRS:
        assert setup_lat(a, m) == sv_params.call("traverse_pkg", "setup_lat", a, m)
    assert setup_lat(2, 1) == sv_params.value("f24_pkg", "F24_DIV_LAT") + 13


@pytest.mark.parametrize("add_lat,mul_lat", depths.cases())
def test_traverse_setup(add_lat: int, mul_lat: int) -> None:
    runner.run("tb_traverse_setup", "test_traverse_setup", HERE,
               parameters=depths.parameters(add_lat, mul_lat),
               extra_env=depths.env(add_lat, mul_lat),
               extra_sources=[str(HERE / "tb_traverse_setup.sv")], rtl_top="traverse_setup")


