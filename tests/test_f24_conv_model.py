# SPDX-License-Identifier: Apache-2.0
"""model.f24_conv against independent references.

* from_unorm: every code for 8 and 16 bits against MPFR (gmpy2, 17-bit precision, round to nearest
  even, exponent range wide enough to be unbounded here) on the exact rational k / (2^n - 1), and
  against exact ``fractions.Fraction`` rounding.
* to_index: all 2^24 patterns against math-style floor on the decoded float64 values, clamped.
* from_int: the whole signed 20-bit range against MPFR (17-bit, RNE) on the integer.
"""
from __future__ import annotations

from fractions import Fraction

import gmpy2
import numpy as np
import pytest

from model import f24, f24_conv


def _mpfr_ctx() -> gmpy2.context:
    return gmpy2.context(precision=17, round=gmpy2.RoundToNearest, emax=1 << 20, emin=-(1 << 20),
                         subnormalize=False)


def _patterns(v: list[float]) -> np.ndarray:
    """Values with at most 17 significant bits, in range, as their f24 patterns (exact)."""
    return f24.from_float(np.array(v, dtype=np.float64))


def _round_fraction(q: Fraction) -> float:
    """Round a non-negative rational to 17 significant bits, ties to even, exactly."""
    if q == 0:
        return 0.0
    e = q.numerator.bit_length() - q.denominator.bit_length()
    if Fraction(2) ** e > q:
        e -= 1
    # q in [2^e, 2^(e+1)): scale to [2^16, 2^17)
    scaled = q / Fraction(2) ** (e - 16)
    sig = scaled.numerator // scaled.denominator
    rem = scaled - sig
    if rem > Fraction(1, 2) or (rem == Fraction(1, 2) and sig % 2 == 1):
        sig += 1
    return float(Fraction(sig) * Fraction(2) ** (e - 16))


@pytest.mark.parametrize("bits", [8, 16])
def test_from_unorm_exhaustive(bits: int) -> None:
    d = (1 << bits) - 1
    k = np.arange(d + 1, dtype=np.int64)
    got = f24.from_unorm(k, bits)
    assert got.dtype == np.uint32 and got.shape == k.shape
    with gmpy2.context(_mpfr_ctx()):
        ref_mpfr = _patterns([float(gmpy2.mpfr(gmpy2.mpq(int(i), d))) for i in k])
    ref_frac = _patterns([_round_fraction(Fraction(int(i), d)) for i in k])
    bad = int(np.count_nonzero(got != ref_mpfr))
    bad_frac = int(np.count_nonzero(got != ref_frac))
    print(f"\nfrom_unorm bits={bits}: {len(k)} codes, {bad} mismatches vs MPFR, "
          f"{bad_frac} vs Fraction")
    assert bad == 0 and bad_frac == 0
    assert got[0] == f24.POS_ZERO and got[-1] == f24.ONE
    # Monotone, and every code maps to a distinct float (17 bits is enough for 16-bit unorm).
    assert np.all(np.diff(f24.to_float(got)) > 0)


def test_from_unorm_errors() -> None:
    with pytest.raises(ValueError):
        f24.from_unorm(np.array([1]), 10)
    with pytest.raises(ValueError):
        f24.from_unorm(np.array([256]), 8)
    with pytest.raises(ValueError):
        f24.from_unorm(np.array([-1]), 8)
    with pytest.raises(TypeError):
        f24.from_unorm(np.array([0.5]), 8)
    assert f24.from_unorm(np.zeros((2, 3), dtype=np.uint8), 8).shape == (2, 3)


def _to_index_ref(bits: np.ndarray, width: int) -> tuple[np.ndarray, np.ndarray]:
    """Independent reference: floor of the decoded float64 value, clamped; NaN -> (0, True).

    float64 holds every f24 value and its floor exactly; the range ends are compared as the
    powers of two +-2^(width-1) (exact in float64), the clamped values are set as integers.
    """
    lim = 2.0 ** (width - 1)
    v = f24.to_float(bits)
    nan = np.isnan(v)
    fl = np.floor(np.where(nan, 0.0, v))
    over, under = fl >= lim, fl < -lim
    idx = np.where(over | under, 0.0, fl).astype(np.int64)
    idx = np.where(over, (1 << (width - 1)) - 1, np.where(under, -(1 << (width - 1)), idx))
    return np.where(nan, 0, idx), over | under | nan


