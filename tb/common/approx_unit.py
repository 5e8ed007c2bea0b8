# SPDX-License-Identifier: Apache-2.0
"""The cocotb tests shared by the approximate one-operand units (f24_rsqrt, f24_log2).

Each unit is checked against its bit-exact model on every fraction at several exponents, on the
special values and on random patterns; ``unary_tests`` builds the three cocotb tests for a unit
and ``run`` its build: the unit at every latency of :data:`LATS` (its LAT parameter; 2, the
default, built with no parameter), all in one build (``fp_unit.run_lats``: one instance per LAT on
the same stimulus and en_i), each instance checked at its own latency.
"""
from __future__ import annotations

from pathlib import Path
from typing import Callable, Sequence

import cocotb
import numpy as np

from model import f24, f24_vectors as vec
from tb.common import fp_unit, runner

#: The latencies the units are built and checked at (their LAT parameter; 2 is the default).
LATS = (2, 3)
#: The units' default latency.
DEFAULT_LAT = 2
#: Biased exponents swept over all 2^16 fractions under make test-long (TB_LONG=1), at every
#: latency: both parities (both tables) and the range ends.
EXPONENTS = (1, 2, 62, 63, 64, 65, 125, 126)
#: The sweep at the default latency in make test: both parities, both range ends and the two
#: exponents around 1.0 (half of EXPONENTS: the other four only under make test-long).
EXPONENTS_DEFAULT_LAT = (1, 63, 64, 126)
#: The sweep at the other latencies in make test (the same tables and datapath, registers placed
#: elsewhere): one exponent of each parity.  A build holding the default latency too checks every
#: instance on the default's sweep (one stream for all).
EXPONENTS_OTHER_LAT = (63, 64)


def exponents(latencies: Sequence[int]) -> tuple[int, ...]:
    """The exponents whose every fraction is checked in a build of ``latencies``: each one's
    sweep (all of them under make test-long), merged."""
    if runner.long_stimulus():
        return EXPONENTS
    return tuple(sorted({e for lat in latencies
                         for e in (EXPONENTS_DEFAULT_LAT if lat == 2 else EXPONENTS_OTHER_LAT)}))


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
        lanes = fp_unit.lanes(dut)
        n = await fp_unit.check_pipeline(dut, lanes, {"a_i": a}, {"y_o": model(a)}, rng)
        dut._log.info("VECTORS %s LAT=%s %s: %d each, 0 mismatches", unit,
                      fp_unit.lat_list(lanes), what, n)

    async def every_fraction_test(dut):
        rng = np.random.default_rng(fp_unit.seed())
        exps = exponents([lane.latency for lane in fp_unit.lanes(dut)])
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


def run(unit: str, test_dir: Path) -> None:
    """Build ``unit`` at every latency of :data:`LATS` and run its cocotb tests
    (``test_<unit>`` in ``test_dir``)."""
    fp_unit.run_lats(unit, f"test_{unit}", test_dir, LATS, DEFAULT_LAT)
