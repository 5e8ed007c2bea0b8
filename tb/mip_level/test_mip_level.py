# SPDX-License-Identifier: Apache-2.0
"""mip_level (with its tri_table) against model.texture.ray_length / mip_level in the f24 engine.

Each phase writes the triangle table through the write port (log2 Pb words for both textures,
with en_i random or held at 0), sets the configuration (mip_en, the two level counts) and
streams hits with random en_i gaps and valid bubbles, a hit every other enabled clock at most
and none mip_gap or mip_gap + 1 enabled clocks after another (tb/common/valid_pipe.py with jobs =
spacing = 2 and those two distances forbidden: the two textures share the lod datapath, one
adder serves Pl and both lods, and each hit gives its colour level, tex_o = 0, MIP_LAT enabled edges later and its normal map's,
tex_o = 1, on the next one); the levels must equal the model's bit for bit:
  random       realistic t, seg, Pl0 and table words: lod from far below 0 to beyond the levels;
               every triangle id
  boundaries   table words k/4 and Pl0 chosen (with the model) so that lod + 0.5 lies within
               4 ulps of an integer (the floor's edges), and Pl0 around powers of two
  specials     t, seg, Pl0 and table words from the special patterns: NaN t, t = 0, Pl = 0
               (Pl0 = -t seg), negative Pl, Inf, huge and tiny values
  extremes     one level (level 0 always) and 32 levels with lod up to +Inf
  mip off      mip_en = 0: level 0 whatever the hit
  counts       level counts 0 and 40 in the configuration (read as 1 and 32)
and a reset of a full pipeline while stalled.

Run at the float units' depths (ADD_LAT, MUL_LAT) of tb/common/depths.py with the same
stimulus: (3, 2), the package defaults (built with no parameter, so the run also checks the
defaults), and under make test-long the paper's (2, 1).  The colour level must come exactly
pipe_pkg::mip_lat(ADD_LAT, MUL_LAT) enabled edges after valid_i (20 at (3, 2), 14 at (2, 1)),
the normal map's on the next one, with the same levels.

The configurations of CASES (the design's unit; two triangles with a 3-bit tag and 5,000
vectors) and, under make test-long, LONG_CASES (the first at (2, 1)) are built once, side by
side, in the wrapper ``mip_level_tb`` (one instance each, own ports and reset, a shared clock;
its parameter LONG adds LONG_CASES) and run at once in one simulation, each with its own random
stream from the printed seed and its own checks; a failure names the configuration.
"""
from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import cocotb
import numpy as np
from cocotb.triggers import FallingEdge, RisingEdge

from model import f24, f24_vectors as vec, texture
from model.arith import ENGINES
from tb.common import cases, depths, fp_unit, runner
from tb.common.valid_pipe import ValidPipe
from tb.harness import sv_params

#: The package defaults (ADD_LAT, MUL_LAT).
DEFAULT_LATS = depths.DEFAULT
INS = ["t_i", "seg_i", "pl0_i", "tri_i"]
OUTS = ["tex_o", "level_o"]  # two results per hit: colour (tex_o 0), then the normal map (1)
AR = ENGINES["f24"]


def logu(rng: np.random.Generator, lo: float, hi: float, n: int) -> np.ndarray:
    """f24 patterns log-uniform in [lo, hi]."""
    return f24.from_float(np.exp(rng.uniform(np.log(lo), np.log(hi), n)))


def expected(ins: dict[str, np.ndarray], table: np.ndarray, levels: tuple[int, int],
             mip: bool) -> list[np.ndarray]:
    """The model on the patterns' values: Pl = ray_length, L = mip_level per texture (colour,
    normal map)."""
    t, seg, pl0 = (f24.to_float(ins[k]) for k in ("t_i", "seg_i", "pl0_i"))
    pl = texture.ray_length(AR, pl0, t, seg)
    out = []
    for x in range(2):
        if mip:
            pb = f24.to_float(table[ins["tri_i"].astype(np.int64), x])
            out.append(np.asarray(texture.mip_level(AR, pl, pb, levels[x]), dtype=np.int64))
        else:
            out.append(np.zeros(len(t), dtype=np.int64))
    return out


