# SPDX-License-Identifier: Apache-2.0
"""f24_from_int against model.f24.from_int: boundary values plus random integers, or the whole
signed range.

The DUT's width W is read from the width of ``k_i``.  Inputs are driven and reported as W-bit
two's complement patterns.  W <= 16 always runs the whole range; the W = 20 build runs 100k random
values by default (the whole 2^20 range takes about 90 s of simulation) and the whole range with
``FROM_INT_EXHAUSTIVE=1``.
Run at every latency the unit accepts (LAT 1, the default, built with no parameter, and 2), all in
one build (fp_unit.run_lats: one instance per LAT on the same stimulus and en_i);
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold
while en_i = 0 and every result bit.  test_f24_from_int_lats checks that exactly these LATs
elaborate.
make test runs USED_LATS only (the design's), make test-long every one.
"""
import os
from pathlib import Path

import cocotb
import numpy as np
import pytest

from model import f24
from tb.common import fp_unit

#: The unit's default latency and every LAT it accepts.
DEFAULT_LAT = 1
LATS = (1, 2)
#: The widths W tested: 20 (the design's), 12.
WIDTHS = (20, 12)
#: The LATs make test runs: every one (traverse_setup builds its boundary conversions at LAT CL:
#: 2 at the design's float-unit depths, 1 at the paper's).
USED_LATS = LATS


def boundary_values(w: int) -> np.ndarray:
    """Range ends, 0, +-1, and every +-(2^j + d) for small d (where the bit length changes)."""
    lo, hi = -(1 << (w - 1)), (1 << (w - 1)) - 1
    vals = {lo, hi, lo + 1, hi - 1, 0, 1, -1, 2, -2}
    for j in range(w):
        for d in range(-3, 4):
            for v in ((1 << j) + d, -(1 << j) - d):
                vals.add(v)
    # Halfway and near-halfway cases at every bit length above 17: ...x1000 and ...x0111 / ...1001.
    for j in range(17, w - 1):
        half = 1 << (j - 17)  # half an ulp for bit length j + 1
        for base in ((1 << j) | (1 << (j - 16)), 1 << j, (1 << (j + 1)) - (1 << (j - 16))):
            for d in (-1, 0, 1):
                for v in (base + half + d, -(base + half + d)):
                    vals.add(v)
    return np.array(sorted(v for v in vals if lo <= v <= hi), dtype=np.int64)


@cocotb.test()
async def from_int_boundary_random_exhaustive(dut):
    rng = np.random.default_rng(fp_unit.seed())
    w = len(dut.k_i)
    lo, hi = -(1 << (w - 1)), (1 << (w - 1)) - 1
    bnd = boundary_values(w)
    exhaustive = w <= 16 or (w <= 20 and os.environ.get("FROM_INT_EXHAUSTIVE", "0") == "1")
    if exhaustive:
        full = rng.permutation(np.arange(lo, hi + 1, dtype=np.int64))
    else:
        full = rng.integers(lo, hi, max(fp_unit.vectors(), 100_000), endpoint=True, dtype=np.int64)
    k = np.concatenate([bnd, full])
    mask = (1 << w) - 1
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(dut, lanes, {"k_i": k & mask}, {"y_o": f24.from_int(k, w)},
                                     rng, describe=lambda i: f"k_i={int(k[i])}")
    dut._log.info("VECTORS f24_from_int W=%d LAT=%s: %d each (%d boundary, %d %s), "
                  "0 mismatches", w, fp_unit.lat_list(lanes), n, len(bnd), len(full),
                  "= whole range, shuffled" if exhaustive else "random")


@pytest.mark.parametrize("w", [pytest.param(w, id=f"w{w}") for w in WIDTHS])
def test_f24_from_int(w: int) -> None:
    """Every LAT under test at width W, in one build."""
    fp_unit.run_lats("f24_from_int", "test_f24_from_int", Path(__file__).parent,
                     fp_unit.lat_set(LATS, USED_LATS), DEFAULT_LAT, parameters={"W": w})


def test_f24_from_int_lats():
    fp_unit.check_lats("f24_from_int", LATS)
