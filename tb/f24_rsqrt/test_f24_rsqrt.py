# SPDX-License-Identifier: Apache-2.0
"""f24_rsqrt against model.f24.rsqrt: all fractions at several exponents, specials, random.

Run at LAT = 2 (the default, no parameter given) and LAT = 3 (the deeper pipeline), both in one
build (tb.common.approx_unit.run): the same stimulus, each instance checked at its latency.
"""
from pathlib import Path

from model import f24
from tb.common import approx_unit

rsqrt_every_fraction, rsqrt_specials, rsqrt_random = approx_unit.unary_tests("f24_rsqrt", f24.rsqrt)


def test_f24_rsqrt():
    """LAT 2 (the default) and 3."""
    approx_unit.run("f24_rsqrt", Path(__file__).parent)
