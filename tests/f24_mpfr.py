# SPDX-License-Identifier: Apache-2.0
"""An independent, correctly rounded reference for the 24-bit float format, on MPFR (gmpy2).

It shares no code with ``model/f24.py``: patterns are decoded and encoded here from the field
definitions of FLOAT24.md, and every operation is rounded by MPFR itself at 17 bits of precision
with an (effectively) unbounded exponent, after which overflow and flush-to-zero are applied.
"""
from __future__ import annotations

from typing import Callable, Iterable

import gmpy2
from gmpy2 import mpfr

CTX17 = gmpy2.context(precision=17, round=gmpy2.RoundToNearest, emax=1 << 20, emin=-(1 << 20),
                      subnormalize=False, trap_divzero=False, trap_invalid=False,
                      trap_overflow=False, trap_underflow=False, trap_inexact=False)


def _ctx() -> None:
    """Every operation here runs in CTX17 (decoding is exact there: patterns have 17 bits)."""
    gmpy2.set_context(CTX17)


def decode(b: int) -> mpfr:
    """Pattern -> exact mpfr (subnormal patterns are signed zeros)."""
    s, e, f = b >> 23 & 1, b >> 16 & 0x7F, b & 0xFFFF
    if e == 0:
        v = mpfr(0)
    elif e == 127:
        v = mpfr("inf") if f == 0 else mpfr("nan")
    else:
        v = gmpy2.mul_2exp(mpfr(0x10000 | f), e - 63 - 16)
    return -v if s else v


def encode(r: mpfr) -> int:
    """A 17-bit-rounded mpfr -> pattern, applying overflow to Inf and the flush below 2^-62."""
    if gmpy2.is_nan(r):
        return 0x7F8000
    s = 1 if gmpy2.is_signed(r) else 0
    if gmpy2.is_infinite(r):
        return s << 23 | 0x7F0000
    if r == 0:
        return s << 23
    m, e = abs(r).as_mantissa_exp()
    m, e = int(m), int(e)
    while m >= 1 << 17:
        assert m & 1 == 0, "value has more than 17 significant bits"
        m >>= 1
        e += 1
    while m < 1 << 16:
        m <<= 1
        e -= 1
    biased = e + 16 + 63
    if biased > 126:
        return s << 23 | 0x7F0000
    if biased < 1:
        return s << 23
    return s << 23 | biased << 16 | (m & 0xFFFF)


def _rounded(fn: Callable[..., mpfr], *args: mpfr) -> int:
    return encode(fn(*args))


def add(a: int, b: int) -> int:
    return _rounded(lambda x, y: x + y, decode(a), decode(b))


def sub(a: int, b: int) -> int:
    return _rounded(lambda x, y: x - y, decode(a), decode(b))


def mul(a: int, b: int) -> int:
    return _rounded(lambda x, y: x * y, decode(a), decode(b))


def div(a: int, b: int) -> int:
    return _rounded(lambda x, y: x / y, decode(a), decode(b))


def sqrt(a: int) -> int:
    return _rounded(gmpy2.sqrt, decode(a))


def from_float(x: float) -> int:
    """Round a float64 (exact in MPFR) to the format."""
    return encode(gmpy2.mul(mpfr(x, 53), 1))  # rounds to the context precision


def cmp(a: int, b: int) -> tuple[bool, bool, bool, bool]:
    x, y = decode(a), decode(b)
    un = gmpy2.is_nan(x) or gmpy2.is_nan(y)
    if un:
        return False, False, False, True
    return x < y, x == y, x > y, False


_ctx()


def map_binary(fn: Callable[[int, int], int], a: Iterable[int], b: Iterable[int]) -> list[int]:
    return [fn(int(x), int(y)) for x, y in zip(a, b)]
