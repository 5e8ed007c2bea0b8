"""f24_log2 against model.f24.log2: all fractions at several exponents, specials, random."""
from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner

LATENCY = 2
#: Biased exponents swept over all 2^16 fractions: both parities (both tables) and the range ends.
EXPONENTS = (1, 2, 62, 63, 64, 65, 125, 126)


def every_fraction(exps) -> np.ndarray:
    f = np.arange(1 << f24.FRAC_BITS, dtype=np.uint32)
    return np.concatenate([f24.pack(0, e, f) for e in exps]).astype(np.uint32)


def specials() -> np.ndarray:
    """The shared special set with both signs, every class of zero / Inf / NaN, and negatives."""
    s = vec.SPECIALS
    extra = np.array([0x000000, 0x800000, 0x00ffff, 0x80ffff, 0x7f0000, 0xff0000, 0x7f0001,
                      0xff8000, 0xbf0000, 0x810000, 0xfeffff], dtype=np.uint32)
    return np.concatenate([s, s ^ np.uint32(f24.SIGN_BIT), extra]).astype(np.uint32)


async def _run(dut, what: str, a: np.ndarray, rng: np.random.Generator) -> None:
    n = await fp_unit.check_pipeline(dut, LATENCY, {"a_i": a}, {"y_o": f24.log2(a)}, rng)
    dut._log.info("VECTORS f24_log2 %s: %d, 0 mismatches", what, n)


@cocotb.test()
async def log2_every_fraction(dut):
    rng = np.random.default_rng(fp_unit.seed())
    a = every_fraction(EXPONENTS)
    await _run(dut, f"every fraction at biased exponents {EXPONENTS}", a, rng)


@cocotb.test()
async def log2_specials(dut):
    rng = np.random.default_rng(fp_unit.seed())
    await _run(dut, "specials", specials(), rng)


@cocotb.test()
async def log2_random(dut):
    """fp_unit.vectors() patterns: half random bits, half near 1.0; every other one positive."""
    rng = np.random.default_rng(fp_unit.seed())
    a = vec.random_unary(rng, fp_unit.vectors())
    a[::2] &= np.uint32(f24.MASK24 ^ f24.SIGN_BIT)
    await _run(dut, "random", a, rng)


def test_f24_log2():
    runner.run("f24_log2", "test_f24_log2", Path(__file__).parent)
