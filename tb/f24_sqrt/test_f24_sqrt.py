# SPDX-License-Identifier: Apache-2.0
"""f24_sqrt against model.f24.sqrt: random patterns, values near 1.0 and the directed set.

Run at every latency the unit accepts (LAT 2, the default, built with no parameter, and 3), all in
one build (fp_unit.run_lats: one instance per LAT on the same stimulus and en_i);
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold
while en_i = 0 and every result bit.  test_f24_sqrt_lats checks that exactly these LATs elaborate.
make test runs USED_LATS only (the design's), make test-long every one.
"""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit

#: The unit's default latency and every LAT it accepts.
DEFAULT_LAT = 2
LATS = (2, 3)
#: The LATs make test runs: the default only (the design builds the unit at its default).
USED_LATS = (DEFAULT_LAT,)


@cocotb.test()
async def sqrt_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    da = vec.directed_unary_sqrt(rng)
    ra = vec.random_unary(rng, fp_unit.vectors())
    a = np.concatenate([da, ra])
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(dut, lanes, {"a_i": a}, {"y_o": f24.sqrt(a)}, rng)
    dut._log.info("VECTORS f24_sqrt LAT=%s: %d each (%d directed, %d random), 0 mismatches",
                  fp_unit.lat_list(lanes), n, len(da), len(ra))


def test_f24_sqrt():
    fp_unit.run_lats("f24_sqrt", "test_f24_sqrt", Path(__file__).parent,
                     fp_unit.lat_set(LATS, USED_LATS), DEFAULT_LAT)


def test_f24_sqrt_lats():
    fp_unit.check_lats("f24_sqrt", LATS)