def results(per_tex: list[np.ndarray]) -> dict[str, np.ndarray]:
    """The unit's result stream: per hit the colour level, then the normal map's."""
    n = len(per_tex[0])
    return {"tex_o": np.tile([0, 1], n), "level_o": np.stack(per_tex, axis=1).ravel()}


async def write_table(dut, clk, table: np.ndarray, rng: np.random.Generator,
                      en_random: bool) -> None:
    """Every word {tri, tex} through the write port, in random order, with en_i random or 0 and
    valid_i = 0 (only bubbles enter the pipeline)."""
    tris = table.shape[0]
    order = rng.permutation(2 * tris)
    dut.valid_i.value = 0
    for a in order:
        dut.tt_we_i.value = 1
        dut.tt_waddr_i.value = int(a)
        dut.tt_wdata_i.value = int(table[a >> 1, a & 1])
        dut.en_i.value = int(rng.random() < 0.5) if en_random else 0
        await RisingEdge(clk)
        await FallingEdge(clk)
    dut.tt_we_i.value = 0
    dut.en_i.value = 0


def random_hits(rng: np.random.Generator, n: int, tris: int) -> dict[str, np.ndarray]:
    t = f24.from_float(rng.uniform(0.0, 1.0, n))
    t[rng.random(n) < 0.02] = f24.POS_ZERO
    t[rng.random(n) < 0.02] = f24.ONE
    tri = rng.integers(0, tris, n).astype(np.uint32)
    tri[: 4 * tris] = np.tile(np.arange(tris), 4)[: min(n, 4 * tris)]  # every id
    return {"t_i": t, "seg_i": logu(rng, 1.0, 500.0, n), "pl0_i": logu(rng, 5.0, 20000.0, n),
            "tri_i": tri}


