# SPDX-License-Identifier: Apache-2.0
"""f24_add against model.f24.add: random patterns, values near 1.0 and the directed set.

Run at every latency the unit accepts (LAT 2, the default, built with no parameter; 3; 4), all
in one build (fp_unit.run_lats: one instance per LAT on the same stimulus and en_i);
fp_unit.check_pipeline drops en_i at random and checks each instance's latency, its hold while
en_i = 0 and every result bit.  test_f24_add_lats checks that exactly these LATs elaborate.
"""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit

#: The unit's default latency (the paper's) and every LAT it accepts.
DEFAULT_LAT = 2
LATS = (2, 3, 4)


def binade_edges(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """a near a power of two minus b, exponent difference 0..24 (the result drops a binade, guard
    and sticky decide), b's fraction at its ends and at the halfway patterns."""
    fa = np.array([0x0000, 0x0001, 0xffff], dtype=np.uint32)
    fb = np.array([0x0000, 0x0001, 0x7fff, 0x8000, 0x8001, 0xfffe, 0xffff], dtype=np.uint32)
    parts_a, parts_b = [], []
    for d in range(25):
        ea = rng.integers(2 + d, 127, 8, dtype=np.uint32)
        ga, gb, ge = np.meshgrid(fa, fb, ea, indexing="ij")
        s = rng.integers(0, 2, ga.size, dtype=np.uint32)
        parts_a.append(f24.pack(s, ge.ravel(), ga.ravel()))
        parts_b.append(f24.pack(1 - s, ge.ravel() - d, gb.ravel()))
    return np.concatenate(parts_a), np.concatenate(parts_b)


@cocotb.test()
async def add_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    da, db = vec.directed_binary("add", rng)
    ea, eb = binade_edges(rng)
    da, db = np.concatenate([da, ea, eb]), np.concatenate([db, eb, ea])
    ra, rb = vec.random_binary(rng, fp_unit.vectors())
    a, b = np.concatenate([da, ra]), np.concatenate([db, rb])
    # Inf - Inf in the float64 model: NaN is the expected result
    with np.errstate(invalid="ignore"):
        y = f24.add(a, b)
    lanes = fp_unit.lanes(dut)
    n = await fp_unit.check_pipeline(dut, lanes, {"a_i": a, "b_i": b}, {"y_o": y}, rng)
    dut._log.info("VECTORS f24_add LAT=%s: %d each (%d directed, %d random), 0 mismatches",
                  fp_unit.lat_list(lanes), n, len(da), len(ra))


def test_f24_add():
    fp_unit.run_lats("f24_add", "test_f24_add", Path(__file__).parent, LATS, DEFAULT_LAT)


def test_f24_add_lats():
    fp_unit.check_lats("f24_add", LATS)
