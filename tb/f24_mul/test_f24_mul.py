"""f24_mul against model.f24.mul: random patterns, values near 1.0 and the directed set."""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner

LATENCY = 1


@cocotb.test()
async def mul_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    da, db = vec.directed_binary("mul", rng)
    ra, rb = vec.random_binary(rng, fp_unit.vectors())
    a, b = np.concatenate([da, ra]), np.concatenate([db, rb])
    n = await fp_unit.check_pipeline(dut, LATENCY, {"a_i": a, "b_i": b}, {"y_o": f24.mul(a, b)}, rng)
    dut._log.info("VECTORS f24_mul: %d (%d directed, %d random), 0 mismatches", n, len(da), len(ra))


def test_f24_mul():
    runner.run("f24_mul", "test_f24_mul", Path(__file__).parent)
