# SPDX-License-Identifier: Apache-2.0
"""tex_addr against model.texture.lookup_addresses in the f24 engine, bit for bit.

Each phase sets one texture configuration (scales su, sv = Texture.scale_for's f24 words; per
level W_k, H_k and byte offsets, the base address; the unused levels of the configuration filled
with junk) and streams lookups with random en_i gaps and valid bubbles, a lookup every other
enabled clock at most (tb/common/valid_pipe.py, spacing 2: the u and v axes share the float units
a clock apart).  The four addresses (modulo 2^ADDR_W) and fx, fy must equal the model's.
Directed: lookups at the minimum spacing, a lookup on every other clock with en_i = 1 and no
bubbles, then every other enabled clock with en_i gaps (the first phase's lookups again).

Textures (only their level sizes matter here: zero-stride stand-ins for the large ones):
  37 x 100 and 100 x 37 (non-square, not powers of two: 8 levels), scale 1 and scale != 1 (the
  texture on maps of other sizes: 37/64, 100/64, 3/7, ...), 1 x 1 (scale 1 and 1/64), twice the
  map (scale 2), 20000 x 32768 (16 levels: the largest configuration, 3.5 GB; level_i 16 .. 31
  read as 15),
  and a texture whose addresses wrap past 2^ADDR_W.
With NTEX > 1 (the unit shared by several textures, as dm_pipeline shares one for the colour
texture and the normal map) each phase configures NTEX of these textures at once and streams
their lookups interleaved in random order, each with its texture in tex_i (and, when tex_i has
more codes than textures, codes above NTEX - 1 that must read texture NTEX - 1); with NTEX = 1
tex_i carries random bits that must be ignored.
Lookups per texture (every level):
  random       u, v uniform over the map and 10% beyond it on each side, random level
  centres      texel centres and halfway points of every level (exact with scale 1)
  edges        u, v at 0, -0, the map edge and just inside / beyond it, -0.5, -1, 2x the map
  specials     NaN / Inf / zero / subnormal / huge / tiny words in u or v, huge finite values
               around the to_index saturation (2^19) and beyond
  pow2 sweep   (scale-1 textures) u, v with every exponent 0..127, both signs, several
               fractions, at every level: the exponent arithmetic of mul(ut, 2^-L) including
               its flush to zero (in make test once per texture and float-unit depths: see
               below)
  patterns     u, v random 24-bit patterns
and a reset of a full pipeline while stalled.

Every configuration is at one pair of float-unit depths (ADD_LAT, MUL_LAT) of
tb/common/depths.py: the package defaults (3, 2) (built with no depth parameter, so the defaults
are checked too), and under ``make test-long`` (TB_LONG=1) the paper's (2, 1) too; the latency
the run expects is pipe_pkg::tex_addr_lat(ADD_LAT, MUL_LAT), which must equal this file's
mirror of the schedule (and TEX_ADDR_LAT at the defaults); the stimulus and the bit-exact
checks are the same at every depth.

The configurations of CASES (the design's unit; TAG_W 1 with ADDR_W 40; NTEX 2 with TAG_W 9)
and, under make test-long, LONG_CASES (the first and the third at (2, 1); NTEX 3) are built
once, side by side, in the wrapper ``tex_addr_tb`` (one instance each, own ports and reset, a
shared clock; its parameter LONG adds LONG_CASES) and run at once in one simulation, each with
its own random stream from the printed seed and its own checks; a failure names the
configuration.

The pow2 sweep (about a third of an instance's lookups) checks the float path from u, v to the
texel indices and weights, which is the same in every instance at one pair of depths (TAG_W,
ADDR_W and NTEX widen the tag, the addresses and the texture select around it).  So in make
test it runs on the design's unit (every scale-1 texture) and, in the NTEX 2 instance, on the
texture of each phase that comes first (each texture is first in one phase: its scale word
through the texture select), not on TAG_W 1 / ADDR_W 40 (:attr:`Case.sweep` False) nor a
second time as the second texture of a phase; under make test-long every instance sweeps every
scale-1 texture of every phase (:func:`sweeps`).
"""
from __future__ import annotations

