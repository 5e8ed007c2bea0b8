# SPDX-License-Identifier: Apache-2.0
"""Conversions between integers and the 24-bit float format (bit-accurate, vectorised).

Three conversions, each mirrored by one RTL unit in ``rtl/fp``:

* :func:`from_unorm` -- an n-bit unorm code k (n = 8 or 16) to the f24 of k / (2^n - 1),
  correctly rounded (RNE to 17 significant bits).  ``f24_from_unorm``.
* :func:`to_index` -- an f24 to a signed ``width``-bit texel index: floor(x), saturated, with a
  saturation flag.  ``f24_to_index``.
* :func:`from_int` -- a signed ``width``-bit integer to f24, exact when it has at most 17
  significant bits, RNE otherwise.  ``f24_from_int``.

Everything is computed with exact integer arithmetic on ``int64`` arrays (no float division, no
float rounding), so the rounding is visibly correct: a value is written as an integer significand
``sig`` in [2^16, 2^17) times a power of two plus a remainder, and the remainder decides the
rounding (above half: up; exactly half: up when ``sig`` is odd).  Rounding follows
``docs/number-format.md``: RNE with an unbounded exponent, then overflow to Inf / flush below 2^-62
(neither can happen for these conversions' ranges, but the packing handles both).
"""
from __future__ import annotations

import numpy as np
import numpy.typing as npt

U32 = npt.NDArray[np.uint32]
I64 = npt.NDArray[np.int64]
Bool = npt.NDArray[np.bool_]

# Format constants (restated here: model.f24 imports this module while it is being initialised).
_BIAS = 63
_EXP_MAX = 127
_FRAC_BITS = 16
_NAN = 0x7F8000

#: Unorm widths :func:`from_unorm` accepts.
UNORM_BITS = (8, 16)
#: Widths :func:`to_index` and :func:`from_int` accept (int64 arithmetic stays exact up to here).
MIN_WIDTH = 2
MAX_WIDTH = 62


def _bit_length(m: I64) -> I64:
    """Bit length of non-negative integers (0 for 0).

    ``frexp`` of an integer below 2^53 is exact: m = f * 2^e with f in [0.5, 1), so e is the bit
    length.
    """
    _, e = np.frexp(m.astype(np.float64))
    return np.where(m == 0, 0, e).astype(np.int64)


def _round_pack(sign: I64, exp_unb: I64, sig: I64, rem: I64, half: I64) -> U32:
    """Pack sign * (sig + rem/(2*half)) * 2^(exp_unb - 16), rounded to nearest, ties to even.

    ``sig`` is the truncated 17-bit significand in [2^16, 2^17); ``rem`` / ``(2 * half)`` is the
    discarded fraction of one unit in the last place, so ``rem > half`` is above the halfway point
    and ``rem == half`` is exactly halfway.  A carry out of 17 bits bumps the exponent; the result
    overflows to Inf above the largest finite value and flushes to a signed zero below 2^-62.
    """
    up = (rem > half) | ((rem == half) & ((sig & 1) == 1))
    sig = sig + up
    carry = sig >= (1 << 17)
    sig = np.where(carry, sig >> 1, sig)
    bexp = exp_unb + _BIAS + carry
    s = sign.astype(np.uint32) << np.uint32(23)
    frac = (sig & ((1 << _FRAC_BITS) - 1)).astype(np.uint32)
    out = s | (np.clip(bexp, 0, _EXP_MAX).astype(np.uint32) << np.uint32(16)) | frac
    out = np.where(bexp > 126, s | np.uint32(_EXP_MAX << 16), out)
    out = np.where(bexp < 1, s, out)
    return out.astype(np.uint32)


def _int_array(k: npt.ArrayLike, what: str) -> I64:
    a = np.asarray(k)
    if a.dtype == np.bool_ or not np.issubdtype(a.dtype, np.integer):
        raise TypeError(f"{what}: integer array expected, got dtype {a.dtype}")
    if a.dtype == np.uint64 and a.size and int(a.max()) >= 1 << 63:
        raise ValueError(f"{what}: value out of range")
    return a.astype(np.int64)


def _check_width(width: int) -> None:
    if not isinstance(width, (int, np.integer)) or not MIN_WIDTH <= width <= MAX_WIDTH:
        raise ValueError(f"width must be an int in [{MIN_WIDTH}, {MAX_WIDTH}], got {width!r}")


