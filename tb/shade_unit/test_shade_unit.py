# SPDX-License-Identifier: Apache-2.0
"""shade_unit against model.shade.shade(ENGINES["f24"], ...), all three unorm8 codes bit for bit.

Stimulus, per configuration (the default Material at D = 20.48, then random materials, light
directions and depth scales, and odd ones: negative KD with zero AMBIENT and KS, D = 0, a light
from straight above or from below the surface, AMBIENT > 1):

- directed: normal-map texels with components 0, 0.5 (a zero normal: the EPS path), 1 and the
  unorm8 codes either side of 0.5, against colours 0, 1 and random, and rays du = dv = 0, steep,
  grazing and huge; colours with every component 0 or 1; every special word (signed zeros,
  subnormal patterns, Inf, NaNs, extremes: model.f24_vectors.SPECIALS) in each of the eight input
  words in turn, and in all of them at once; grazing rays of magnitude up to 2^40;
- random: realistic pixels (colours and normals in [0, 1], rays up to several D) and, for one
  tenth, random bit patterns in every input word.

The whole directed set (:func:`directed`, about 4,200 pixels) goes to the default configuration;
in ``make test`` the seven others get its part that meets what tells them apart, the light
direction, AMBIENT, KD, KS and D (``full=False``, about 1,700 pixels): every normal of the cube
against every ray (one of the three colours each, in turn), the 0 / 1 colours, every special word
in the ray words (against D and D^2) with all four base pixels and in the colour and normal words
with two, and a quarter of the all-specials and grazing-ray pixels.  The rest of the cube (each
normal and ray again with the other two colours, the same special words on more base pixels)
exercises the datapath the same way under every configuration; ``make test-long`` (TB_LONG=1)
gives every configuration the whole set.

Pixels stream in with random valid bubbles (random data on the ports while valid_i = 0), a
pixel every 4th enabled clock at most (the unit's float units serve up to four operations), at
that minimum spacing and at random larger ones, so pixels come on every phase modulo 4 (counted
and checked: the unit aligns them to phase 0), and en_i dropped at random (20% or 60% of the
clocks, by configuration); after every clock valid_o, tag_o and rgb_o must be those of the pixel
(or bubble) presented exactly SHADE_LAT enabled clocks earlier, and hold while en_i = 0.  The
pipeline is drained between configurations (the configuration is static while busy).  A reset
with pixels in flight (en_i = 0 during the reset) must clear valid.  The hard-wired constants of
rtl/pipe/shade_pkg.sv are checked against the model's.

Built and run at the depth pairs (ADD_LAT, MUL_LAT) of tb/common/depths.py: the package defaults
(3, 2), and under make test-long the paper's (2, 1); SHADE_LAT is the Python mirror of shade_pkg's schedule (shade_op_stage / shade_lat) at
that pair, so a unit whose latency differs from the mirror fails every pixel check.
test_shade_latency checks the mirror itself: 67 at (2, 1), 90 at (3, 2), and no unit given two
operations of one phase.

Environment: SEED, VECTORS (random pixels, default 10,000; 50,000 with TB_LONG=1), WAVES=1;
SHADE_ADD_LAT, SHADE_MUL_LAT (the depth pair, set by test_shade_unit).
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import cocotb
import pytest
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from model import f24, f24_vectors as vec, shade
from model.arith import ENGINES
from tb.common import depths, fp_unit, report, runner
from tb.harness import sv_params

HERE = Path(__file__).resolve().parent
PKG = runner.RTL / "pipe" / "shade_pkg.sv"
TAG_W = 12
F24 = ENGINES["f24"]
DEFAULT_DEPTH = 20.48  # 8% of a 256-texel map (README "Scenes and views")


def pkg_value(name: str) -> int:
    """A localparam of shade_pkg.sv (decimal or 24'h... literal)."""
    m = re.search(rf"localparam\s+\S+(?:\s+\S+)?\s+{name}\s*=\s*(?:24'h([0-9a-fA-F_]+)|(\d+))\s*;",
                  PKG.read_text())
    assert m, f"{name} not found in {PKG}"
    return int(m.group(1).replace("_", ""), 16) if m.group(1) else int(m.group(2))



# --------------------------------------------------------------------------------------------
# schedule: a mirror of shade_pkg's shade_op_stage / shade_lat (the greedy phase assignment)

#: The shared-unit operations in shade_pkg's priority order: (name, unit, stream).
OPS = [("du2", "uv2hy2", False), ("ny", "nua", False), ("ny2", "ny2h", False),
       ("dv2", "dvnc", False), ("uv", "nua", False), ("vv", "nv", False), ("rv", "rvnh", False),
       ("vy", "ny2h", False), ("vxz", "va", True), ("hxz", "nxh", True), ("hxz2", "hkd", True),
       ("hy", "hd", False), ("hy2", "uv2hy2", False), ("hxy2", "nv", False), ("hh", "nv", False),
       ("rh", "rvnh", False), ("huy", "hunh1", False), ("huxz", "ny2h", True),
       ("nxz", "nc", True), ("nxy2", "nxh", False), ("nn", "nv", False), ("rn", "rvnh", False),
       ("nuxz", "dvnc", True), ("nhxz", "nunh1", True), ("nuy", "nunh1", False),
       ("nhy", "hunh1", False), ("nhxy", "hd", False), ("nly", "hunh1", False),
       ("nlxy", "nxh", False), ("dots", "hd", True), ("kdn", "hkd", False), ("a", "nua", False),
       ("cya", "dvnc", False), ("s2", "sq", False), ("s4", "sq", False), ("s8", "sq", False),
       ("s16", "sq", False), ("caxz", "caa", True), ("sp", "caa", False), ("cg", "nua", False),
       ("crb", "nc", True)]
ADDERS = {"nc", "nua", "nv", "nxh", "hd"}


def schedule(add_lat: int, mul_lat: int, rsqrt_lat: int) -> dict[str, int]:
    """The core stage of every shared-unit operation (shade_pkg.shade_op_stage)."""
    m = mul_lat
    st: dict[str, int] = {}
    rs: dict[str, int] = {}
    used: dict[str, set[int]] = {}

    def ready(op: str) -> int:
        """The stage the operation's last operand is ready in (x of a stream)."""
        r = rs.get
        table = {
            "ny2": lambda: r("ny"), "uv": lambda: max(r("du2"), r("dv2")), "vv": lambda: r("uv"),
            "rv": lambda: r("vv"), "vy": lambda: r("rv"), "vxz": lambda: r("rv"),
            "hxz": lambda: r("vxz"), "hxz2": lambda: r("hxz"), "hy": lambda: r("vy"),
            "hy2": lambda: r("hy"), "hxy2": lambda: max(r("hxz2"), r("hy2")),
            "hh": lambda: max(r("hxy2"), r("hxz2") + 1), "rh": lambda: r("hh"),
            "huy": lambda: max(r("rh"), r("hy")), "huxz": lambda: max(r("rh"), r("hxz")),
            "nxy2": lambda: max(r("nxz") + m, r("ny2")),
            "nn": lambda: max(r("nxy2"), r("nxz") + m + 1), "rn": lambda: r("nn") + 1,
            "nuxz": lambda: max(r("rn"), r("nxz")), "nhxz": lambda: max(r("nuxz"), r("huxz")),
            "nuy": lambda: max(r("rn"), r("ny")), "nhy": lambda: max(r("nuy"), r("huy")),
            "nhxy": lambda: max(r("nhxz"), r("nhy")), "nly": lambda: r("nuy"),
            "nlxy": lambda: max(r("nuxz") + m, r("nly")),
            "dots": lambda: max(r("nlxy"), r("nuxz") + m + 1, r("nhxy") - 1, r("nhxz")),
            "kdn": lambda: r("dots") + 1, "a": lambda: r("kdn"), "cya": lambda: r("a"),
            "caxz": lambda: r("a"), "s2": lambda: r("dots") + 2, "s4": lambda: r("s2"),
            "s8": lambda: r("s4"), "s16": lambda: r("s8"), "sp": lambda: r("s16"),
            "cg": lambda: max(r("cya"), r("sp")), "crb": lambda: max(r("caxz"), r("sp"))}
        return table[op]() if op in table else 0

    for op, unit, stream in OPS:
        e = ready(op)
        ph = used.setdefault(unit, set())
        a = e + 1
        while (a % 4 in ph or (stream and (a + 1) % 4 in ph)) and a < e + 9:
            a += 1
        ph.add(a % 4)
        if stream:
            ph.add((a + 1) % 4)
        st[op] = a
        lat = add_lat if unit in ADDERS else rsqrt_lat if unit == "rvnh" else mul_lat
        rs[op] = a + lat
    return st


def shade_lat(add_lat: int, mul_lat: int) -> int:
    """shade_pkg.shade_lat: the clamp's stage, + 1 + MUL + ADD + floor + 2 (G, B) + 3 (alignment)."""
    rsqrt_lat, idx_lat = sv_params.values("pipe_pkg", "F24_RSQRT_LAT", "F24_TO_INDEX_LAT")
    st = schedule(add_lat, mul_lat, rsqrt_lat)
    c0 = max(st["crb"] + add_lat, st["cg"] + add_lat - 1)
    return c0 + 1 + mul_lat + add_lat + idx_lat + 2 + 3


SHADE_LAT = shade_lat(*depths.current())


# --------------------------------------------------------------------------------------------
# configuration


@dataclass
class Config:
    name: str
    material: shade.Material
    depth: float

    def words(self) -> list[int]:
        """The fields of shade_cfg_t, light_x first: what shade() gets from its const()."""
        m = self.material
        light = f24.from_float(m.light_unit())
        d = f24.from_float(np.float64(self.depth))
        return [int(x) for x in light] + [int(f24.from_float(np.float64(v)))
                                          for v in (m.ambient, m.kd, m.ks)] + \
            [int(d), int(f24.mul(d, d))]

    def packed(self) -> int:
        v = 0
        for w in self.words():
            v = (v << 24) | w
        return v


def configs(rng: np.random.Generator) -> list[Config]:
    out = [Config("default", shade.Material(), DEFAULT_DEPTH)]
    for i in range(4):
        light = tuple(float(x) for x in rng.normal(size=3))
        if i < 2:
            light = (light[0], light[1], abs(light[2]))  # above the surface
        out.append(Config(f"random{i}", shade.Material(
            light=light, ambient=float(rng.uniform(0, 0.5)), kd=float(rng.uniform(0, 1)),
            ks=float(rng.uniform(0, 1))), float(rng.uniform(1, 100))))
    # signed zeros everywhere: a = 0 + KD max(n.l, 0) <= 0, sp = 0
    out.append(Config("odd: light overhead, AMBIENT = KS = 0, KD < 0",
                      shade.Material(light=(0.0, 0.0, 1.0), ambient=0.0, kd=-0.6, ks=0.0),
                      DEFAULT_DEPTH))
    # D = 0: a vertical ray has vv = 0, rv = +Inf, v = NaN
    out.append(Config("odd: D = 0", shade.Material(), 0.0))
    out.append(Config("odd: light below, AMBIENT > 1, KS = 3, D = 1e-3",
                      shade.Material(light=(0.3, -0.2, -1.0), ambient=1.5, kd=2.0, ks=3.0), 1e-3))
    return out


# --------------------------------------------------------------------------------------------
# stimulus: (N, 8) uint32 words: C (3), M (3), du, dv


def words_of(x) -> np.ndarray:
    return f24.from_float(np.asarray(x, dtype=np.float64))


def realistic(rng: np.random.Generator, n: int, depth: float) -> np.ndarray:
    col = words_of(rng.uniform(0, 1, (n, 3)))
    # normal maps: mostly unorm8 / unorm16 codes as the filter would give them, some arbitrary
    nrm = words_of(rng.uniform(0, 1, (n, 3)))
    k8 = rng.random(n) < 0.3
    nrm[k8] = f24.from_unorm(rng.integers(0, 256, (int(k8.sum()), 3)).astype(np.uint32), 8)
    up = rng.random(n) < 0.5  # mostly facing up: z in [0.5, 1]
    nrm[up, 2] = words_of(rng.uniform(0.5, 1, int(up.sum())))
    scale = max(depth, 1.0) * rng.choice([0.05, 1.0, 4.0], n)
    ray = words_of(rng.uniform(-1, 1, (n, 2)) * scale[:, None])
    return np.concatenate([col, nrm, ray], axis=1).astype(np.uint32)


def wild(rng: np.random.Generator, n: int) -> np.ndarray:
    return vec.rand_bits(rng, n * 8).reshape(n, 8)


def directed(rng: np.random.Generator, depth: float, full: bool = True) -> np.ndarray:
    """The directed pixels of the module docstring at depth scale ``depth``: (N, 8) words.

    ``full`` False: the part that meets the configuration (light, AMBIENT, KD, KS, D; the module
    docstring): every (normal, ray) pair of the cube with one colour, the colours in turn; the
    special words in the ray words on all four base pixels, in the other words on two; 100 of
    the 400 all-specials and of the 400 grazing-ray pixels."""
    rows = []
    zero, half, one = 0x000000, 0x3E0000, 0x3F0000
    nvals = [zero, half, one, int(f24.from_unorm(np.uint32(127), 8)),
             int(f24.from_unorm(np.uint32(128), 8))]
    cols = [[zero] * 3, [one] * 3, list(words_of(rng.uniform(0, 1, 3)))]
    d = max(depth, 1.0)
    rays = [(0.0, 0.0), (-0.0, 0.0), (0.3 * d, -0.2 * d), (-40.0 * d, 25.0 * d), (1e6, -1e6),
            (2.0**40, 2.0**40)]
    normals = [[nx, ny, nz] for nx in nvals for ny in nvals for nz in nvals]
    for j, nrm in enumerate(normals):
        for r, (du, dv) in enumerate(rays):
            # not full: the colour of normal j and ray r is colour (j + r) mod 3, so every
            # normal meets every colour over the rays and every ray every colour over the normals
            for c in (cols if full else [cols[(j + r) % len(cols)]]):
                rows.append(c + nrm + [int(words_of(du)), int(words_of(dv))])
    # colours with every component 0 or 1, flat and tilted normals, a few rays
    for bits in range(8):
        c = [one if bits >> i & 1 else zero for i in range(3)]
        for m in ([half, half, one], [0x3E8000, 0x3D0000, 0x3F0000]):
            for du, dv in rays[:4]:
                rows.append(c + m + [int(words_of(du)), int(words_of(dv))])
    base = realistic(rng, 4, depth)
    specials = np.concatenate([vec.SPECIALS, np.array([half, 0x3effff, 0x3e0001], np.uint32)])
    # every special word in each input word in turn (the ray words, du and dv: on every base)
    for slot in range(8):
        for s in specials:
            for b in (base if full or slot >= 6 else base[:2]):
                r = b.copy()
                r[slot] = s
                rows.append(list(r))
    n_odd = 400 if full else 100
    # specials everywhere at once
    rows += [list(r) for r in rng.choice(specials, (n_odd, 8))]
    # grazing rays: |du|, |dv| up to 2^40
    g = realistic(rng, n_odd, depth)
    mag = 2.0 ** rng.uniform(0, 40, (n_odd, 2)) * rng.choice([-1.0, 1.0], (n_odd, 2))
    g[:, 6:8] = words_of(mag)
    rows += [list(r) for r in g]
    return np.array(rows, dtype=np.uint32)


def expected(cfg: Config, x: np.ndarray) -> np.ndarray:
    """model.shade.shade on the f24 engine: (N, 3) uint8."""
    v = f24.to_float(x)
    return shade.shade(F24, v[:, 0:3], v[:, 3:6], v[:, 6], v[:, 7], cfg.depth, cfg.material)


# --------------------------------------------------------------------------------------------
# driver and checker


class Bench:
    def __init__(self, dut, rng: np.random.Generator):
        self.dut = dut
        self.rng = rng
        self.enabled = 0       # enabled edges since the last reset
        self.entries: list[tuple[bool, int, int]] = []  # per enabled edge: valid, tag, rgb
        self.checked = 0
        self.bad: list[str] = []
        self.nbad = 0
        self.phases = [0] * 4    # pixels presented per phase (enabled edges since reset, mod 4)
        self.gaps = [0] * 9      # pixels per spacing from the previous one (4 .. 7, 8 = 8 or more)
        self.last = -100         # the enabled edge of the last pixel
        self.what: dict[int, str] = {}  # tag -> description, for mismatch reports

    async def start(self):
        d = self.dut
        cocotb.start_soon(Clock(d.clk_i, 10, unit="ns").start())
        d.en_i.value = 0
        d.valid_i.value = 0
        d.tag_i.value = 0
        d.col_i.value = 0
        d.nrm_i.value = 0
        d.du_i.value = 0
        d.dv_i.value = 0
        await self.reset()

    async def reset(self):
        """rst_ni low for 3 clocks with en_i = 0: valid must clear anyway."""
        d = self.dut
        await FallingEdge(d.clk_i)
        d.rst_ni.value = 0
        d.en_i.value = 0
        for _ in range(3):
            await RisingEdge(d.clk_i)
        await FallingEdge(d.clk_i)
        d.rst_ni.value = 1
        self.enabled = 0
        self.last = -100
        self.entries = []
        if int(d.valid_o.value) != 0:
            raise AssertionError("valid_o is 1 after reset")

    def check_outputs(self, cyc: int) -> None:
        d = self.dut
        i = self.enabled - SHADE_LAT
        exp_v, exp_tag, exp_rgb = self.entries[i] if i >= 0 else (False, 0, 0)
        v = int(d.valid_o.value)
        if v != int(exp_v):
            raise AssertionError(f"valid_o = {v}, expected {int(exp_v)} (clock {cyc}, enabled "
                                 f"edge {self.enabled})")
        if exp_v:
            tag, rgb = int(d.tag_o.value), int(d.rgb_o.value)
            if tag != exp_tag:
                raise AssertionError(f"tag_o = 0x{tag:x}, expected 0x{exp_tag:x} (clock {cyc})")
            if rgb != exp_rgb:
                self.nbad += 1
                if len(self.bad) < 10:
                    got = [(rgb >> (8 * c)) & 255 for c in range(3)]
                    want = [(exp_rgb >> (8 * c)) & 255 for c in range(3)]
                    self.bad.append(f"{self.what.get(tag, '?')}: got {got} expected {want}")

    async def stream(self, cfg: Config, x: np.ndarray, exp: np.ndarray, en_prob: float = 0.8,
                     valid_prob: float = 0.75) -> int:
        """Present every row of x (with bubbles), then drain; returns the pixels checked."""
        d = self.dut
        rng = self.rng
        d.cfg_i.value = cfg.packed()
        n = len(x)
        col = [(int(r[2]) << 48) | (int(r[1]) << 24) | int(r[0]) for r in x]
        nrm = [(int(r[5]) << 48) | (int(r[4]) << 24) | int(r[3]) for r in x]
        du = [int(v) for v in x[:, 6]]
        dv = [int(v) for v in x[:, 7]]
        rgb = [int(e[0]) | (int(e[1]) << 8) | (int(e[2]) << 16) for e in exp]
        m = 4 * n + 4 * SHADE_LAT + 64
        en_seq = (rng.random(m) < en_prob).tolist()
        val_seq = (rng.random(m) < valid_prob).tolist()
        junk = vec.rand_bits(rng, 4 * m).tolist()
        sent = 0
        drain_left = SHADE_LAT + 1
        cyc = 0
        since = 4  # enabled clocks since the last pixel: a pixel every 4th one at most
        while drain_left > 0:
            en = en_seq[cyc % m]
            valid = sent < n and val_seq[cyc % m] and since >= 4
            if valid:
                tag = sent % (1 << TAG_W)
                self.what[tag] = (f"[{cfg.name}] pixel {sent}: C/M/du/dv = "
                                  + " ".join(f"{int(w):06x}" for w in x[sent]))
                d.col_i.value = col[sent]
                d.nrm_i.value = nrm[sent]
                d.du_i.value = du[sent]
                d.dv_i.value = dv[sent]
            else:  # a bubble: random data on the ports
                j = 4 * (cyc % m)
                tag = junk[j] % (1 << TAG_W)
                d.col_i.value = (junk[j] << 48) | (junk[j + 1] << 24) | junk[j + 2]
                d.nrm_i.value = (junk[j + 3] << 48) | (junk[j] << 24) | junk[j + 1]
                d.du_i.value = junk[j + 2]
                d.dv_i.value = junk[j + 3]
            d.valid_i.value = int(valid)
            d.tag_i.value = tag
            d.en_i.value = int(en)
            await RisingEdge(d.clk_i)
            await FallingEdge(d.clk_i)
            cyc += 1
            if en:
                since = 1 if valid else since + 1
                if valid:
                    self.phases[self.enabled % 4] += 1
                    self.gaps[min(self.enabled - self.last, 8)] += 1
                    self.last = self.enabled
                self.enabled += 1
                self.entries.append((valid, tag, rgb[sent] if valid else 0))
                if valid:
                    sent += 1
                elif sent >= n:
                    drain_left -= 1
            self.check_outputs(cyc)
            if en and self.enabled >= SHADE_LAT and self.entries[self.enabled - SHADE_LAT][0]:
                self.checked += 1  # a pixel's result appeared (first look; later ones are holds)
        d.en_i.value = 0
        return n


def check_constants() -> None:
    """The hard-wired patterns of shade_pkg equal the model's constants rounded by the engine."""
    want = {"SHADE_EPS": shade.EPS, "SHADE_TWO": 2.0, "SHADE_ONE": 1.0, "SHADE_ZERO": 0.0,
            "SHADE_255": 255.0, "SHADE_HALF": 0.5}
    for name, val in want.items():
        got = pkg_value(name)
        exp = int(f24.from_float(np.float64(val)))
        assert got == exp, f"shade_pkg {name} = 0x{got:06x}, model 0x{exp:06x}"
        assert f24.to_float(np.uint32(exp)) == val, f"{name}: the model's constant is not exact"


@cocotb.test()
async def shade_random_and_directed(dut):
    check_constants()
    rng = np.random.default_rng(fp_unit.seed())
    n_rand = fp_unit.vectors(fp_unit.VECTORS_COMPOSITE)
    bench = Bench(dut, rng)
    await bench.start()
    cfgs = configs(rng)
    counts = {"directed": 0, "random": 0, "wild": 0}
    for i, cfg in enumerate(cfgs):
        # the default configuration gets half of the random pixels, the others share the rest
        nr = n_rand // 2 if i == 0 else max(200, n_rand // (2 * (len(cfgs) - 1)))
        nw = nr // 10
        # the whole directed set on the default configuration (on every one under TB_LONG=1)
        full = i == 0 or runner.long_stimulus()
        parts = {"directed": directed(rng, cfg.depth, full),
                 "random": realistic(rng, nr - nw, cfg.depth), "wild": wild(rng, nw)}
        x = np.concatenate(list(parts.values()))
        perm = rng.permutation(len(x))
        x = x[perm]
        exp = expected(cfg, x)
        # alternate a mostly running pipeline with one stalled more often than not
        await bench.stream(cfg, x, exp, en_prob=0.8 if i % 2 == 0 else 0.4,
                           valid_prob=0.75 if i % 2 == 0 else 0.95)
        for k, v in parts.items():
            counts[k] += len(v)
        dut._log.info("config %s: %d pixels (%d directed), %d mismatches so far", cfg.name, len(x),
                      len(parts["directed"]), bench.nbad)
    # a reset with pixels in flight (en_i = 0 throughout the reset): nothing may come out
    x = realistic(rng, 3 * SHADE_LAT, DEFAULT_DEPTH)
    cfg = cfgs[0]
    d = dut
    d.cfg_i.value = cfg.packed()
    d.en_i.value = 1
    for k, r in enumerate(x[:SHADE_LAT // 2]):
        d.valid_i.value = int(k % 4 == 0)  # a pixel every 4th clock
        d.col_i.value = (int(r[2]) << 48) | (int(r[1]) << 24) | int(r[0])
        await RisingEdge(d.clk_i)
        await FallingEdge(d.clk_i)
    d.valid_i.value = 0  # reset() waits a clock first: no pixel then (any SHADE_LAT)
    await bench.reset()
    for _ in range(2 * SHADE_LAT):
        d.en_i.value = 1
        await RisingEdge(d.clk_i)
        await FallingEdge(d.clk_i)
        if int(d.valid_o.value):
            raise AssertionError("valid_o after a reset with pixels in flight")
    total = sum(counts.values())
    report.record("shade_unit", "RTL vs model.shade.shade f24", total, bench.nbad)
    dut._log.info("VECTORS shade_unit: %d pixels (%d directed, %d random, %d random bit patterns) "
                  "over %d configurations, %d checked at the output, %d mismatches", total,
                  counts["directed"], counts["random"], counts["wild"], len(cfgs), bench.checked,
                  bench.nbad)
    dut._log.info("pixels per arrival phase (mod 4) %s, per spacing 4 .. 7, >= 8: %s",
                  bench.phases, bench.gaps[4:])
    assert all(bench.phases), f"a phase of arrival was never driven: {bench.phases}"
    assert min(bench.gaps[4:]) > 0, f"a spacing was never driven: {bench.gaps}"
    assert not any(bench.gaps[:4]), f"pixels closer than 4 enabled clocks: {bench.gaps}"
    assert bench.checked == total, f"{bench.checked} pixels came out, {total} went in"
    if bench.bad:
        raise AssertionError("\n".join(bench.bad + [f"{bench.nbad} mismatching pixels of {total}"]))


@pytest.mark.parametrize("add_lat,mul_lat", depths.cases())
def test_shade_unit(add_lat: int, mul_lat: int) -> None:
    runner.run("shade_unit", "test_shade_unit", HERE,
               parameters={"TAG_W": TAG_W, **depths.parameters(add_lat, mul_lat)},
               extra_env=depths.env(add_lat, mul_lat))


def test_shade_latency() -> None:
    """The Python mirror of the schedule: 67 clocks at the paper's depths (2, 1) and 90 at the
    design's (3, 2) (shade_pkg's figures; 59 and 86 when the four squares and KS s^16 had five
    multipliers of their own), and every shared unit's operations are in distinct phases mod 4 at
    each tested depth pair."""
    rsqrt_lat = sv_params.value("pipe_pkg", "F24_RSQRT_LAT")
    assert shade_lat(2, 1) == 67
    assert shade_lat(3, 2) == 90
    units = {op: unit for op, unit, _ in OPS}
    for add_lat, mul_lat in depths.PAIRS:
        st = schedule(add_lat, mul_lat, rsqrt_lat)
        for unit in set(units.values()):
            phases = [(st[op] + k) % 4 for op, u, stream in OPS if u == unit
                      for k in ((0, 1) if stream else (0,))]
            assert len(phases) == len(set(phases)), f"{unit} at {add_lat, mul_lat}: {phases}"
