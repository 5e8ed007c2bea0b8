"""f24_rsqrt against model.f24.rsqrt: all fractions at several exponents, specials, random."""
from pathlib import Path

from model import f24
from tb.common import runner
from tb.common.approx_unit import unary_tests

rsqrt_every_fraction, rsqrt_specials, rsqrt_random = unary_tests("f24_rsqrt", f24.rsqrt)


def test_f24_rsqrt():
    runner.run("f24_rsqrt", "test_f24_rsqrt", Path(__file__).parent)
