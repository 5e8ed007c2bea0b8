# SPDX-License-Identifier: Apache-2.0
"""f24_mul against model.f24.mul: random patterns, values near 1.0 and the directed set.

Run at every latency the unit accepts (LAT 1, the default, built with no parameter; 2; 3), all in
one build (fp_unit.run_lats: one instance per LAT on the same stimulus and en_i);
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold
while en_i = 0 and every result bit.  test_f24_mul_lats checks that exactly these LATs elaborate.
make test runs USED_LATS only (the design's), make test-long every one.
"""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import depths, fp_unit

#: The unit's default latency (the paper's) and every LAT it accepts.
DEFAULT_LAT = 1
LATS = (1, 2, 3)
#: The LATs make test runs: the default (the paper's) and the design's MUL_LAT.
USED_LATS = (DEFAULT_LAT, depths.DEFAULT[1])


@cocotb.test()
async def mul_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    da, db = vec.directed_binary("mul", rng)
    ra, rb = vec.random_binary(rng, fp_unit.vectors())
    a, b = np.concatenate([da, ra]), np.concatenate([db, rb])
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(dut, lanes, {"a_i": a, "b_i": b}, {"y_o": f24.mul(a, b)}, rng)
    dut._log.info("VECTORS f24_mul LAT=%s: %d each (%d directed, %d random), 0 mismatches",
                  fp_unit.lat_list(lanes), n, len(da), len(ra))


def test_f24_mul():
    fp_unit.run_lats("f24_mul", "test_f24_mul", Path(__file__).parent,
                     fp_unit.lat_set(LATS, USED_LATS), DEFAULT_LAT)


def test_f24_mul_lats():
    fp_unit.check_lats("f24_mul", LATS)
