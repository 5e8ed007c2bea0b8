# SPDX-License-Identifier: Apache-2.0
"""f24_cmp against model.f24.cmp: random patterns, values near 1.0 and the directed set.

Run at every latency the unit accepts (LAT 1, the default, built with no parameter, and 2), all in
one build (fp_unit.run_lats: one instance per LAT on the same stimulus and en_i);
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold
while en_i = 0 and every result bit.  test_f24_cmp_lats checks that exactly these LATs elaborate.
make test runs USED_LATS only (the design's), make test-long every one.
"""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit

#: The unit's default latency and every LAT it accepts.
DEFAULT_LAT = 1
LATS = (1, 2)
#: The LATs make test runs: the default only (the design builds the unit at its default).
USED_LATS = (DEFAULT_LAT,)


@cocotb.test()
async def cmp_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    da, db = vec.directed_binary("cmp", rng)
    ra, rb = vec.random_binary(rng, fp_unit.vectors())
    # Equal magnitudes with both signs and equal patterns are where comparators go wrong.
    eq = vec.rand_bits(rng, 4096)
    a = np.concatenate([da, ra, eq, eq])
    b = np.concatenate([db, rb, eq, eq ^ np.uint32(f24.SIGN_BIT)])
    lt, eq_, gt, un = f24.cmp(a, b)
    exp = {"lt_o": lt.astype(np.uint32), "eq_o": eq_.astype(np.uint32),
           "gt_o": gt.astype(np.uint32), "un_o": un.astype(np.uint32)}
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(dut, lanes, {"a_i": a, "b_i": b}, exp, rng)
    dut._log.info("VECTORS f24_cmp LAT=%s: %d each (%d directed, %d random), 0 mismatches",
                  fp_unit.lat_list(lanes), n, len(da) + 8192, len(ra))


def test_f24_cmp():
    fp_unit.run_lats("f24_cmp", "test_f24_cmp", Path(__file__).parent,
                     fp_unit.lat_set(LATS, USED_LATS), DEFAULT_LAT)


def test_f24_cmp_lats():
    fp_unit.check_lats("f24_cmp", LATS)
