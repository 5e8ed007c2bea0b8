"""f24_cmp against model.f24.cmp: random patterns, values near 1.0 and the directed set."""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner

LATENCY = 1


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
    n = await fp_unit.check_pipeline(dut, LATENCY, {"a_i": a, "b_i": b}, exp, rng)
    dut._log.info("VECTORS f24_cmp: %d (%d directed, %d random), 0 mismatches", n, len(da) + 8192,
                  len(ra))


def test_f24_cmp():
    runner.run("f24_cmp", "test_f24_cmp", Path(__file__).parent)
