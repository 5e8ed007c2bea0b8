# SPDX-License-Identifier: Apache-2.0
"""f24_round_index against the model: every result is model.f24_conv.to_index(model.f24.add(a,
0.5), W), the word of the pair it replaces (f24_add(a, 0.5), then f24_to_index #(.W(W))).

Stimulus (seed printed, SEED=... to repeat): a directed set (the specials; the one word the sum
rounds across an integer, 0.5 - 2^-18, and its neighbours; a few ulps either side of every
half-integer and integer of the index range and beyond its ends; every exponent from 2^-6 to
2^(W+2) with the fractions 0, 1, 0x8000, 0xFFFF and random ones, both signs), then random words.
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold while
en_i = 0 and every result bit.  Built at the design's (W, LAT) pairs, shade_unit's (9, 4) and
mip_level's (7, 4); make test-long adds the paper's depths' LAT 3 and the range ends W = 2 and 16
at LAT 2.  One build per W with all its LATs (fp_unit.run_lats: one instance per LAT on the same
stimulus and en_i).
test_round_index_every_word (make test-long) runs a numpy mirror of the unit's two stages over all
2^24 words against the model at every W (the mirror's equality with the RTL is what the cocotb
test checks on its vectors); test_round_index_miter runs the SAT proof against the pair at the
design's widths (and its mutant, which must fail); test_round_index_rejects checks the
elaboration errors for W and LAT out of range.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import cocotb
import numpy as np
import numpy.typing as npt
import pytest

from model import f24, f24_conv, f24_vectors as vec
from tb.common import fp_unit, runner

HERE = Path(__file__).parent
HALF = 0x3E0000           # 0.5
ROUNDS_UP = 0x3DFFFF      # 0.5 - 2^-18: S = 1 - 2^-18 rounds (tie, to even) to 1.0
#: (W, LAT) pairs: the design's (make test), then the others of make test-long.
USED = [(9, 4), (7, 4)]
LONG = [(9, 3), (7, 3), (16, 2), (2, 2)]


def expected(a: npt.ArrayLike, w: int) -> np.ndarray:
    """to_index(add(a, 0.5), W) of the f24 engine."""
    a = np.asarray(a, dtype=np.uint32)
    idx, _ = f24_conv.to_index(f24.add(a, np.full_like(a, HALF)), w)
    return idx


def directed(rng: np.random.Generator, w: int) -> np.ndarray:
    parts = [vec.SPECIALS, np.array([ROUNDS_UP], dtype=np.uint32)]
    parts.append((np.int64(ROUNDS_UP) + np.arange(-3, 4)).astype(np.uint32))
    # integers and half-integers across the range and past its ends, a few ulps either side
    top = float(1 << (w - 1)) + 3.0
    q = np.arange(-top, top + 0.25, 0.5)
    p = f24.from_float(q)
    p = p[(p & 0x7F0000) != 0]
    for d in range(-2, 3):
        parts.append((p.astype(np.int64) + d).astype(np.uint32))
    # every exponent from 2^-6 to 2^(W+2), both signs, edge and random fractions
    for e in range(f24.BIAS - 6, min(f24.BIAS + w + 3, 127)):
        fr = np.concatenate([[0, 1, 0x8000, 0xFFFF], rng.integers(0, 1 << 16, 28)])
        for s in (0, 1):
            parts.append(f24.pack(np.full(fr.size, s), np.full(fr.size, e), fr))
    return np.concatenate(parts).astype(np.uint32) & np.uint32(f24.MASK24)


@cocotb.test()
async def round_index_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    lanes = fp_unit.lanes(dut)
    w = len(lanes[0].signal("idx_o"))
    d = directed(rng, w)
    r = vec.random_unary(rng, fp_unit.vectors())
    a = np.concatenate([d, r])
    n = await fp_unit.check_pipeline(
        dut, lanes, {"a_i": a}, {"idx_o": expected(a, w) & ((1 << w) - 1)}, rng,
        describe=lambda i: f"a=0x{int(a[i]):06x}", label="RTL vs model to_index(add(a, 0.5))")
    dut._log.info("VECTORS f24_round_index W=%d LAT=%s: %d each (%d directed, %d random), "
                  "0 mismatches", w, fp_unit.lat_list(lanes), n, len(d), len(r))


def _case(w: int):
    """W's build: skipped in make test when the design builds no LAT at W."""
    long_only = all(uw != w for uw, _ in USED)
    return pytest.param(w, id=f"w{w}", marks=[pytest.mark.skipif(
        not runner.long_stimulus(), reason="not a pair the design builds: make test-long "
        "(TB_LONG=1)")] if long_only else [])


