# SPDX-License-Identifier: Apache-2.0
"""Bit-accurate model of the 24-bit floating-point format and its units.

The format (see ``docs/number-format.md``): 1 sign bit, 7 exponent bits with bias 63,
16 fraction bits.  Zero exponent is a signed zero (subnormal inputs flush to zero), exponent 127 is
Inf (fraction 0) or NaN (fraction != 0); every NaN a unit produces is :data:`NAN` (0x7F8000).

Every function works on numpy arrays of raw patterns (``uint32``, value in the low 24 bits) and is
vectorised.  Add, sub, mul, div and sqrt are correctly rounded: the operands are exact in float64,
float64 has more than 2*17+2 significand bits, so the float64 result rounded once more to 17 bits
is the correctly rounded result (no double-rounding error).  :func:`from_float` does that rounding:
round to 17 significant bits, ties to even, with an unbounded exponent; then overflow to +-Inf and
flush results below 2^-62 to a zero of the result's sign.

The conversions and the approximate units (reciprocal square root, log2) live in
:mod:`model.f24_conv` and :mod:`model.f24_approx` and are re-exported here, so that
``model.f24`` is the one API the RTL is checked against.
"""
from __future__ import annotations

import numpy as np
import numpy.typing as npt

U32 = npt.NDArray[np.uint32]
F64 = npt.NDArray[np.float64]

SIGN_BIT = 1 << 23
EXP_BITS = 7
FRAC_BITS = 16
BIAS = 63
EXP_MAX = (1 << EXP_BITS) - 1  # 127: Inf / NaN
FRAC_MASK = (1 << FRAC_BITS) - 1
MASK24 = (1 << 24) - 1

POS_ZERO = 0x000000
NEG_ZERO = 0x800000
POS_INF = 0x7F0000
NEG_INF = 0xFF0000
NAN = 0x7F8000
MAX_FINITE = 0x7EFFFF
MIN_NORMAL = 0x010000
ONE = 0x3F0000

#: Largest finite value, 2^63 * (2 - 2^-16).
MAX_VALUE = 2.0**63 * (2.0 - 2.0**-16)
#: Smallest normal value, 2^-62.
MIN_VALUE = 2.0**-62


def _u32(x: npt.ArrayLike) -> U32:
    return np.asarray(x).astype(np.uint32) & np.uint32(MASK24)


def fields(bits: npt.ArrayLike) -> tuple[U32, U32, U32]:
    """Split patterns into (sign, biased exponent, fraction)."""
    b = _u32(bits)
    return b >> np.uint32(23), (b >> np.uint32(16)) & np.uint32(EXP_MAX), b & np.uint32(FRAC_MASK)


def pack(sign: npt.ArrayLike, exp: npt.ArrayLike, frac: npt.ArrayLike) -> U32:
    """Pack fields into patterns (no checks)."""
    s = np.asarray(sign).astype(np.uint32)
    e = np.asarray(exp).astype(np.uint32)
    f = np.asarray(frac).astype(np.uint32)
    return (s << np.uint32(23)) | (e << np.uint32(16)) | f


def is_nan(bits: npt.ArrayLike) -> npt.NDArray[np.bool_]:
    _, e, f = fields(bits)
    return (e == EXP_MAX) & (f != 0)


def is_inf(bits: npt.ArrayLike) -> npt.NDArray[np.bool_]:
    _, e, f = fields(bits)
    return (e == EXP_MAX) & (f == 0)


def is_zero(bits: npt.ArrayLike) -> npt.NDArray[np.bool_]:
    """True for both zeros and for subnormal patterns (which read as zero)."""
    _, e, _ = fields(bits)
    return e == 0


def to_float(bits: npt.ArrayLike) -> F64:
    """Decode patterns to float64 (exact).  Subnormal patterns read as signed zeros."""
    s, e, f = fields(bits)
    mag = np.ldexp(1.0 + f.astype(np.float64) / 65536.0, e.astype(np.int64) - BIAS)
    mag = np.where(e == 0, 0.0, mag)
    mag = np.where(e == EXP_MAX, np.where(f == 0, np.inf, np.nan), mag)
    return np.where(s == 1, -mag, mag)


