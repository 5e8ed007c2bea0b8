"""f24_div against model.f24.div: random patterns, values near 1.0 and the directed set."""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner

LATENCY = 2


@cocotb.test()
async def div_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    da, db = vec.directed_binary("div", rng)
    ra, rb = vec.random_binary(rng, fp_unit.vectors())
    a, b = np.concatenate([da, ra]), np.concatenate([db, rb])
    n = await fp_unit.check_pipeline(dut, LATENCY, {"a_i": a, "b_i": b}, {"y_o": f24.div(a, b)}, rng)
    dut._log.info("VECTORS f24_div: %d (%d directed, %d random), 0 mismatches", n, len(da), len(ra))


def test_f24_div():
    runner.run("f24_div", "test_f24_div", Path(__file__).parent)
