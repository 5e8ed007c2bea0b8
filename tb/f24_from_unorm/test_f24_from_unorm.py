"""f24_from_unorm against model.f24.from_unorm: every code, several times, in shuffled orders.

The DUT's width W (8 or 16) is read from the width of ``k_i``; the pytest functions build W = 8 and
W = 16.
"""
from pathlib import Path

import cocotb
import numpy as np

from model import f24
from tb.common import fp_unit, runner

LATENCY = 1


@cocotb.test()
async def from_unorm_all_codes(dut):
    rng = np.random.default_rng(fp_unit.seed())
    w = len(dut.k_i)
    codes = np.arange(1 << w, dtype=np.uint32)
    rounds = 8 if w <= 8 else 1
    # In order first (neighbouring codes), then shuffled passes.
    k = np.concatenate([codes] + [rng.permutation(codes) for _ in range(rounds)])
    n = await fp_unit.check_pipeline(dut, LATENCY, {"k_i": k}, {"y_o": f24.from_unorm(k, w)}, rng)
    dut._log.info("VECTORS f24_from_unorm W=%d: %d (all %d codes %d times), 0 mismatches",
                  w, n, 1 << w, rounds + 1)


def test_f24_from_unorm_w8():
    runner.run("f24_from_unorm", "test_f24_from_unorm", Path(__file__).parent, parameters={"W": 8})


def test_f24_from_unorm_w16():
    runner.run("f24_from_unorm", "test_f24_from_unorm", Path(__file__).parent, parameters={"W": 16})
