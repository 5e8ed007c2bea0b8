# SPDX-License-Identifier: Apache-2.0
"""f24_log2 against model.f24.log2: all fractions at several exponents, specials, random.

Run once per latency: LAT = 2 (the default, no parameter given) and LAT = 3 (the deeper pipeline).
"""
from pathlib import Path

import pytest

from model import f24
from tb.common import runner
from tb.common.approx_unit import LATS, unary_tests

log2_every_fraction, log2_specials, log2_random = unary_tests("f24_log2", f24.log2)


def test_f24_log2():
    """The default: no parameter given, latency 2."""
    runner.run("f24_log2", "test_f24_log2", Path(__file__).parent, extra_env={"APPROX_LAT": "2"})


@pytest.mark.parametrize("lat", [lat for lat in LATS if lat != 2])
def test_f24_log2_lat(lat: int):
    runner.run("f24_log2", "test_f24_log2", Path(__file__).parent, parameters={"LAT": lat},
               extra_env={"APPROX_LAT": str(lat)})
