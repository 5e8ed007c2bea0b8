"""f24_log2 against model.f24.log2: all fractions at several exponents, specials, random."""
from pathlib import Path

from model import f24
from tb.common import runner
from tb.common.approx_unit import unary_tests

log2_every_fraction, log2_specials, log2_random = unary_tests("f24_log2", f24.log2)


def test_f24_log2():
    runner.run("f24_log2", "test_f24_log2", Path(__file__).parent)
