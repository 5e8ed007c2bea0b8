# SPDX-License-Identifier: Apache-2.0
"""f24_sqrt against model.f24.sqrt: random patterns, values near 1.0 and the directed set."""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner

LATENCY = 2


@cocotb.test()
async def sqrt_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    da = vec.directed_unary_sqrt(rng)
    ra = vec.random_unary(rng, fp_unit.vectors())
    a = np.concatenate([da, ra])
    n = await fp_unit.check_pipeline(dut, LATENCY, {"a_i": a}, {"y_o": f24.sqrt(a)}, rng)
    dut._log.info("VECTORS f24_sqrt: %d (%d directed, %d random), 0 mismatches", n, len(da), len(ra))


def test_f24_sqrt():
    runner.run("f24_sqrt", "test_f24_sqrt", Path(__file__).parent)
