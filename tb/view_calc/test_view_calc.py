# SPDX-License-Identifier: Apache-2.0
"""view_calc against model.view.view_calc in the f24 engine, bit for bit.

Stimulus (every word an f24 pattern; the model gets the patterns' values):
  random orthonormal TBNs with unit views, most pointing into the surface; views parallel to
  the surface (rounded, and exactly z = 0 with axis-aligned frames); views pointing away; grazing
  views (down tiny: k overflows); single words replaced by NaN / Inf / zero / subnormal /
  extreme patterns; zero TBNs; fully random patterns.  The depth scale D is configuration: the
  stream runs once per D (20.48, 1, the largest finite value, the smallest normal, +Inf, +0,
  negative, NaN), with random en_i gaps and valid bubbles, a fragment every 4th enabled clock at
  most (tb/common/valid_pipe.py, spacing 4: z, x and y share their float units), and a reset of
  a full pipeline while stalled.

Run at the float units' depths (ADD_LAT, MUL_LAT) of tb/common/depths.py with the same
stimulus: (3, 2), the package defaults (built with no parameter, so the run also checks the
defaults), and under make test-long the paper's (2, 1).  valid_o must come exactly
pipe_pkg::view_calc_lat(ADD_LAT, MUL_LAT) enabled edges after valid_i (21 at (3, 2), 17 at
(2, 1)), with the same words.

The configurations of CASES (the design's unit; TAG_W 1 with 2,000 random vectors) and, under
make test-long, LONG_CASES (the first at (2, 1)) are built once, side by side, in the wrapper
``view_calc_tb`` (one instance each, own ports and reset, a shared clock; its parameter LONG
adds LONG_CASES) and run at once in one simulation, each with its own random stream from the
printed seed and its own checks; a failure names the configuration.
"""
from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import cocotb
import numpy as np

from model import f24, f24_vectors as vec, view
from model.arith import ENGINES
from tb.common import cases, depths, fp_unit, runner
from tb.common.valid_pipe import ValidPipe
from tb.harness import sv_params

#: The package defaults (ADD_LAT, MUL_LAT).
DEFAULT_LATS = depths.DEFAULT
SPACING = 4   # enabled clocks from one fragment to the next, at least (view_calc's spacing)
WORDS = ["tx_i", "ty_i", "tz_i", "bx_i", "by_i", "bz_i", "nx_i", "ny_i", "nz_i",
         "vx_i", "vy_i", "vz_i"]
OUTS = ["du_o", "dv_o", "seg_o"]


class Case(NamedTuple):
    """One instance of view_calc_tb: its parameters and the random vectors of its first depth
    scale (``vectors``: None for fp_unit.vectors(VECTORS_COMPOSITE), i.e. VECTORS=... or the
    default)."""
    ADD_LAT: int
    MUL_LAT: int
    TAG_W: int
    vectors: int | None

    def name(self) -> str:
        """How a failure names the configuration."""
        return f"view_calc ADD_LAT {self.ADD_LAT}, MUL_LAT {self.MUL_LAT}, TAG_W {self.TAG_W}"


#: The instances g_case[0 ..] of view_calc_tb (the wrapper's table): the design's unit (the
#: package defaults) and a 1-bit tag.
CASES = [Case(*DEFAULT_LATS, 8, None), Case(*DEFAULT_LATS, 1, 2000)]
#: The instances after CASES in the make test-long build (the wrapper's LONG = 1): the design's
#: unit at the other depths of depths.PAIRS (the paper's (2, 1)).
LONG_CASES = [Case(a, m, 8, None) for a, m in depths.PAIRS if (a, m) != DEFAULT_LATS]


def build_cases() -> list[Case]:
    """The instances of the build: CASES, and LONG_CASES under TB_LONG=1."""
    return CASES + (LONG_CASES if runner.long_stimulus() else [])


def orthonormal(rng: np.random.Generator, n: int) -> np.ndarray:
    """(n, 3, 3) random orthonormal matrices (columns T, B, N)."""
    q, _ = np.linalg.qr(rng.normal(size=(n, 3, 3)))
    return q