def from_float(x: npt.ArrayLike) -> U32:
    """Round float64 values to the 24-bit format (RNE to 17 bits, then overflow / flush)."""
    xa = np.asarray(x, dtype=np.float64)
    sign = np.signbit(xa).astype(np.uint32)
    mag = np.abs(xa)
    finite = np.isfinite(mag) & (mag > 0)
    m, e = np.frexp(np.where(finite, mag, 1.0))  # mag = m * 2^e, m in [0.5, 1)
    sig = np.rint(m * 131072.0).astype(np.int64)  # 17 bits, ties to even; may round up to 2^17
    carry = sig >= (1 << 17)
    sig = np.where(carry, sig >> 1, sig)
    bexp = e.astype(np.int64) + 62 + carry  # value = sig/2^16 * 2^(e-1)
    out = pack(sign, np.clip(bexp, 0, EXP_MAX), sig & FRAC_MASK)
    out = np.where(bexp > 126, pack(sign, EXP_MAX, 0), out)  # overflow after rounding
    out = np.where(bexp < 1, pack(sign, 0, 0), out)  # flush after rounding
    out = np.where(mag == 0, pack(sign, 0, 0), out)
    out = np.where(np.isinf(mag), pack(sign, EXP_MAX, 0), out)
    out = np.where(np.isnan(xa), np.uint32(NAN), out)
    return out.astype(np.uint32)


def add(a: npt.ArrayLike, b: npt.ArrayLike) -> U32:
    """a + b, correctly rounded."""
    with np.errstate(invalid="ignore"):  # Inf - Inf is NaN by design
        return from_float(to_float(a) + to_float(b))


def sub(a: npt.ArrayLike, b: npt.ArrayLike) -> U32:
    """a - b (the adder with b's sign flipped)."""
    return add(a, _u32(b) ^ np.uint32(SIGN_BIT))


def mul(a: npt.ArrayLike, b: npt.ArrayLike) -> U32:
    """a * b, correctly rounded."""
    with np.errstate(invalid="ignore"):  # 0 * Inf is NaN by design
        return from_float(to_float(a) * to_float(b))


def div(a: npt.ArrayLike, b: npt.ArrayLike) -> U32:
    """a / b, correctly rounded; finite / 0 is a signed Inf, 0/0 and Inf/Inf are NaN."""
    fa, fb = to_float(a), to_float(b)
    with np.errstate(divide="ignore", invalid="ignore"):
        return from_float(fa / fb)


def sqrt(a: npt.ArrayLike) -> U32:
    """Square root, correctly rounded; sqrt(-0) = -0, sqrt of a negative number is NaN."""
    fa = to_float(a)
    with np.errstate(invalid="ignore"):
        return from_float(np.sqrt(fa))


def cmp(a: npt.ArrayLike, b: npt.ArrayLike) -> tuple[npt.NDArray[np.bool_], ...]:
    """Compare: returns (lt, eq, gt, un); -0 == +0, any NaN operand is unordered."""
    fa, fb = to_float(a), to_float(b)
    un = np.isnan(fa) | np.isnan(fb)
    with np.errstate(invalid="ignore"):
        return (fa < fb) & ~un, (fa == fb) & ~un, (fa > fb) & ~un, un


def neg(a: npt.ArrayLike) -> U32:
    """Flip the sign bit (exact, as the hardware does it with a wire)."""
    return _u32(a) ^ np.uint32(SIGN_BIT)


def abs_(a: npt.ArrayLike) -> U32:
    """Clear the sign bit."""
    return _u32(a) & np.uint32(MASK24 ^ SIGN_BIT)


# Conversions and approximate units: same API, own modules (re-exported).
from .f24_conv import from_unorm, from_int, to_index  # noqa: E402,F401
from .f24_approx import rsqrt, log2, RSQRT_MAX_ULP, LOG2_MAX_ABS_ERR  # noqa: E402,F401


def round_value(x: npt.ArrayLike) -> F64:
    """float64 -> the nearest f24 value, as float64: ``to_float(from_float(x))``, but fast.

    The traversal's f24 engine keeps its numbers as float64 values that are always exactly
    representable in the format, rounding after every operation with this function.
    """
    xa = np.asarray(x, dtype=np.float64)
    b = xa.view(np.uint64)
    lsb = (b >> np.uint64(36)) & np.uint64(1)
    b = (b + np.uint64((1 << 35) - 1) + lsb) & ~np.uint64((1 << 36) - 1)  # RNE to 17 bits
    y = b.view(np.float64)
    mag = np.abs(y)
    y = np.where(mag > MAX_VALUE, np.copysign(np.inf, xa), y)
    y = np.where(mag < MIN_VALUE, np.copysign(0.0, xa), y)
    return np.where(np.isnan(xa), np.nan, y)
