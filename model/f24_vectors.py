# SPDX-License-Identifier: Apache-2.0
"""Test vectors for the 24-bit float units: random patterns and the directed edge-case set.

Shared by the model's tests (against MPFR through gmpy2) and the RTL tests (against the model), so
that both see the same edge cases.  Every generator takes a numpy ``Generator`` (seeded by the
caller, who prints the seed) and returns ``uint32`` pattern arrays.
"""
from __future__ import annotations

import numpy as np
import numpy.typing as npt

from . import f24

U32 = npt.NDArray[np.uint32]

#: Special operands: signed zeros, subnormal patterns (read as zero), Inf, NaNs, extremes, ones.
SPECIALS = np.array([
    0x000000, 0x800000, 0x000001, 0x00ffff, 0x808000,      # zeros and subnormal patterns
    0x7f0000, 0xff0000,                                    # +-Inf
    0x7f8000, 0x7f0001, 0xffffff, 0x7fffff,                # NaNs
    0x7effff, 0xfeffff, 0x7e0000, 0x010000, 0x810000,      # largest, smallest normal
    0x010001, 0x01ffff, 0x3f0000, 0xbf0000, 0x3f0001,      # near smallest, 1.0, -1.0, 1+ulp
    0x3effff, 0x3fffff, 0x400000, 0x3e0000, 0x5f0000,      # 1-ulp/2, 2-ulp, 2, 0.5, 2^32
    0x200000, 0x1f0000, 0x5e0000, 0x3f8000, 0x408000,      # 2^-31, 2^-32, 2^31, 1.5, 3
], dtype=np.uint32)


def rand_bits(rng: np.random.Generator, n: int) -> U32:
    """Uniformly random 24-bit patterns (every class appears)."""
    return rng.integers(0, 1 << 24, n, dtype=np.uint32)


def rand_near_one(rng: np.random.Generator, n: int) -> U32:
    """Random values of either sign with magnitude in [0.25, 4)."""
    s = rng.integers(0, 2, n, dtype=np.uint32)
    e = rng.integers(f24.BIAS - 2, f24.BIAS + 2, n, dtype=np.uint32)
    f = rng.integers(0, 1 << 16, n, dtype=np.uint32)
    return f24.pack(s, e, f)


def rand_finite(rng: np.random.Generator, n: int, emin: int = 1, emax: int = 126) -> U32:
    """Random normal numbers with biased exponent in [emin, emax]."""
    s = rng.integers(0, 2, n, dtype=np.uint32)
    e = rng.integers(emin, emax + 1, n, dtype=np.uint32)
    f = rng.integers(0, 1 << 16, n, dtype=np.uint32)
    return f24.pack(s, e, f)


def _pairs_all(x: U32) -> tuple[U32, U32]:
    a, b = np.meshgrid(x, x, indexing="ij")
    return a.ravel(), b.ravel()


