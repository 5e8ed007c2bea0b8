# SPDX-License-Identifier: Apache-2.0
"""f24_one_minus against model.f24.add(1, neg(x)): the traverse ring's plane, 1 - H.

Stimulus: the f24 of every unorm16 code (f24_from_unorm's outputs, the ring's only inputs), every
fraction at the exponents where the rounding changes shape (0.5 .. 1: exact with a leading-zero
shift; shifts of 1, 16, 17 and 18 bits: the guard at the top, at the hidden one, below it), the
ends (+0, 1.0, 2^-62), and random words over the whole range [+0, 1] (every exponent), in a
shuffled order.  ``make test-long`` (TB_LONG=1) adds every fraction at every exponent: all
4,128,770 words of the range.
Run at every latency the unit accepts (LAT 1, the default, built with no parameter, and 2), all in
one build (fp_unit.run_lats: one instance per LAT on the same stimulus and en_i);
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold
while en_i = 0 and every result bit.  test_f24_one_minus_lats checks that exactly these LATs
elaborate.
make test runs USED_LATS only (the design's), make test-long every one.
"""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_conv
from tb.common import fp_unit, runner

#: The unit's default latency and every LAT it accepts.
DEFAULT_LAT = 1
LATS = (1, 2)
#: The LATs make test runs: the default only (the design builds the unit at its default).
USED_LATS = (DEFAULT_LAT,)
ONE = int(f24.from_float(1.0))


def domain(rng: np.random.Generator, exhaustive: bool) -> np.ndarray:
    """Words in [+0, 1]: directed exponents whole, the rest sampled (or every word)."""
    frac = np.arange(1 << 16, dtype=np.uint32)
    exps = range(1, 63) if exhaustive else (62, 61, 46, 45, 44, 1)
    parts = [f24_conv.from_unorm(np.arange(1 << 16), 16),
             np.array([0, ONE, f24.pack(0, 1, 0)], dtype=np.uint32)]
    parts += [f24.pack(np.zeros_like(frac), np.full_like(frac, e), frac) for e in exps]
    n = fp_unit.vectors()
    parts.append(f24.pack(np.zeros(n, np.uint32), rng.integers(1, 63, n).astype(np.uint32),
                          rng.integers(0, 1 << 16, n).astype(np.uint32)))
    a = np.concatenate(parts).astype(np.uint32)
    return a[rng.permutation(len(a))]


@cocotb.test()
async def one_minus_range(dut):
    rng = np.random.default_rng(fp_unit.seed())
    whole = runner.long_stimulus()
    x = domain(rng, whole)
    want = f24.add(np.full_like(x, ONE), f24.neg(x))
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(dut, lanes, {"a_i": x}, {"y_o": want}, rng)
    dut._log.info("VECTORS f24_one_minus LAT=%s: %d each (all unorm16 H, %s, random), "
                  "0 mismatches", fp_unit.lat_list(lanes), n,
                  "every word of [+0, 1]" if whole else "6 exponents whole")


def test_f24_one_minus():
    fp_unit.run_lats("f24_one_minus", "test_f24_one_minus", Path(__file__).parent,
                     fp_unit.lat_set(LATS, USED_LATS), DEFAULT_LAT)


def test_f24_one_minus_lats():
    fp_unit.check_lats("f24_one_minus", LATS)
