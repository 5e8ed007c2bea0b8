# SPDX-License-Identifier: Apache-2.0
"""f24_rsqrt against model.f24.rsqrt: all fractions at several exponents, specials, random.

Run once per latency: LAT = 2 (the default, no parameter given) and LAT = 3 (the deeper pipeline).
"""
from pathlib import Path

import pytest

from model import f24
from tb.common import runner
from tb.common.approx_unit import LATS, unary_tests

rsqrt_every_fraction, rsqrt_specials, rsqrt_random = unary_tests("f24_rsqrt", f24.rsqrt)


def test_f24_rsqrt():
    """The default: no parameter given, latency 2."""
    runner.run("f24_rsqrt", "test_f24_rsqrt", Path(__file__).parent, extra_env={"APPROX_LAT": "2"})


@pytest.mark.parametrize("lat", [lat for lat in LATS if lat != 2])
def test_f24_rsqrt_lat(lat: int):
    runner.run("f24_rsqrt", "test_f24_rsqrt", Path(__file__).parent, parameters={"LAT": lat},
               extra_env={"APPROX_LAT": str(lat)})