from pathlib import Path

from typing import NamedTuple

import cocotb
from cocotb.triggers import FallingEdge
import numpy as np

from model import f24, f24_vectors as vec, texture
from model.arith import ENGINES
from tb.common import cases, depths, fp_unit, runner
from tb.common.valid_pipe import ValidPipe
from tb.harness import sv_params

def tex_addr_lat(add_lat: int, mul_lat: int) -> int:
    """The schedule's latency (the module header's stage table): the item register, mul, 2^-L,
    - 0.5, floor, from_int, fx, fy a clock after fx."""
    idx, fi = sv_params.values("pipe_pkg", "F24_TO_INDEX_LAT", "F24_FROM_INT_LAT")
    return 1 + mul_lat + 1 + add_lat + idx + fi + add_lat + 1


def latency(pair: tuple[int, int]) -> int:
    """The latency under test: pipe_pkg::tex_addr_lat at the instance's depths ``pair``, checked
    against the mirror above (and TEX_ADDR_LAT at the defaults)."""
    return depths.latency("tex_addr_lat", tex_addr_lat, "TEX_ADDR_LAT", pair=pair)


SPACING = 2  # enabled clocks from one lookup to the next, at least (u, then v on the same units)
TEX_LEVELS, DIM_W, TEX_LVL_W, TEX_ADDR_W = sv_params.values(
    "pipe_pkg", "TEX_LEVELS", "TEX_DIM_W", "TEX_LVL_W", "TEX_ADDR_W")
INS = ["u_i", "v_i", "level_i", "tex_i"]
OUTS = ["addr00_o", "addr01_o", "addr10_o", "addr11_o", "fx_o", "fy_o"]
AR = ENGINES["f24"]


class Case(NamedTuple):
    """One instance of tex_addr_tb: its parameters and the random lookups of its first phase
    (``vectors``: None for fp_unit.vectors(VECTORS_COMPOSITE), i.e. VECTORS=... or the default)."""
    ADD_LAT: int
    MUL_LAT: int
    TAG_W: int
    ADDR_W: int
    NTEX: int
    vectors: int | None
    #: make test: the pow2 sweep on the first texture of each phase (False: on none; the float
    #: path at these depths is swept in an instance before); see :func:`sweeps`.
    sweep: bool = True

    def name(self) -> str:
        """How a failure names the configuration."""
        return (f"tex_addr ADD_LAT {self.ADD_LAT}, MUL_LAT {self.MUL_LAT}, TAG_W {self.TAG_W}, "
                f"ADDR_W {self.ADDR_W}, NTEX {self.NTEX}")


_ADD, _MUL = depths.DEFAULT
_OTHER = [p for p in depths.PAIRS if p != depths.DEFAULT]
#: The instances g_case[0 ..] of tex_addr_tb (the wrapper's table): the design's unit (the
#: package defaults), TAG_W 1 with 40-bit addresses, two textures sharing the unit as in
#: dm_pipeline (colour and normal map).
CASES = [Case(_ADD, _MUL, 8, TEX_ADDR_W, 1, None),
         Case(_ADD, _MUL, 1, 40, 1, 3000, sweep=False),
         Case(_ADD, _MUL, 9, TEX_ADDR_W, 2, 6000)]
#: The instances after CASES in the make test-long build (the wrapper's LONG = 1): the design's
#: unit and the two textures at the other depths of depths.PAIRS (the paper's (2, 1)); three
#: textures (not the design's two: tex_i = 3 must read texture 2).
LONG_CASES = ([Case(a, m, 8, TEX_ADDR_W, 1, None) for a, m in _OTHER]
              + [Case(a, m, 9, TEX_ADDR_W, 2, 6000) for a, m in _OTHER]
              + [Case(_ADD, _MUL, 8, TEX_ADDR_W, 3, 3000)])


