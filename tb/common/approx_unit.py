# SPDX-License-Identifier: Apache-2.0
"""The cocotb tests shared by the approximate one-operand units (f24_rsqrt, f24_log2).

Each unit is checked against its bit-exact model on every fraction at several exponents, on the
special values and on random patterns; ``unary_tests`` builds the three cocotb tests for a unit.
The latency under test is the environment's APPROX_LAT (the unit's LAT parameter; default 2).
"""
from __future__ import annotations

import os
from typing import Callable

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner

#: The latencies the units are built and checked at (their LAT parameter; 2 is the default).
LATS = (2, 3)
#: Biased exponents swept over all 2^16 fractions under make test-long (TB_LONG=1), at every
#: latency: both parities (both tables) and the range ends.
EXPONENTS = (1, 2, 62, 63, 64, 65, 125, 126)
#: The sweep at the default latency in make test: both parities, both range ends and the two
#: exponents around 1.0 (half of EXPONENTS: the other four only under make test-long).
EXPONENTS_DEFAULT_LAT = (1, 63, 64, 126)
#: The sweep at the other latencies in make test (the same tables and datapath, registers placed
#: elsewhere): one exponent of each parity.
EXPONENTS_OTHER_LAT = (63, 64)


def exponents(latency: int) -> tuple[int, ...]:
    """The exponents whose every fraction is checked at ``latency``."""
    if runner.long_stimulus():
        return EXPONENTS
    return EXPONENTS_DEFAULT_LAT if latency == 2 else EXPONENTS_OTHER_LAT


def every_fraction(exps: tuple[int, ...]) -> np.ndarray:
    f = np.arange(1 << f24.FRAC_BITS, dtype=np.uint32)
    return np.concatenate([f24.pack(0, e, f) for e in exps]).astype(np.uint32)


def specials() -> np.ndarray:
    """The shared special set with both signs, every class of zero / Inf / NaN, and negatives."""
    s = vec.SPECIALS
    extra = np.array([0x000000, 0x800000, 0x00ffff, 0x80ffff, 0x7f0000, 0xff0000, 0x7f0001,
                      0xff8000, 0xbf0000, 0x810000, 0xfeffff], dtype=np.uint32)
    return np.concatenate([s, s ^ np.uint32(f24.SIGN_BIT), extra]).astype(np.uint32)


def unary_tests(unit: str, model: Callable[[np.ndarray], np.ndarray]) -> tuple:
    """(every_fraction, specials, random) cocotb tests of ``unit`` against ``model``."""
    prefix = unit.removeprefix("f24_")

    async def run(dut, what: str, a: np.ndarray, rng: np.random.Generator) -> None:
        latency = int(os.environ.get("APPROX_LAT", "2"))
        n = await fp_unit.check_pipeline(dut, latency, {"a_i": a}, {"y_o": model(a)}, rng)
        dut._log.info("VECTORS %s LAT=%d %s: %d, 0 mismatches", unit, latency, what, n)

    async def every_fraction_test(dut):
        rng = np.random.default_rng(fp_unit.seed())
        exps = exponents(int(os.environ.get("APPROX_LAT", "2")))
        await run(dut, f"every fraction at biased exponents {exps}", every_fraction(exps), rng)

    async def specials_test(dut):
        rng = np.random.default_rng(fp_unit.seed())
        await run(dut, "specials", specials(), rng)

    async def random_test(dut):
        """fp_unit.vectors() patterns: half random bits, half near 1.0; every other one positive."""
        rng = np.random.default_rng(fp_unit.seed())
        a = vec.random_unary(rng, fp_unit.vectors())
        a[::2] &= np.uint32(f24.MASK24 ^ f24.SIGN_BIT)
        await run(dut, "random", a, rng)

    tests = []
    for fn, name in ((every_fraction_test, "every_fraction"), (specials_test, "specials"),
                     (random_test, "random")):
        fn.__name__ = fn.__qualname__ = f"{prefix}_{name}"
        tests.append(cocotb.test()(fn))
    return tuple(tests)
