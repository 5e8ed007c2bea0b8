# SPDX-License-Identifier: Apache-2.0
"""f24_to_index against model.f24.to_index: random patterns plus a directed set (specials, integers
and half-integers around 0, values one ulp either side of integers, the +-2^(W-1) boundaries).

The width W is read from the width of the instances' ``idx_o``; ``idx_o`` is compared as a W-bit
two's complement pattern (expected idx & (2^W - 1)), ``sat_o`` as 0 / 1.
Run at every latency the unit accepts (LAT 1, the default, built with no parameter, and 2), all in
one build (fp_unit.run_lats: one instance per LAT on the same stimulus and en_i);
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold
while en_i = 0 and every result bit.  test_f24_to_index_lats checks that exactly these LATs
elaborate.
make test runs USED_LATS only (the design's), make test-long every one.
"""
from pathlib import Path

import cocotb
import numpy as np
import pytest

from model import f24, f24_vectors as vec
from tb.common import fp_unit

#: The unit's default latency and every LAT it accepts.
DEFAULT_LAT = 1
LATS = (1, 2)
#: The widths W tested: 20, 8, and 9 (shade_unit's colour conversion, f24_to_index #(.W(9))).
WIDTHS = (20, 8, 9)
#: The LATs make test runs: the default only (the design builds the unit at its default).
USED_LATS = (DEFAULT_LAT,)


def directed(rng: np.random.Generator, w: int) -> np.ndarray:
    parts = [vec.SPECIALS]
    # Integers, halves and quarters around 0 (exact in f24).
    q = np.arange(-64.0, 64.25, 0.25)
    parts.append(f24.from_float(q))
    # One ulp either side of every integer in [-512, 512] and of random larger integers.
    ints = np.concatenate([np.arange(-512, 513), rng.integers(-(1 << (w - 1)), 1 << (w - 1), 2048)])
    p = f24.from_float(ints.astype(np.float64))
    p = p[(p & 0x7F0000) != 0]  # drop zero: its neighbours are subnormal patterns
    for d in (-2, -1, 1, 2):
        parts.append((p.astype(np.int64) + d).astype(np.uint32))
    # +-2^j for j around the range end, and a few ulps either side (in pattern space).
    for j in list(range(max(w - 4, 0), w + 3)) + [0, 16, 17]:
        base = f24.from_float(np.array([2.0 ** j, -(2.0 ** j)]))
        for d in range(-4, 5):
            parts.append((base.astype(np.int64) + d).astype(np.uint32))
    # Every exponent from 2^-20 to 2^(W+4), both signs, random fractions.
    m = 64
    for e in range(f24.BIAS - 20, min(f24.BIAS + w + 5, 127)):
        parts.append(f24.pack(rng.integers(0, 2, m), np.full(m, e), rng.integers(0, 1 << 16, m)))
    return np.concatenate(parts).astype(np.uint32) & np.uint32(f24.MASK24)


@cocotb.test()
async def to_index_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    lanes = fp_unit.lanes(dut)
    w = len(lanes[0].signal("idx_o"))
    d = directed(rng, w)
    r = vec.random_unary(rng, fp_unit.vectors())
    a = np.concatenate([d, r])
    idx, sat = f24.to_index(a, w)
    exp = {"idx_o": idx & ((1 << w) - 1), "sat_o": sat.astype(np.int64)}
    n = await fp_unit.check_pipeline(dut, lanes, {"a_i": a}, exp, rng)
    dut._log.info("VECTORS f24_to_index W=%d LAT=%s: %d each (%d directed, %d random; "
                  "%d saturated), 0 mismatches", w, fp_unit.lat_list(lanes), n, len(d), len(r),
                  int(sat.sum()))


@pytest.mark.parametrize("w", [pytest.param(w, id=f"w{w}") for w in WIDTHS])
def test_f24_to_index(w: int) -> None:
    """Every LAT under test at width W, in one build."""
    fp_unit.run_lats("f24_to_index", "test_f24_to_index", Path(__file__).parent,
                     fp_unit.lat_set(LATS, USED_LATS), DEFAULT_LAT, parameters={"W": w})


def test_f24_to_index_lats():
    fp_unit.check_lats("f24_to_index", LATS)