def directed_binary(op: str, rng: np.random.Generator) -> tuple[U32, U32]:
    """Directed operand pairs for ``op`` in {'add', 'mul', 'div', 'cmp'}."""
    parts_a: list[U32] = []
    parts_b: list[U32] = []

    def put(a: npt.ArrayLike, b: npt.ArrayLike) -> None:
        parts_a.append(np.asarray(a, dtype=np.uint32))
        parts_b.append(np.asarray(b, dtype=np.uint32))

    put(*_pairs_all(SPECIALS))
    m = 64
    # Every exponent difference 0..40, both orders, both sign combinations, random fractions.
    for d in range(41):
        ea = rng.integers(1 + d, 127, m, dtype=np.uint32)
        a = f24.pack(rng.integers(0, 2, m), ea, rng.integers(0, 1 << 16, m))
        b = f24.pack(rng.integers(0, 2, m), ea - d, rng.integers(0, 1 << 16, m))
        put(a, b)
        put(b, a)
    # Cancellation: b = -(a + k ulps) for small k, and exact negation.
    a = rand_finite(rng, 512, 2, 125)
    for k in (-3, -2, -1, 0, 1, 2, 3):
        b = (a.astype(np.int64) + k).astype(np.uint32) ^ np.uint32(f24.SIGN_BIT)
        put(a, b)
    if op in ("add", "cmp"):
        # Exact halfway cases: the bits shifted out are exactly 1000...0.
        for d in range(1, 18):
            ea = rng.integers(1 + d, 127, m, dtype=np.uint32)
            fa = rng.integers(0, 1 << 16, m, dtype=np.uint32)
            sigb = (rng.integers(0, 1 << 16, m, dtype=np.uint32) | (1 << 16))
            sigb = (sigb & ~np.uint32((1 << d) - 1)) | np.uint32(1 << (d - 1))
            sa = rng.integers(0, 2, m)
            for sb in (sa, 1 - sa):
                put(f24.pack(sa, ea, fa), f24.pack(sb, ea - d, sigb & 0xFFFF))
        # Overflow boundary: MAX + (1/2 ulp of MAX) ties up to Inf; a little less does not.
        big = np.array([0x7effff, 0x7efffe, 0x7e8000], dtype=np.uint32)
        near = np.array([0x6e0000, 0x6dffff, 0x6e0001, 0x6f0000, 0x6d0000], dtype=np.uint32)
        for s in (0, f24.SIGN_BIT):
            put(*(x.ravel() | np.uint32(s) for x in np.meshgrid(big, near, indexing="ij")))
        # Underflow boundary: differences that land around 2^-62.
        a = f24.pack(0, rng.integers(1, 4, 512), rng.integers(0, 1 << 16, 512))
        b = f24.pack(1, rng.integers(1, 4, 512), rng.integers(0, 1 << 16, 512))
        put(a, b)
    if op == "mul":
        # Exact halfway products: two 9-bit odd significands give an 18-bit odd product.
        hi = rng.integers(256, 512, 8192) | 1
        lo = rng.integers(256, 512, 8192) | 1
        keep = (hi * lo) >= (1 << 17)
        hi, lo = hi[keep], lo[keep]
        n = len(hi)
        ea = rng.integers(40, 90, n)
        eb = rng.integers(40, 90, n)
        put(f24.pack(rng.integers(0, 2, n), ea, (hi << 8) & 0xFFFF),
            f24.pack(rng.integers(0, 2, n), eb, (lo << 8) & 0xFFFF))
    if op in ("mul", "div"):
        # Overflow and underflow boundaries: exponents whose sum / difference hits the range ends.
        n = 4096
        ea = rng.integers(1, 127, n)
        if op == "mul":
            tgt = rng.choice([126, 127, 0, 1, 2, -1], n)
            eb = tgt + 63 - ea
        else:
            tgt = rng.choice([126, 127, 0, 1, 2, -1], n)
            eb = ea + 63 - tgt
        ok = (eb >= 1) & (eb <= 126)
        fa = rng.integers(0, 1 << 16, n)
        fb = np.where(rng.random(n) < 0.3, np.where(rng.random(n) < 0.5, 0, 0xFFFF),
                      rng.integers(0, 1 << 16, n))
        put(f24.pack(rng.integers(0, 2, n), ea, fa)[ok], f24.pack(rng.integers(0, 2, n), eb, fb)[ok])
    if op == "div":
        # A quotient of two 17-bit significands is never exactly halfway; take the closest cases:
        # a = round(q * b) for a halfway 18-bit q.
        n = 4096
        q = (rng.integers(1 << 17, 1 << 18, n) | 1).astype(np.float64) / (1 << 17)
        b = rand_finite(rng, n, 40, 80)
        a = f24.from_float(q * f24.to_float(b))
        put(a, b)
        # Exact quotients and division by +-1, +-0.
        a = rand_finite(rng, 512)
        for c in (0x3f0000, 0xbf0000, 0x400000, 0x000000, 0x800000):
            put(a, np.full(512, c, dtype=np.uint32))
            put(np.full(512, c, dtype=np.uint32), a)
    return np.concatenate(parts_a), np.concatenate(parts_b)


def directed_unary_sqrt(rng: np.random.Generator) -> U32:
    """Directed operands for sqrt: specials, exact squares, near-halfway roots, both parities."""
    parts = [SPECIALS]
    r = rng.integers(1 << 16, 1 << 17, 2048).astype(np.float64) / (1 << 16)
    e = rng.integers(-30, 31, 2048)
    parts.append(f24.from_float(np.ldexp(r * r, e)))  # mostly inexact; exact where r*r fits
    small = rng.integers(256, 512, 2048).astype(np.float64)  # 9-bit roots: exact squares
    parts.append(f24.from_float(np.ldexp(small * small, rng.integers(-60, 40, 2048))))
    # Near-halfway roots: a = round(q^2) for 18-bit halfway q (an exact halfway root is impossible).
    q = (rng.integers(1 << 17, 1 << 18, 4096) | 1).astype(np.float64) / (1 << 17)
    parts.append(f24.from_float(np.ldexp(q * q, rng.integers(-60, 60, 4096))))
    parts.append(rand_finite(rng, 1024) ^ np.uint32(f24.SIGN_BIT))  # negatives -> NaN
    for be in (1, 2, 125, 126):  # every fraction at the exponent ends
        parts.append(f24.pack(0, be, rng.integers(0, 1 << 16, 256)))
    return np.concatenate(parts).astype(np.uint32)


def random_binary(rng: np.random.Generator, n: int) -> tuple[U32, U32]:
    """Half random patterns, half values near 1.0 (where rounding is exercised densely)."""
    h = n // 2
    return (np.concatenate([rand_bits(rng, h), rand_near_one(rng, n - h)]),
            np.concatenate([rand_bits(rng, h), rand_near_one(rng, n - h)]))


def random_unary(rng: np.random.Generator, n: int) -> U32:
    h = n // 2
    return np.concatenate([rand_bits(rng, h), rand_near_one(rng, n - h)])
