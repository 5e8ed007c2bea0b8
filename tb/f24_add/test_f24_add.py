"""f24_add against model.f24.add: random patterns, values near 1.0 and the directed set."""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner

LATENCY = 2


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
    with np.errstate(invalid="ignore"):  # Inf - Inf in the float64 model: NaN is the expected result
        y = f24.add(a, b)
    n = await fp_unit.check_pipeline(dut, LATENCY, {"a_i": a, "b_i": b}, {"y_o": y}, rng)
    dut._log.info("VECTORS f24_add: %d (%d directed, %d random), 0 mismatches", n, len(da), len(ra))


def test_f24_add():
    runner.run("f24_add", "test_f24_add", Path(__file__).parent)