@pytest.mark.parametrize("width", [20, 8, 2, 62])
def test_to_index_all_patterns(width: int) -> None:
    x = np.arange(1 << 24, dtype=np.uint32)
    idx, sat = f24.to_index(x, width)
    assert idx.dtype == np.int64 and sat.dtype == np.bool_
    ridx, rsat = _to_index_ref(x, width)
    bad = int(np.count_nonzero((idx != ridx) | (sat != rsat)))
    print(f"\nto_index width={width}: {len(x)} patterns, {int(sat.sum())} saturated, "
          f"{bad} mismatches")
    assert bad == 0


def test_to_index_directed() -> None:
    vals = [-0.5, -1.0, -1.5, 0.5, 0.0, -0.0, 1.0, 2.75, -2.75, 524284.0, -524288.0, 524288.0,
            -524296.0, np.inf, -np.inf]
    exp = [(-1, False), (-1, False), (-2, False), (0, False), (0, False), (0, False), (1, False),
           (2, False), (-3, False), (524284, False), (-524288, False), (524287, True),
           (-524288, True), (524287, True), (-524288, True)]
    idx, sat = f24.to_index(f24.from_float(np.array(vals)))
    assert [(int(i), bool(s)) for i, s in zip(idx, sat)] == exp
    idx, sat = f24.to_index(np.array([f24.NAN, 0xFFFFFF, 0x800001, 0x00FFFF], dtype=np.uint32))
    assert list(idx) == [0, 0, 0, 0] and list(sat) == [True, True, False, False]
    with pytest.raises(ValueError):
        f24.to_index(np.array([0]), 1)


@pytest.mark.parametrize("width", [20])
def test_from_int_exhaustive(width: int) -> None:
    k = np.arange(-(1 << (width - 1)), 1 << (width - 1), dtype=np.int64)
    got = f24.from_int(k, width)
    assert got.dtype == np.uint32
    with gmpy2.context(_mpfr_ctx()):
        ref = _patterns([float(gmpy2.mpfr(int(i))) for i in k])
    bad = int(np.count_nonzero(got != ref))
    exact = int(np.count_nonzero(f24.to_float(got) == k))
    print(f"\nfrom_int width={width}: {len(k)} values, {exact} exact, {bad} mismatches vs MPFR")
    assert bad == 0
    # Exact: |k| < 2^17 (2^18 - 1 values), even |k| in [2^17, 2^18) and multiples of 4 in
    # [2^18, 2^19) (2^16 per sign each), and -2^19: 2^19 values in all.
    assert exact == 1 << 19


def test_from_int_wide_random() -> None:
    rng = np.random.default_rng(1)
    for width in (2, 8, 17, 18, 32, 62):
        lo, hi = -(1 << (width - 1)), (1 << (width - 1)) - 1
        k = np.concatenate([rng.integers(lo, hi, 20000, endpoint=True),
                            np.array([lo, hi, 0, -1, 1, lo + 1, hi - 1])])
        with gmpy2.context(_mpfr_ctx()):
            ref = _patterns([float(gmpy2.mpfr(int(i))) for i in k])
        bad = int(np.count_nonzero(f24.from_int(k, width) != ref))
        print(f"\nfrom_int width={width}: {len(k)} random values, {bad} mismatches vs MPFR")
        assert bad == 0


def test_from_int_errors() -> None:
    with pytest.raises(ValueError):
        f24.from_int(np.array([1 << 19]), 20)
    with pytest.raises(ValueError):
        f24.from_int(np.array([-(1 << 19) - 1]), 20)
    with pytest.raises(ValueError):
        f24.from_int(np.array([0]), 63)
    with pytest.raises(TypeError):
        f24.from_int(np.array([1.0]), 20)
    assert int(f24.from_int(np.array([0]))[0]) == f24.POS_ZERO


def test_reexported() -> None:
    assert f24.from_unorm is f24_conv.from_unorm
    assert f24.from_int is f24_conv.from_int
    assert f24.to_index is f24_conv.to_index
