# SPDX-License-Identifier: Apache-2.0
"""f24_log2 against model.f24.log2: all fractions at several exponents, specials, random.

Run at LAT = 2 (the default, no parameter given) and LAT = 3 (the deeper pipeline), both in one
build (tb.common.approx_unit.run): the same stimulus, each instance checked at its latency.
"""
from pathlib import Path

from model import f24
from tb.common import approx_unit

log2_every_fraction, log2_specials, log2_random = approx_unit.unary_tests("f24_log2", f24.log2)


def test_f24_log2():
    """LAT 2 (the default) and 3."""
    approx_unit.run("f24_log2", Path(__file__).parent)
