# SPDX-License-Identifier: Apache-2.0
"""f24_from_unorm against model.f24.from_unorm: every code, several times, in shuffled orders.

The DUT's width W (8 or 16) is read from the width of ``k_i``; the pytest functions build W = 8 and
W = 16.
Run at every latency the unit accepts (LAT 1, the default, built with no parameter, and 2), all in
one build (fp_unit.run_lats: one instance per LAT on the same stimulus and en_i);
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold
while en_i = 0 and every result bit.  test_f24_from_unorm_lats checks that exactly these LATs
elaborate.
make test runs USED_LATS only (the design's), make test-long every one.
"""
from pathlib import Path

import cocotb
import numpy as np
import pytest

from model import f24
from tb.common import fp_unit

#: The unit's default latency and every LAT it accepts.
DEFAULT_LAT = 1
LATS = (1, 2)
#: The widths W tested: 8 (the textures' unorm8), 16.
WIDTHS = (8, 16)
#: The LATs make test runs: the default only (the design builds the unit at its default).
USED_LATS = (DEFAULT_LAT,)


@cocotb.test()
async def from_unorm_all_codes(dut):
    rng = np.random.default_rng(fp_unit.seed())
    w = len(dut.k_i)
    codes = np.arange(1 << w, dtype=np.uint32)
    rounds = 8 if w <= 8 else 1
    # In order first (neighbouring codes), then shuffled passes.
    k = np.concatenate([codes] + [rng.permutation(codes) for _ in range(rounds)])
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(dut, lanes, {"k_i": k}, {"y_o": f24.from_unorm(k, w)}, rng)
    dut._log.info("VECTORS f24_from_unorm W=%d LAT=%s: %d each (all %d codes %d times), "
                  "0 mismatches", w, fp_unit.lat_list(lanes), n, 1 << w, rounds + 1)


@pytest.mark.parametrize("w", [pytest.param(w, id=f"w{w}") for w in WIDTHS])
def test_f24_from_unorm(w: int) -> None:
    """Every LAT under test at width W, in one build."""
    fp_unit.run_lats("f24_from_unorm", "test_f24_from_unorm", Path(__file__).parent,
                     fp_unit.lat_set(LATS, USED_LATS), DEFAULT_LAT, parameters={"W": w})


def test_f24_from_unorm_lats():
    fp_unit.check_lats("f24_from_unorm", LATS)