def from_unorm(k: npt.ArrayLike, bits: int = 8) -> U32:
    """The f24 of k / (2^bits - 1), correctly rounded, for unorm codes k in [0, 2^bits - 1].

    ``bits`` is 8 or 16 (``ValueError`` otherwise, and for codes out of range).  0 gives +0 and
    2^bits - 1 gives 1.0 exactly.  For 0 < k < 2^bits - 1 with bit length L the value lies in
    [2^(L-bits-1), 2^(L-bits)), so its 17-bit significand is floor(k * 2^(17+bits-L) / D) with
    D = 2^bits - 1 and the remainder of that division decides the rounding (D is odd, so there
    is never a tie).
    """
    if bits not in UNORM_BITS:
        raise ValueError(f"bits must be one of {UNORM_BITS}, got {bits!r}")
    ka = _int_array(k, "from_unorm")
    d = (1 << bits) - 1
    if ka.size and (int(ka.min()) < 0 or int(ka.max()) > d):
        raise ValueError(f"from_unorm: codes must be in [0, {d}]")
    ln = _bit_length(ka)
    sh = np.where(ka == 0, 0, 17 + bits - ln)  # k * 2^sh < 2^(bits + 17): fits in int64
    num = ka << sh
    sig = num // d
    rem2 = 2 * (num % d)  # compare 2 * rem with D: (rem2 > D) is "above half"
    sig_safe = np.where(ka == 0, 1 << 16, sig)  # keep _round_pack's domain; zero patched below
    out = _round_pack(np.zeros_like(ka), ln - bits - 1, sig_safe, rem2, np.full_like(ka, d))
    return np.where(ka == 0, np.uint32(0), out).astype(np.uint32)


def from_int(k: npt.ArrayLike, width: int = 20) -> U32:
    """The signed ``width``-bit integer k as f24: exact with at most 17 significant bits, RNE above.

    ``ValueError`` if ``width`` is outside [2, 62] or any k is outside [-2^(width-1),
    2^(width-1) - 1].  0 gives +0.  The magnitude m with bit length L > 17 is split into
    sig = m >> (L - 17) and the L - 17 discarded bits, which round to nearest, ties to even.
    """
    _check_width(width)
    ka = _int_array(k, "from_int")
    lo, hi = -(1 << (width - 1)), (1 << (width - 1)) - 1
    if ka.size and (int(ka.min()) < lo or int(ka.max()) > hi):
        raise ValueError(f"from_int: values must be in [{lo}, {hi}] for width {width}")
    sign = (ka < 0).astype(np.int64)
    m = np.abs(ka)
    ln = _bit_length(m)
    drop = np.maximum(ln - 17, 0)  # bits below the 17-bit significand
    sig = np.where(drop > 0, m >> drop, m << np.maximum(17 - ln, 0))
    rem = m & ((np.int64(1) << drop) - 1)
    half = np.where(drop > 0, np.int64(1) << np.maximum(drop - 1, 0), 1)  # rem == 0 when drop == 0
    sig_safe = np.where(m == 0, 1 << 16, sig)
    out = _round_pack(sign, ln - 1, sig_safe, rem, half)
    return np.where(m == 0, np.uint32(0), out).astype(np.uint32)


def to_index(x: npt.ArrayLike, width: int = 20) -> tuple[I64, Bool]:
    """floor(x) as a signed ``width``-bit index, saturating: returns ``(idx, sat)``.

    ``idx`` is floor(x) clamped to [-2^(width-1), 2^(width-1) - 1]; ``sat`` is true when the value
    was clamped or x is NaN (NaN gives idx 0).  +-Inf saturate to the range ends; zeros and
    subnormal patterns give 0 (floor(-0) = 0).  Floor rounds toward minus infinity: -0.5 -> -1,
    -1.0 -> -1.  ``width`` must be in [2, 62] (``ValueError`` otherwise).
    """
    _check_width(width)
    b = np.asarray(x).astype(np.int64) & ((1 << 24) - 1)
    neg = (b >> 23) == 1
    e = (b >> 16) & _EXP_MAX
    sig = (b & 0xFFFF) | (1 << 16)  # |x| = sig * 2^(e - 63 - 16) for normal x
    exp_unb = e - _BIAS
    lo, hi = -(1 << (width - 1)), (1 << (width - 1)) - 1
    # |x| >= 2^width is out of range either way; below that sig << (exp_unb - 16) < 2^(width+1)
    # fits in int64.  Exact integer part and "fraction is nonzero" of |x|:
    big = exp_unb >= width
    sh = np.clip(np.minimum(exp_unb, width) - 16, -64, None)  # sig << sh < 2^(width+1)
    rsh = np.minimum(-sh, 63)
    ipart = np.where(sh >= 0, sig << np.maximum(sh, 0), sig >> np.maximum(rsh, 0))
    ipart = np.where(rsh > 17, 0, ipart)  # numpy shifts of >= 64 bits are not defined
    frac_nz = (sh < 0) & ((sig & ((np.int64(1) << np.clip(rsh, 0, 62)) - 1)) != 0)
    frac_nz |= rsh > 17  # |x| < 1
    fl = np.where(neg, -(ipart + frac_nz), ipart)  # floor(x) for normal x with |x| < 2^width
    zero = e == 0
    special = e == _EXP_MAX
    nan = special & ((b & 0xFFFF) != 0)
    over = ~zero & ~special & ~big & (fl > hi)
    under = ~zero & ~special & ~big & (fl < lo)
    sat_hi = (~neg & (big | special)) | over
    sat_lo = (neg & (big | special)) | under
    idx = np.where(zero, 0, fl)
    idx = np.where(sat_hi, hi, np.where(sat_lo, lo, idx))
    idx = np.where(nan, 0, idx)
    sat = (sat_hi | sat_lo | nan) & ~zero
    return idx.astype(np.int64), sat.astype(np.bool_)
