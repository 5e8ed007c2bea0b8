# SPDX-License-Identifier: Apache-2.0
"""f24_mul against model.f24.mul: random patterns, values near 1.0 and the directed set.

Run at every latency the unit accepts (LAT 1, the default, built with no parameter; 2; 3), each
with the same stimulus; fp_unit.check_pipeline drops en_i at random and checks the latency, the
hold while en_i = 0 and every result bit.  test_f24_mul_lats checks that exactly these LATs
elaborate.
make test runs USED_LATS only (the design's), make test-long every one.
"""
from pathlib import Path

import cocotb
import numpy as np
import pytest

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
    lat = fp_unit.latency(DEFAULT_LAT)
    n = await fp_unit.check_pipeline(dut, lat, {"a_i": a, "b_i": b}, {"y_o": f24.mul(a, b)}, rng)
    dut._log.info("VECTORS f24_mul LAT=%d: %d (%d directed, %d random), 0 mismatches", lat, n,
                  len(da), len(ra))


@pytest.mark.parametrize("lat", fp_unit.lat_cases(LATS, USED_LATS))
def test_f24_mul(lat: int):
    fp_unit.run_lat("f24_mul", "test_f24_mul", Path(__file__).parent, lat, DEFAULT_LAT)


def test_f24_mul_lats():
    fp_unit.check_lats("f24_mul", LATS)