def boundary_hits(rng: np.random.Generator, n: int, tris: int,
                  table: np.ndarray) -> dict[str, np.ndarray]:
    """Hits whose lod + 0.5 (in the model, for the given table) lies within 4 ulps of an
    integer (the floor's edges), for half of them on the colour and half on the normal map.
    Candidates: Pl0 = 2^(q/4) +- 400 ulps with t = 0 (the table holds multiples of 1/4), and
    Pl0 a few ulps around powers of two 2^-20 .. 2^40 (log2 exact) with t = 0 or tiny."""
    m = 16 * n
    q = rng.integers(-8, 40, m)
    pl0 = (f24.from_float(2.0 ** (q / 4.0)).astype(np.int64)
           + rng.integers(-400, 401, m)).astype(np.uint32)
    tri = rng.integers(0, tris, m)
    l2 = texture.log2(AR, f24.to_float(pl0))
    pick = []
    for x in range(2):
        h = AR.add(AR.sub(l2, f24.to_float(table[tri, x])), np.full(m, 0.5))
        _, e = np.frexp(np.abs(h))
        ulps = np.abs(h - np.rint(h)) / np.ldexp(1.0, e - 17)
        close = np.nonzero((ulps <= 4) | (h == 0))[0]
        pick.append(rng.choice(close, min(n // 4, close.size), replace=False))
    sel = np.concatenate(pick)
    r = n - sel.size
    k = rng.integers(-20, 40, r)
    pw = (f24.from_float(np.ldexp(1.0, k)).astype(np.int64)
          + rng.integers(-3, 4, r)).astype(np.uint32)
    t = np.where(rng.random(r) < 0.8, f24.POS_ZERO, f24.from_float(rng.uniform(0, 1e-3, r)))
    return {"t_i": np.concatenate([np.zeros(sel.size), t]).astype(np.uint32),
            "seg_i": logu(rng, 1.0, 100.0, n),
            "pl0_i": np.concatenate([pl0[sel], pw]).astype(np.uint32),
            "tri_i": np.concatenate([tri[sel], rng.integers(0, tris, r)]).astype(np.uint32)}


def special_hits(rng: np.random.Generator, n: int, tris: int) -> dict[str, np.ndarray]:
    def mix(base: np.ndarray) -> np.ndarray:
        out = base.copy()
        pick = rng.random(n) < 0.4
        out[pick] = rng.choice(vec.SPECIALS, int(pick.sum()))
        pick = rng.random(n) < 0.1
        out[pick] = vec.rand_bits(rng, int(pick.sum()))
        return out
    h = random_hits(rng, n, tris)
    h["t_i"], h["seg_i"], h["pl0_i"] = mix(h["t_i"]), mix(h["seg_i"]), mix(h["pl0_i"])
    # Pl = +-0 exactly: Pl0 = -(t seg) (the product rounded: the model's mul)
    z = rng.random(n) < 0.1
    ts = f24.mul(h["t_i"], h["seg_i"])
    h["pl0_i"][z] = f24.neg(ts[z])
    h["t_i"][rng.random(n) < 0.05] = f24.NAN
    return h


def random_table(rng: np.random.Generator, tris: int, lo: float, hi: float) -> np.ndarray:
    return f24.from_float(rng.uniform(lo, hi, (tris, 2))).astype(np.uint32)


class Case(NamedTuple):
    """One instance of mip_level_tb: its parameters and its random vectors (``vectors``: None for
    fp_unit.vectors(VECTORS_COMPOSITE), i.e. VECTORS=... or the default)."""
    ADD_LAT: int
    MUL_LAT: int
    TAG_W: int
    TRIS: int
    vectors: int | None

    def name(self) -> str:
        """How a failure names the configuration."""
        return (f"mip_level ADD_LAT {self.ADD_LAT}, MUL_LAT {self.MUL_LAT}, TAG_W {self.TAG_W}, "
                f"TRIS {self.TRIS}")


#: The instances g_case[0 ..] of mip_level_tb (the wrapper's table): the design's unit (the
#: package defaults) and two triangles with a 3-bit tag.
CASES = [Case(*DEFAULT_LATS, 8, 16, None), Case(*DEFAULT_LATS, 3, 2, 5000)]
#: The instances after CASES in the make test-long build (the wrapper's LONG = 1): the design's
#: unit at the other depths of depths.PAIRS (the paper's (2, 1)).
LONG_CASES = [Case(a, m, 8, 16, None) for a, m in depths.PAIRS if (a, m) != DEFAULT_LATS]


def build_cases() -> list[Case]:
    """The instances of the build: CASES, and LONG_CASES under TB_LONG=1."""
    return CASES + (LONG_CASES if runner.long_stimulus() else [])


@cocotb.test()
async def mip_level_random_and_directed(dut):
    """Every instance of mip_level_tb at once (:func:`random_and_directed` each)."""
    await cases.run_each(dut, build_cases(), Case.name,
                         lambda inst, c, rng: random_and_directed(inst, dut.clk_i, c, rng))


async def random_and_directed(dut, clk, case: Case, rng: np.random.Generator) -> None:
    """Every phase on one instance ``dut`` (clock ``clk``)."""
    tris = 1 << len(dut.tri_i)  # the test runs power-of-two TRIS (tb/tri_table: the others)
    # 50,000 with TB_LONG=1
    nvec = case.vectors or fp_unit.vectors(fp_unit.VECTORS_COMPOSITE)
    add_lat, mul_lat = case.ADD_LAT, case.MUL_LAT
    # pipe_pkg::mip_lat (f24_log2 at pipe_pkg::F24_LOG2_LAT): the colour level's latency
    latency = sv_params.call("pipe_pkg", "mip_lat", add_lat, mul_lat)
    dut._log.info("mip_level ADD_LAT=%d MUL_LAT=%d: latency %d", add_lat, mul_lat, latency)
    gap = sv_params.call("pipe_pkg", "mip_gap", add_lat)  # the shared adder's rule
    pipe = ValidPipe(dut, latency, INS, OUTS, "RTL vs model.texture.mip_level (f24)", jobs=2,
                     spacing=2, forbid=(gap, gap + 1), clk=clk, unit="mip_level")
    dut.tt_we_i.value = 0
    await pipe.reset()
    specials_tab = np.array([f24.NAN, f24.POS_INF, f24.NEG_INF, f24.MAX_FINITE, 0xFEFFFF,
                             f24.POS_ZERO, f24.NEG_ZERO, 0x000001, f24.MIN_NORMAL,
                             f24.from_float(-1e6), f24.from_float(1e6)], dtype=np.uint32)
    quarter = f24.from_float(np.arange(-16, 17) / 4.0).astype(np.uint32)
    quarter_tab = rng.choice(quarter, (tris, 2))
    phases = [
        # name, hits, table, (levels colour, normal), mip_en, table written with en_i random
        ("random", random_hits(rng, nvec, tris), random_table(rng, tris, -6.0, 16.0), (9, 10),
         True, True),
        ("boundaries", boundary_hits(rng, max(nvec // 5, 2000), tris, quarter_tab),
         quarter_tab, (32, 17), True, False),
        ("specials", special_hits(rng, max(nvec // 5, 2000), tris),
         np.where(rng.random((tris, 2)) < 0.6, rng.choice(specials_tab, (tris, 2)),
                  random_table(rng, tris, -6.0, 16.0)).astype(np.uint32), (12, 3), True, True),
        ("extremes", random_hits(rng, max(nvec // 10, 1000), tris),
         rng.choice(np.concatenate([specials_tab, random_table(rng, 4, -40.0, 40.0).ravel()]),
                    (tris, 2)).astype(np.uint32), (1, 32), True, False),
        ("mip off", special_hits(rng, max(nvec // 10, 1000), tris),
         random_table(rng, tris, -6.0, 16.0), (9, 10), False, True),
        # Level counts outside 1 .. 32 (the RTL's documented reading: 0 acts as 1, 40 as 32).
        ("counts 0 and 40", random_hits(rng, 1000, tris), random_table(rng, tris, -30.0, 16.0),
         (1, 32), True, False),
    ]
    cfg_counts = {"counts 0 and 40": (0, 40)}
    total = 0
    for i, (name, hits, table, levels, mip, en_random) in enumerate(phases):
        await write_table(dut, clk, table, rng, en_random)
        dut.cfg_mip_en_i.value = int(mip)
        dut.cfg_levels_colour_i.value = cfg_counts.get(name, levels)[0]
        dut.cfg_levels_normal_i.value = cfg_counts.get(name, levels)[1]
        per_tex = expected(hits, table, levels, mip)

        def describe(k: int, h=hits, tab=table) -> str:
            tri = int(h["tri_i"][k])
            return (f"t=0x{int(h['t_i'][k]):06x} seg=0x{int(h['seg_i'][k]):06x} "
                    f"pl0=0x{int(h['pl0_i'][k]):06x} tri={tri} log2pb=0x{int(tab[tri, 0]):06x},"
                    f"0x{int(tab[tri, 1]):06x}")

        hists = [np.bincount(e, minlength=lv).tolist() for e, lv in zip(per_tex, levels)]
        total += await pipe.run(f"{name} (levels {levels}, mip {int(mip)}; hits per level: "
                                f"colour {hists[0]}, normal {hists[1]})", hits, results(per_tex),
                                rng, describe=describe)
        if i == 0:
            await pipe.flush_check(rng)
    dut._log.info("VECTORS mip_level TRIS=%d: %d hits in %d phases, 0 mismatches", tris, total,
                  len(phases))


def test_default_latency() -> None:
    """pipe_pkg::MIP_LAT (dm_pipeline's) is mip_lat at the package defaults; the function gives
    the header's figures (14 at (2, 1), 20 at (3, 2)); mip_gap is 1 or 2 mod 4 at every ADD_LAT
    the unit takes, so hits a multiple of 4 clocks apart (dm_pipeline's full rate) never meet
    the shared adder's rule."""
    assert sv_params.value("pipe_pkg", "MIP_LAT") == \
        sv_params.call("pipe_pkg", "mip_lat", *DEFAULT_LATS)
    assert sv_params.call("pipe_pkg", "mip_lat", 2, 1) == 14
    assert sv_params.call("pipe_pkg", "mip_lat", 3, 2) == 20
    for add in (2, 3, 4):
        gap = sv_params.call("pipe_pkg", "mip_gap", add)
        assert gap % 4 in (1, 2) and gap >= add + 4, (add, gap)


def test_mip_level() -> None:
    """Build mip_level_tb once (the configurations of CASES; under make test-long, TB_LONG=1,
    with LONG = 1: LONG_CASES too) and run :func:`mip_level_random_and_directed`."""
    here = Path(__file__).parent
    runner.run("mip_level_tb", "test_mip_level", here, rtl_top="mip_level",
               parameters={"LONG": 1} if runner.long_stimulus() else {},
               extra_sources=[str(here / "mip_level_tb.sv")])
