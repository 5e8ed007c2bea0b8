# SPDX-License-Identifier: Apache-2.0
"""f24_div against model.f24.div: random patterns, values near 1.0 and the directed set.

Run at three latencies, all in one build (fp_unit.run_lats: one instance per LAT on the same
stimulus and en_i): LAT = 2 (the default, the paper's: the whole division loop in stage 1; built
with no parameter), the deep divider the design instantiates (f24_pkg::F24_DIV_LAT: 3 quotient
bits per stage) and an odd split of the loop (LAT = 5: 5, 5, 5 and 4 bits per stage).
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold while
en_i = 0 and every result bit.
"""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit
from tb.harness import sv_params


#: The unit's default latency (the paper's).
DEFAULT_LAT = 2


def design_lat() -> int:
    """f24_pkg::F24_DIV_LAT, the latency the design instantiates."""
    return sv_params.value("f24_pkg", "F24_DIV_LAT")


@cocotb.test()
async def div_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    da, db = vec.directed_binary("div", rng)
    ra, rb = vec.random_binary(rng, fp_unit.vectors())
    a, b = np.concatenate([da, ra]), np.concatenate([db, rb])
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(dut, lanes, {"a_i": a, "b_i": b}, {"y_o": f24.div(a, b)}, rng)
    dut._log.info("VECTORS f24_div LAT=%s: %d each (%d directed, %d random), 0 mismatches",
                  fp_unit.lat_list(lanes), n, len(da), len(ra))


def test_f24_div():
    """LAT 2 (the default: no parameter given), f24_pkg::F24_DIV_LAT and 5."""
    fp_unit.run_lats("f24_div", "test_f24_div", Path(__file__).parent,
                     sorted({DEFAULT_LAT, design_lat(), 5}), DEFAULT_LAT)
