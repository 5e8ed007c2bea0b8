# SPDX-License-Identifier: Apache-2.0
"""f24_frac against the model: every result is model.f24.sub(a, from_int(to_index(a, 20), 20)),
the word of the chain it replaces in tex_addr (f24_to_index, f24_from_int, f24_add(a, -that)).

Stimulus (seed printed, SEED=... to repeat): a directed set (the specials and zeros of both signs
with fraction bits; every exponent, both signs, with the fractions 0, 1, 0x8000, 0xFFFF, 0xFFFE
and random ones: the negative values below 1/2 whose 1 - |a| rounds, the integers, the
saturated floors around 2^19 and the ties at 2^35; a few ulps either side of the integers and
half-integers near 0), then random words.  fp_unit.check_pipeline drops en_i at random and checks
each instance's latency, its hold while en_i = 0 and every result bit.  Built at tex_addr's LAT
(ADD_LAT + 2: 5 at the design's depths; make test-long adds 4, the paper's, and 3, the unit's
least and default), all LATs in one build (fp_unit.run_lats: one instance per LAT on the same
stimulus and en_i).
test_frac_every_word (make test-long) runs a numpy mirror of the unit's cases over all 2^24 words
against the model (the mirror's equality with the RTL is what the cocotb test checks on its
vectors);
test_frac_miter runs the SAT proof against the chain (and its mutant, which must fail);
test_frac_rejects checks the elaboration error for LAT below 3.
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
NAN = 0x7F8000
#: LATs: tex_addr's at the design's depths (make test), then the others of make test-long.
USED = [5]
LONG = [4, 3]
#: The unit's default latency (its least).
DEFAULT_LAT = 3


def expected(a: npt.ArrayLike) -> np.ndarray:
    """sub(a, from_int(to_index(a, 20), 20)) of the f24 engine."""
    a = np.asarray(a, dtype=np.uint32)
    j, _ = f24_conv.to_index(a, 20)
    return f24.sub(a, f24_conv.from_int(j, 20))


def directed(rng: np.random.Generator) -> np.ndarray:
    parts = [vec.SPECIALS, np.array([0x000001, 0x80FFFF, 0x7F0000, 0xFF0000, 0x7F0001],
                                    dtype=np.uint32)]
    for e in range(128):
        fr = np.concatenate([[0, 1, 0x8000, 0xFFFF, 0xFFFE], rng.integers(0, 1 << 16, 11)])
        for s in (0, 1):
            parts.append(f24.pack(np.full(fr.size, s), np.full(fr.size, e), fr))
    q = f24.from_float(np.arange(-40.0, 40.25, 0.5))
    q = q[(q & 0x7F0000) != 0]
    for d in range(-2, 3):
        parts.append((q.astype(np.int64) + d).astype(np.uint32))
    return np.concatenate(parts).astype(np.uint32) & np.uint32(f24.MASK24)


@cocotb.test()
async def frac_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    d = directed(rng)
    r = vec.random_unary(rng, fp_unit.vectors())
    a = np.concatenate([d, r])
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(
        dut, lanes, {"a_i": a}, {"y_o": expected(a)}, rng,
        describe=lambda i: f"a=0x{int(a[i]):06x}",
        label="RTL vs model sub(a, from_int(to_index(a)))")
    dut._log.info("VECTORS f24_frac LAT=%s: %d each (%d directed, %d random), 0 mismatches",
                  fp_unit.lat_list(lanes), n, len(d), len(r))


def test_f24_frac() -> None:
    fp_unit.run_lats("f24_frac", "test_f24_frac", HERE, fp_unit.lat_set(USED + LONG, USED),
                     DEFAULT_LAT)


def _norm(v: np.ndarray, e: np.ndarray) -> np.ndarray:
    """The exponent and fraction fields of v (1 <= v < 2^17) in ulps 2^(e - 79)."""
    lead = np.zeros_like(v)
    for i in range(17):
        lead = np.where((v >> i) & 1, i, lead)
    lz = 16 - lead
    return ((e - lz) << 16) | ((v << lz) & 0xFFFF)


def mirror(a: np.ndarray) -> np.ndarray:
    """The unit's cases (f24_frac.sv's header) in numpy, bit for bit."""
    a = a.astype(np.int64)
    s = (a >> 23) & 1
    e = (a >> 16) & 0x7F
    fr = a & 0xFFFF
    m = (1 << 16) | fr
    k = np.clip(79 - e, 0, 17)
    f = m & ((1 << k) - 1)
    frac_pos = np.where(f == 0, 0, _norm(np.maximum(f, 1), e))
    frac_neg = np.where(f == 0, 0, _norm(np.clip((1 << k) - f, 1, (1 << 17) - 1), e))
    sh = np.clip(62 - e, 1, 40)                           # 1 - |a|, rounded (e <= 61)
    q = np.where(sh >= 18, 0, m >> np.minimum(sh, 17))
    g = np.where(sh - 1 >= 17, 0, (m >> np.minimum(sh - 1, 16)) & 1)
    st = (m & ((1 << np.minimum(sh - 1, 17)) - 1)) != 0
    r = q + (g & (st | (q & 1)))
    one_minus = np.where(r == 0, 63 << 16, (62 << 16) | ((1 << 16) - r))
    bv = m - (1 << np.clip(98 - e, 0, 16))                # |a| - 2^19 (82 <= e <= 98)
    big = np.where(bv == 0, 0, _norm(np.maximum(bv, 1), e) | (s << 23))
    tie = np.where(m == (1 << 16), ((e - 1) << 16) | 0xFFFF,
                   np.where(m & 1, (e << 16) | ((m - 1) & 0xFFFF), a & 0x7FFFFF)) | (s << 23)
    y = np.where(e == 0, s << 23, 0)
    y = np.where((e >= 1) & (e <= 62) & (s == 0), a, y)
    y = np.where((e >= 63) & (e <= 78) & (s == 0), frac_pos, y)
    y = np.where((e >= 62) & (e <= 78) & (s == 1), frac_neg, y)
    y = np.where((e >= 1) & (e <= 61) & (s == 1), one_minus, y)
    y = np.where((e >= 79) & (e <= 81), 0, y)
    y = np.where((e >= 82) & (e <= 98), big, y)
    y = np.where(e == 99, tie, y)
    y = np.where((e >= 100) & (e <= 126), a, y)
    return np.where(e == 127, np.where(fr != 0, NAN, a), y)


@pytest.mark.skipif(not runner.long_stimulus(),
                    reason="make test-long: make test proves the unit by the miter")
def test_frac_every_word() -> None:
    """The mirror against the model on all 2^24 words (make test-long)."""
    a = np.arange(1 << 24, dtype=np.uint32)
    exp = expected(a).astype(np.int64)
    got = mirror(a)
    bad = np.nonzero(got != exp)[0]
    assert bad.size == 0, (f"{bad.size} words differ, first a=0x{int(a[bad[0]]):06x}: "
                           f"0x{int(got[bad[0]]):06x} != 0x{int(exp[bad[0]]):06x}")


def test_frac_miter() -> None:
    """The SAT miter (scripts/flow/unit_miter.py --unit frac) proves the unit equal to the
    chain for every word, and finds the counterexample of the mutant (seconds each)."""
    script = runner.ROOT / "scripts" / "flow" / "unit_miter.py"
    for extra, says in (([], "PROVEN"), (["--mutant"], "FAILED")):
        p = subprocess.run([sys.executable, str(script), "--unit", "frac", *extra],
                           capture_output=True, text=True, cwd=runner.ROOT)
        assert p.returncode == 0 and says in p.stdout, p.stdout + p.stderr


def test_frac_rejects() -> None:
    """LAT below 3 stops at the unit's $error; 3 and 7 elaborate."""
    for lat, ok in ((3, True), (7, True), (2, False), (0, False)):
        rc, out = fp_unit.elaborate("f24_frac", {"LAT": lat})
        rejected = "f24_frac: LAT must" in out
        assert (rc == 0 and not rejected) if ok else (rc != 0 and rejected), f"LAT={lat}:\n{out}"
