# SPDX-License-Identifier: Apache-2.0
"""f24_div against model.f24.div: random patterns, values near 1.0 and the directed set.

Run once per latency parameter: LAT = 2 (the default, the paper's: the whole division loop in
stage 1), the deep divider the design instantiates (f24_pkg::F24_DIV_LAT: 3 quotient bits per
stage) and an odd split of the loop (LAT = 5: 5, 5, 5 and 4 bits per stage).
fp_unit.check_pipeline drops en_i at random and checks the latency, the hold while en_i = 0 and
every result bit.
"""
import os
import re
from pathlib import Path

import cocotb
import numpy as np
import pytest

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner
from tb.harness import sv_params


def design_lat() -> int:
    """f24_pkg::F24_DIV_LAT, the latency the design instantiates."""
    return sv_params.value("f24_pkg", "F24_DIV_LAT")


@cocotb.test()
async def div_random_and_directed(dut):
    latency = int(os.environ["DIV_LAT"])
    rng = np.random.default_rng(fp_unit.seed())
    da, db = vec.directed_binary("div", rng)
    ra, rb = vec.random_binary(rng, fp_unit.vectors())
    a, b = np.concatenate([da, ra]), np.concatenate([db, rb])
    n = await fp_unit.check_pipeline(dut, latency, {"a_i": a, "b_i": b}, {"y_o": f24.div(a, b)},
                                     rng)
    dut._log.info("VECTORS f24_div LAT=%d: %d (%d directed, %d random), 0 mismatches", latency, n,
                  len(da), len(ra))


def test_f24_div():
    """The default: no parameter given, latency 2."""
    runner.run("f24_div", "test_f24_div", Path(__file__).parent, extra_env={"DIV_LAT": "2"})


@pytest.mark.parametrize("lat", sorted({design_lat(), 5}))
def test_f24_div_lat(lat: int):
    runner.run("f24_div", "test_f24_div", Path(__file__).parent, parameters={"LAT": lat},
               extra_env={"DIV_LAT": str(lat)})