def unit(rng: np.random.Generator, n: int) -> np.ndarray:
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def words_of(tbn: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(n, 12) patterns: T, B, N (column c, component i = tbn[:, i, c]), then V."""
    cols = [tbn[:, i, c] for c in range(3) for i in range(3)]
    return np.stack([f24.from_float(x) for x in cols + [v[:, i] for i in range(3)]], axis=1)


def stimulus(rng: np.random.Generator, n_random: int) -> tuple[np.ndarray, dict[str, int]]:
    """(N, 12) word patterns: the random frames and every directed class (counts by class)."""
    parts: dict[str, np.ndarray] = {}
    # Random frames, about 85% of the views pointing into the surface (N . V < 0).
    q, v = orthonormal(rng, n_random), unit(rng, n_random)
    nv = np.einsum("ni,ni->n", q[:, :, 2], v)
    flip = (nv > 0) ^ (rng.random(n_random) < 0.15)
    v[flip] = -v[flip]
    parts["random"] = words_of(q, v)
    m = max(n_random // 20, 200)
    # Parallel to the surface: V in the T-B plane (z rounds to something tiny or 0).
    q = orthonormal(rng, m)
    a = rng.uniform(0, 2 * np.pi, m)
    v = np.cos(a)[:, None] * q[:, :, 0] + np.sin(a)[:, None] * q[:, :, 1]
    parts["parallel"] = words_of(q, v)
    # Exactly z = 0: signed permutation frames, V without a component along N's axis; also
    # z = +-0 from cancelling products (N = (1, 1, 0)/s, V = (a, -a, b)).
    perm = np.array([np.eye(3)[rng.permutation(3)] for _ in range(m)])
    perm *= rng.choice([-1.0, 1.0], size=(m, 1, 3))
    v = unit(rng, m)
    axis = np.argmax(np.abs(perm[:, :, 2]), axis=1)
    v[np.arange(m), axis] = 0.0
    w1 = words_of(perm, v)
    qc = orthonormal(rng, m)
    qc[:, :, 2] = np.array([1.0, 1.0, 0.0]) * rng.choice([-1.0, 1.0], size=(m, 1))
    vc = unit(rng, m)
    vc[:, 1] = -vc[:, 0]
    parts["z = 0"] = np.concatenate([w1, words_of(qc, vc)])
    # Pointing away (N . V > 0) and grazing (|N . V| tiny: k = D / down overflows or is huge).
    q, v = orthonormal(rng, m), unit(rng, m)
    nv = np.einsum("ni,ni->n", q[:, :, 2], v)
    v[nv < 0] = -v[nv < 0]
    parts["away"] = words_of(q, v)
    # Rotated frames: z is the rounding noise of the dot product; axis-aligned frames: z is
    # exactly the view's tiny component along N (down down to 1e-25: k = D / down overflows).
    q = orthonormal(rng, m)
    eps = 10.0 ** rng.uniform(-19, -2, m) * rng.choice([-1.0, 1.0], m)
    v = q[:, :, 0] * np.sqrt(1 - eps**2)[:, None] - q[:, :, 2] * eps[:, None]
    perm = np.array([np.eye(3)[rng.permutation(3)] for _ in range(m)])
    perm *= rng.choice([-1.0, 1.0], size=(m, 1, 3))
    v2 = unit(rng, m)
    axis = np.argmax(np.abs(perm[:, :, 2]), axis=1)
    tiny = 10.0 ** rng.uniform(-25, -1, m) * rng.choice([-1.0, 1.0], m, p=[0.8, 0.2])
    v2[np.arange(m), axis] = -tiny * perm[np.arange(m), axis, 2]
    parts["grazing"] = np.concatenate([words_of(q, v), words_of(perm, v2)])
    # Single / few words replaced by special patterns.
    q, v = orthonormal(rng, 4 * m), unit(rng, 4 * m)
    w = words_of(q, v)
    for _ in range(3):
        pos = rng.integers(0, 12, 4 * m)
        pick = rng.random(4 * m) < 0.7
        w[np.arange(4 * m)[pick], pos[pick]] = rng.choice(vec.SPECIALS, int(pick.sum()))
    parts["special words"] = w
    # Zero TBNs (+-0 and subnormal patterns) with random views.
    w = words_of(orthonormal(rng, m), unit(rng, m))
    w[:, :9] = rng.choice(np.array([0x000000, 0x800000, 0x000001, 0x80ffff], np.uint32), (m, 9))
    parts["zero TBN"] = w
    # Every word a random pattern / a random value near 1.
    parts["random patterns"] = np.stack([vec.random_unary(rng, m) for _ in range(12)], axis=1)
    allw = np.concatenate(list(parts.values())).astype(np.uint32)
    return allw, {k: len(x) for k, x in parts.items()}


def expected(words: np.ndarray, d_word: int) -> dict[str, np.ndarray]:
    """The model: view_calc in the f24 engine on the patterns' values."""
    vals = f24.to_float(words)
    tbn = np.empty((len(words), 3, 3))
    for c in range(3):
        for i in range(3):
            tbn[:, i, c] = vals[:, 3 * c + i]
    out = view.view_calc(ENGINES["f24"], tbn, vals[:, 9:12], float(f24.to_float(d_word)))
    return {"du_o": f24.from_float(out.du), "dv_o": f24.from_float(out.dv),
            "seg_o": f24.from_float(out.seg)}


#: The depth scales D (configuration) the stream runs with; the first gets the random bulk.
DEPTHS = {"20.48": int(f24.from_float(20.48)), "1": f24.ONE, "max finite": f24.MAX_FINITE,
          "min normal": f24.MIN_NORMAL, "+Inf": f24.POS_INF, "+0": f24.POS_ZERO,
          "-20.48": int(f24.from_float(-20.48)), "NaN": f24.NAN}


@cocotb.test()
async def view_calc_random_and_directed(dut):
    """Every instance of view_calc_tb at once (:func:`random_and_directed` each)."""
    await cases.run_each(dut, build_cases(), Case.name,
                         lambda inst, c, rng: random_and_directed(inst, dut.clk_i, c, rng))


async def random_and_directed(dut, clk, case: Case, rng: np.random.Generator) -> None:
    """Every depth scale's stream on one instance ``dut`` (clock ``clk``)."""
    add_lat, mul_lat = case.ADD_LAT, case.MUL_LAT
    # pipe_pkg::view_calc_lat (the divider: f24_pkg::F24_DIV_LAT = 8): 17 at (2, 1), 21 at (3, 2)
    latency = sv_params.call("pipe_pkg", "view_calc_lat", add_lat, mul_lat)
    dut._log.info("view_calc ADD_LAT=%d MUL_LAT=%d: latency %d", add_lat, mul_lat, latency)
    # z, x and y share their float units: a fragment every 4th enabled clock at most
    pipe = ValidPipe(dut, latency, WORDS, OUTS, "RTL vs model.view.view_calc (f24)",
                     spacing=SPACING, clk=clk, unit="view_calc")
    await pipe.reset()
    total, classes = 0, {}
    for i, (dname, dword) in enumerate(DEPTHS.items()):
        n_first = case.vectors or fp_unit.vectors(fp_unit.VECTORS_COMPOSITE)
        n_random = n_first if i == 0 else 2000
        words, counts = stimulus(rng, n_random)
        if i == 0:
            classes = counts
        words = words[rng.permutation(len(words))]
        dut.cfg_depth_i.value = dword  # pipeline drained: only bubbles in flight
        exp = expected(words, dword)
        ins = {name: words[:, j] for j, name in enumerate(WORDS)}

        def describe(k: int, w=words, dn=dname) -> str:
            return f"D={dn} " + " ".join(f"{n[:-2]}=0x{int(w[k, j]):06x}"
                                         for j, n in enumerate(WORDS))

        nan = int(np.count_nonzero(exp["seg_o"] == f24.NAN))
        total += await pipe.run(f"D={dname} ({nan} NaN results)", ins, exp, rng,
                                describe=describe)
        if i == 1:
            await pipe.flush_check(rng)
    dut._log.info("VECTORS view_calc: %d over %d depth scales (first: %s), 0 mismatches",
                  total, len(DEPTHS), ", ".join(f"{k} {v}" for k, v in classes.items()))


def test_default_latency() -> None:
    """pipe_pkg::VIEW_CALC_LAT (dm_pipeline's) is view_calc_lat at the package defaults; the
    function gives the header's figures (17 at (2, 1), 21 at (3, 2))."""
    assert sv_params.value("pipe_pkg", "VIEW_CALC_LAT") == \
        sv_params.call("pipe_pkg", "view_calc_lat", *DEFAULT_LATS)
    assert sv_params.call("pipe_pkg", "view_calc_lat", 2, 1) == 17
    assert sv_params.call("pipe_pkg", "view_calc_lat", 3, 2) == 21


def test_view_calc() -> None:
    """Build view_calc_tb once (the configurations of CASES; under make test-long, TB_LONG=1,
    with LONG = 1: LONG_CASES too) and run :func:`view_calc_random_and_directed`."""
    here = Path(__file__).parent
    runner.run("view_calc_tb", "test_view_calc", here, rtl_top="view_calc",
               parameters={"LONG": 1} if runner.long_stimulus() else {},
               extra_sources=[str(here / "view_calc_tb.sv")])