@pytest.mark.parametrize("w", [_case(w) for w in dict.fromkeys(w for w, _ in USED + LONG)])
def test_f24_round_index(w: int) -> None:
    """Every LAT under test at W, in one build."""
    lats = fp_unit.lat_set([lat for pw, lat in USED + LONG if pw == w],
                           [lat for pw, lat in USED if pw == w])
    fp_unit.run_lats("f24_round_index", "test_f24_round_index", HERE, lats, 2,
                     parameters={"W": w})


def mirror(a: np.ndarray, w: int) -> np.ndarray:
    """The unit's two stages (f24_round_index.sv) in numpy, bit for bit."""
    a = a.astype(np.int64)
    s = (a >> 23) & 1
    e = (a >> 16) & 0x7F
    fr = a & 0xFFFF
    m = (1 << 16) | fr
    rp = (78 - e) & 31
    sh = m >> rp
    tz = np.full_like(m, 16)
    for i in range(15, -1, -1):
        tz = np.where((m >> i) & 1, i, tz)
    r = sh & 1
    inc = np.where(s == 1, r & (tz < rp), r | ((e == 61) & (fr == 0xFFFF)))
    mg = ((sh >> 1) & ((1 << (w - 1)) - 1)) + inc
    imax, imin = (1 << (w - 1)) - 1, -(1 << (w - 1))
    y = np.where(s == 1, -mg, np.where((mg >> (w - 1)) & 1, imax, mg))
    y = np.where(e >= 62 + w, np.where(s == 1, imin, imax), y)
    return np.where(((e == 127) & (fr != 0)) | (e < 61), 0, y)


@pytest.mark.skipif(not runner.long_stimulus(),
                    reason="make test-long: make test proves the design's widths by the miter")
def test_round_index_every_word() -> None:
    """The mirror against the model on all 2^24 words at every W from 2 to 16 (make
    test-long)."""
    a = np.arange(1 << 24, dtype=np.uint32)
    s = f24.add(a, np.full_like(a, HALF))
    for w in range(2, 17):
        exp, _ = f24_conv.to_index(s, w)
        bad = np.nonzero(mirror(a, w) != exp)[0]
        assert bad.size == 0, (f"W={w}: {bad.size} words differ, first a=0x{int(a[bad[0]]):06x}: "
                               f"{int(mirror(a[bad[:1]], w)[0])} != {int(exp[bad[0]])}")
    # the one word whose sum rounds across an integer: the case the unit adds by hand
    assert int(expected([ROUNDS_UP], 9)[0]) == 1


def test_round_index_rejects() -> None:
    """W outside 2 .. 16 and LAT below 2 stop at the unit's $error; the edges elaborate."""
    for params, ok in (({"W": 2, "LAT": 2}, True), ({"W": 16, "LAT": 5}, True),
                       ({"W": 1, "LAT": 2}, False), ({"W": 17, "LAT": 2}, False),
                       ({"W": 9, "LAT": 1}, False), ({"W": 9, "LAT": 0}, False)):
        rc, out = fp_unit.elaborate("f24_round_index", params)
        rejected = "f24_round_index: " in out
        assert (rc == 0 and not rejected) if ok else (rc != 0 and rejected), f"{params}:\n{out}"


@pytest.mark.parametrize("w", [9, 7])
def test_round_index_miter(w: int) -> None:
    """The SAT miter (scripts/flow/unit_miter.py) proves the unit equal to f24_add(a, 0.5) +
    f24_to_index for every word at the design's widths, and finds the counterexample of the
    mutant without the one word whose sum rounds across an integer (seconds each)."""
    script = runner.ROOT / "scripts" / "flow" / "unit_miter.py"
    for extra, says in (([], "PROVEN"), (["--mutant"], "FAILED")):
        p = subprocess.run([sys.executable, str(script), "--unit", "round_index", "--width",
                            str(w), *extra], capture_output=True, text=True, cwd=runner.ROOT)
        assert p.returncode == 0 and says in p.stdout, p.stdout + p.stderr