def sweeps(case: Case, t: int) -> bool:
    """Whether texture ``t`` of a phase of instance ``case`` gets the pow2 sweep (when its scale
    is 1): under make test-long (TB_LONG=1) always, in make test when ``case.sweep`` and ``t`` is
    0 (the module docstring says why)."""
    return runner.long_stimulus() or (case.sweep and t == 0)


def build_cases() -> list[Case]:
    """The instances of the build: CASES, and LONG_CASES under TB_LONG=1."""
    return CASES + (LONG_CASES if runner.long_stimulus() else [])


def stand_in(h: int, w: int) -> texture.Texture:
    """A texture with the MIP chain of an h x w image (rows x columns) and no texel memory."""
    levels = []
    while True:
        levels.append(np.broadcast_to(np.zeros(4, np.uint8), (h, w, 4)))
        if h == 1 and w == 1:
            return texture.Texture(levels)
        h, w = -(-h // 2), -(-w // 2)


def f24w(x) -> np.ndarray:
    return f24.from_float(np.asarray(x, dtype=np.float64)).astype(np.uint32)


def lookups(rng: np.random.Generator, tex: texture.Texture, map_w: int, map_h: int,
            scale: tuple[float, float], n_random: int, sweep: bool,
            sat_levels: bool) -> tuple[dict[str, np.ndarray], dict[str, int]]:
    """u, v words and levels of every stimulus class, and the count per class."""
    nl = tex.n_levels
    parts: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}
    # random
    u = rng.uniform(-0.1, 1.1, n_random) * map_w
    v = rng.uniform(-0.1, 1.1, n_random) * map_h
    parts["random"] = (f24w(u), f24w(v), rng.integers(0, nl, n_random))
    # centres and halfway points of every level (texture coordinates 2^L (j + 0.5) and 2^L j)
    us, vs, ls = [], [], []
    for lv in range(nl):
        wl, hl = tex.level_size(lv)
        for off in (0.5, 0.0):
            js = np.arange(wl + 1) if wl <= 40 else np.unique(np.concatenate(
                [np.arange(3), np.arange(wl - 2, wl + 1), rng.integers(0, wl + 1, 34)]))
            iv = rng.integers(0, hl + 1, js.size)
            us.append(2.0**lv * (js + off) / scale[0])
            vs.append(2.0**lv * (iv + off) / scale[1])
            ls.append(np.full(js.size, lv))
            is_ = np.arange(hl + 1) if hl <= 40 else np.unique(np.concatenate(
                [np.arange(3), np.arange(hl - 2, hl + 1), rng.integers(0, hl + 1, 34)]))
            ju = rng.integers(0, wl + 1, is_.size)
            us.append(2.0**lv * (ju + off) / scale[0])
            vs.append(2.0**lv * (is_ + off) / scale[1])
            ls.append(np.full(is_.size, lv))
    parts["centres"] = (f24w(np.concatenate(us)), f24w(np.concatenate(vs)), np.concatenate(ls))
    # edges of the map, crossed, at every level
    def edge_vals(m: int) -> np.ndarray:
        ulp = 2.0 ** (np.floor(np.log2(m)) - 16)
        return np.array([0.0, -0.0, m, m - ulp, m + ulp, m + 0.5, m - 0.5, 2.0 * m, -0.5, -1.0,
                         -1e-3, 0.5, 1e-30, -1e-30, 0.25, m / 2.0])
    eu, ev = np.meshgrid(edge_vals(map_w), edge_vals(map_h), indexing="ij")
    eu, ev = np.tile(eu.ravel(), nl), np.tile(ev.ravel(), nl)
    parts["edges"] = (f24w(eu), f24w(ev), np.repeat(np.arange(nl), eu.size // nl))
    # special words in one coordinate, huge values around the index saturation
    huge = f24w([2.0**19 - 4, 2.0**19, -2.0**19, -2.0**19 - 8, 2.0**20, -2.0**20, 1e10, -1e10,
                 2.0**17 + 2, 2.0**16 + 1, 131071.0, -131071.0, 1e-19])
    sp = np.concatenate([vec.SPECIALS, huge])
    m = 6 * sp.size
    su_ = np.tile(sp, 6)
    other = f24w(rng.uniform(0, 1, m) * max(map_w, map_h))
    lv = rng.integers(0, nl, 2 * m)
    parts["specials"] = (np.concatenate([su_, other]),
                         np.concatenate([other, rng.permutation(su_)]), lv)
    if sweep:
        e = np.arange(128, dtype=np.uint32)
        fr = np.array([0, 1, 0x8000, 0xFFFF, 0x1234], dtype=np.uint32)
        s = np.array([0, 1], dtype=np.uint32)
        ee, ff, ss = (a.ravel() for a in np.meshgrid(e, fr, s, indexing="ij"))
        w = f24.pack(ss, ee, ff).astype(np.uint32)
        wu = np.tile(w, nl)
        wv = rng.permutation(wu)
        parts["pow2 sweep"] = (wu, wv, np.repeat(np.arange(nl), w.size))
    m = max(n_random // 10, 500)
    parts["patterns"] = (vec.rand_bits(rng, m), vec.rand_bits(rng, m), rng.integers(0, nl, m))
    if sat_levels:  # level_i above TEX_LEVELS - 1: read as TEX_LEVELS - 1
        m = 400
        parts["level > 15"] = (f24w(rng.uniform(-0.1, 1.1, m) * map_w),
                               f24w(rng.uniform(-0.1, 1.1, m) * map_h),
                               rng.integers(TEX_LEVELS, 32, m))
    ins = {"u_i": np.concatenate([p[0] for p in parts.values()]).astype(np.uint32),
           "v_i": np.concatenate([p[1] for p in parts.values()]).astype(np.uint32),
           "level_i": np.concatenate([p[2] for p in parts.values()]).astype(np.int64)}
    return ins, {k: len(p[0]) for k, p in parts.items()}


def expected(tex: texture.Texture, ins: dict[str, np.ndarray], su: int, sv: int, base: int,
             addr_w: int) -> dict[str, np.ndarray]:
    """The model on the words' values: lookup_addresses with the scale words' values."""
    lvl = np.minimum(ins["level_i"], TEX_LEVELS - 1)
    la = texture.lookup_addresses(tex, AR, f24.to_float(ins["u_i"]), f24.to_float(ins["v_i"]),
                                  lvl, (f24.to_float(np.array([su])), f24.to_float(np.array([sv]))),
                                  base=base)
    mask = (1 << addr_w) - 1
    out = {name: la.addr[:, k] & mask for k, name in enumerate(OUTS[:4])}
    out["fx_o"] = f24.from_float(la.fx)
    out["fy_o"] = f24.from_float(la.fy)
    return out


async def configure(dut, clk, rng: np.random.Generator,
                    textures: list[tuple[texture.Texture, int, int, int]]) -> None:
    """Drive the cfg_* ports with (texture, su, sv, base) per texture index and write the level
    tables through the lvt_* port (levels beyond a texture's own: random junk).  The writes come
    in random order, about a third of the entries written with junk first (the last write
    counts), with writes to texture codes NTEX and above (ignored) mixed in, and en_i random
    (the write port does not wait for it); ``clk``: the unit's clock."""
    ntex = len(textures)
    addr_w = len(dut.cfg_base_i) // ntex
    sel_w = len(dut.tex_i)
    su = sv = bv = 0
    final: list[tuple[int, int]] = []
    for t, (tex, su_t, sv_t, base) in enumerate(textures):
        offs = tex.level_offsets()
        for k in range(TEX_LEVELS):
            if k < tex.n_levels:
                w, h = tex.level_size(k)
                o = offs[k]
            else:
                w, h = (int(x) for x in rng.integers(1, 1 << DIM_W, 2))
                o = int(rng.integers(0, 1 << addr_w))
            final.append(((t << TEX_LVL_W) | k, o))
            final.append(((1 << (sel_w + TEX_LVL_W)) | (t << TEX_LVL_W) | k, (h << DIM_W) | w))
        su |= su_t << (24 * t)
        sv |= sv_t << (24 * t)
        bv |= base << (addr_w * t)
    dw = len(dut.lvt_wdata_i)
    junk = [(a, int(rng.integers(0, 1 << dw))) for a, _ in final if rng.random() < 0.3]
    junk += [((kind << (sel_w + TEX_LVL_W)) | (t << TEX_LVL_W) | k,
              int(rng.integers(0, 1 << dw)))
             for kind in (0, 1) for t in range(ntex, 1 << sel_w) for k in range(TEX_LEVELS)]
    order = [junk[i] for i in rng.permutation(len(junk))] + \
        [final[i] for i in rng.permutation(len(final))]
    dut.cfg_su_i.value = su
    dut.cfg_sv_i.value = sv
    dut.cfg_base_i.value = bv
    dut.valid_i.value = 0
    for a, d in order:
        await FallingEdge(clk)
        dut.en_i.value = int(rng.random() < 0.7)
        dut.lvt_we_i.value = 1
        dut.lvt_waddr_i.value = a
        dut.lvt_wdata_i.value = d
    await FallingEdge(clk)
    dut.lvt_we_i.value = 0
    dut.en_i.value = 1


def configs(rng: np.random.Generator, addr_w: int) -> list[tuple[str, texture.Texture, int, int,
                                                                    int]]:
    """(name, texture, map width, map height, base address) of every phase."""
    def base_for(tex: texture.Texture) -> int:
        top = (1 << addr_w) - tex.memory_size()
        return int(rng.integers(0, top // 64)) * 64

    t37 = stand_in(37, 100)  # 37 rows, 100 columns
    t100 = stand_in(100, 37)
    t1 = stand_in(1, 1)
    big = stand_in(20000, 32768)  # 3.5 GB: row products up to 2^29
    odd = stand_in(200, 513)
    out = [("37x100, map 100x37 (scale 1)", t37, 100, 37, base_for(t37)),
           ("100x37 on a 64x64 map", t100, 64, 64, base_for(t100)),
           ("37x100 on a 7x3 map", t37, 7, 3, base_for(t37)),
           ("1x1 (scale 1)", t1, 1, 1, base_for(t1)),
           ("1x1 on a 64x48 map", t1, 64, 48, base_for(t1)),
           ("2x the map: 96x128 on 64x48", stand_in(96, 128), 64, 48, 0),
           ("20000x32768 (16 levels, scale 1)", big, 32768, 20000, base_for(big)),
           ("200x513 on 256x256, addresses wrap", odd, 256, 256,
            (1 << addr_w) - odd.memory_size() // 2)]
    return out


@cocotb.test()
async def tex_addr_random_and_directed(dut):
    """Every instance of tex_addr_tb at once (:func:`random_and_directed` each)."""
    await cases.run_each(dut, build_cases(), Case.name,
                         lambda inst, c, rng: random_and_directed(inst, dut.clk_i, c, rng))


async def random_and_directed(dut, clk, case: Case, rng: np.random.Generator) -> None:
    """The phases of the module docstring on one instance ``dut`` (clock ``clk``)."""
    addr_w = len(dut.addr00_o)
    ntex = len(dut.cfg_su_i) // 24
    sel_codes = 1 << len(dut.tex_i)
    pair = (case.ADD_LAT, case.MUL_LAT)
    lat = latency(pair)
    dut._log.info("ADD_LAT, MUL_LAT = %s: latency %d", pair, lat)
    pipe = ValidPipe(dut, lat, INS, OUTS, "RTL vs model.texture.lookup_addresses (f24)",
                     spacing=SPACING, clk=clk, unit="tex_addr")
    dut.lvt_we_i.value = 0
    await pipe.reset()
    cfgs = configs(rng, addr_w)
    total, lines = 0, []
    for i in range(len(cfgs)):
        group = [cfgs[(i + t) % len(cfgs)] for t in range(ntex)]  # texture t of this phase
        textures, parts, names = [], [], []
        for t, (name, tex, mw, mh, base) in enumerate(group):
            su_v, sv_v = tex.scale_for(AR, mw, mh)
            su, sv = int(f24w(su_v)[0]), int(f24w(sv_v)[0])
            scale = (float(su_v[0]), float(sv_v[0]))
            sweep = scale == (1.0, 1.0) and sweeps(case, t)
            n_first = case.vectors or fp_unit.vectors(fp_unit.VECTORS_COMPOSITE)
            n_random = n_first if i == 0 else 3000
            ins_t, counts = lookups(rng, tex, mw, mh, scale, n_random // ntex, sweep,
                                    tex.n_levels == TEX_LEVELS)
            n = len(ins_t["u_i"])
            if ntex == 1:
                sel = rng.integers(0, sel_codes, n)            # ignored by the unit
            elif t == ntex - 1 and sel_codes > ntex:           # codes above NTEX - 1: the last
                sel = np.where(rng.random(n) < 0.3, rng.integers(ntex, sel_codes, n), t)
            else:
                sel = np.full(n, t)
            ins_t["tex_i"] = sel.astype(np.int64)
            textures.append((tex, su, sv, base))
            exp_t = expected(tex, ins_t, su, sv, base, addr_w)
            parts.append((ins_t, exp_t))
            names.append(f"{name} (su=0x{su:06x} sv=0x{sv:06x}, {tex.n_levels} levels)")
            lines.append(f"{name}: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
        ins = {k: np.concatenate([p[0][k] for p in parts]) for k in INS}
        exp = {k: np.concatenate([p[1][k] for p in parts]) for k in OUTS}
        perm = rng.permutation(len(ins["u_i"]))
        ins = {k: v[perm] for k, v in ins.items()}
        exp = {k: v[perm] for k, v in exp.items()}
        await configure(dut, clk, rng, textures)  # pipeline drained: only bubbles in flight

        def describe(k: int, ins=ins, names=names) -> str:
            t = min(int(ins["tex_i"][k]), ntex - 1) if ntex > 1 else 0
            return (f"[{names[t]}] tex_i={int(ins['tex_i'][k])} u=0x{int(ins['u_i'][k]):06x} "
                    f"v=0x{int(ins['v_i'][k]):06x} L={int(ins['level_i'][k])}")

        nan = int(np.count_nonzero(f24.is_nan(exp["fx_o"]) | f24.is_nan(exp["fy_o"])))
        total += await pipe.run(" + ".join(names) + f", {nan} NaN weights", ins, exp, rng,
                                describe=describe)
        if i == 0:  # the minimum spacing: back to back without stalls, then with en_i gaps
            m = min(len(ins["u_i"]), 4000)
            ins_m = {k: v[:m] for k, v in ins.items()}
            exp_m = {k: v[:m] for k, v in exp.items()}
            total += await pipe.run(f"minimum spacing, en_i = 1: {names[0]}", ins_m, exp_m, rng,
                                    en_prob=1.0, bubble=0.0, describe=describe)
            total += await pipe.run(f"minimum spacing, en_i gaps: {names[0]}", ins_m, exp_m, rng,
                                    en_prob=0.6, bubble=0.0, describe=describe)
        if i == 1:
            await pipe.flush_check(rng)
    for ln in lines:
        dut._log.info("  %s", ln)
    dut._log.info("VECTORS tex_addr: %d lookups over %d textures (NTEX %d, ADD_LAT %d, MUL_LAT "
                  "%d), 0 mismatches", total, len(lines), ntex, *pair)


def test_tex_addr() -> None:
    """Build tex_addr_tb once (the configurations of CASES; under make test-long, TB_LONG=1, with
    LONG = 1: LONG_CASES too) and run :func:`tex_addr_random_and_directed` on every instance."""
    here = Path(__file__).parent
    runner.run("tex_addr_tb", "test_tex_addr", here, rtl_top="tex_addr",
               parameters={"LONG": 1} if runner.long_stimulus() else {},
               extra_sources=[str(here / "tex_addr_tb.sv")])
