# SPDX-License-Identifier: Apache-2.0
"""model/f24.py against the independent MPFR reference (tests/f24_mpfr.py).

Per operation: F24_MODEL_VECTORS random vectors (default 100,000: half random bit patterns, half
values near 1.0) plus the directed set of model/f24_vectors.py.  `make bench` runs a 10 M soak.
"""
from __future__ import annotations

import os

import numpy as np
import pytest

import f24_mpfr as ref
from model import f24, f24_vectors as vec
from tb.common import report

N = int(os.environ.get("F24_MODEL_VECTORS", "100000"))


def _report(name: str, got: np.ndarray, exp: np.ndarray, *ops: np.ndarray) -> None:
    bad = np.nonzero(got != exp)[0]
    print(f"VECTORS model {name}: {len(got)} vectors, {len(bad)} mismatches")
    report.record("model.f24", f"{name} vs MPFR", len(got), len(bad))
    if len(bad):
        lines = [", ".join(f"0x{int(o[i]):06x}" for o in ops) +
                 f" -> model 0x{int(got[i]):06x}, MPFR 0x{int(exp[i]):06x}" for i in bad[:10]]
        pytest.fail(f"{name}: {len(bad)} mismatches\n" + "\n".join(lines))


@pytest.mark.parametrize("op", ["add", "sub", "mul", "div"])
def test_binary_against_mpfr(op: str, rng: np.random.Generator) -> None:
    da, db = vec.directed_binary("add" if op == "sub" else op, rng)
    ra, rb = vec.random_binary(rng, N)
    a, b = np.concatenate([da, ra]), np.concatenate([db, rb])
    got = getattr(f24, op)(a, b)
    exp = np.array(ref.map_binary(getattr(ref, op), a, b), dtype=np.uint32)
    _report(op, got, exp, a, b)


def test_sqrt_against_mpfr(rng: np.random.Generator) -> None:
    a = np.concatenate([vec.directed_unary_sqrt(rng), vec.random_unary(rng, N)])
    got = f24.sqrt(a)
    exp = np.array([ref.sqrt(int(x)) for x in a], dtype=np.uint32)
    _report("sqrt", got, exp, a)


def test_cmp_against_mpfr(rng: np.random.Generator) -> None:
    da, db = vec.directed_binary("cmp", rng)
    ra, rb = vec.random_binary(rng, N)
    a, b = np.concatenate([da, ra]), np.concatenate([db, rb])
    got = np.stack(f24.cmp(a, b), axis=1)
    exp = np.array([ref.cmp(int(x), int(y)) for x, y in zip(a, b)], dtype=bool)
    _report("cmp", got.astype(np.uint32) @ np.array([8, 4, 2, 1], dtype=np.uint32),
            exp.astype(np.uint32) @ np.array([8, 4, 2, 1], dtype=np.uint32), a, b)
    assert (got.sum(axis=1) == 1).all(), "exactly one relation must hold"


def test_from_float_against_mpfr(rng: np.random.Generator) -> None:
    """Rounding of wider numbers: random float64 over the whole range and near every boundary."""
    x = np.concatenate([
        rng.standard_normal(N) * np.exp2(rng.integers(-70, 70, N)),
        # Exact halfway points and their float64 neighbours (ties to even, and just off ties).
        (f24.to_float(vec.rand_finite(rng, N // 8, 2, 125)) *
         (1 + 2.0**-17 * rng.choice([1.0, 1 + 2**-40, 1 - 2**-40], N // 8))),
        # Around overflow (MAX + half ulp) and the flush point 2^-62.
        f24.MAX_VALUE + 2.0**46 * rng.uniform(-2, 2, N // 8),
        2.0**-62 * rng.uniform(0.99, 1.01, N // 8),
        np.array([0.0, -0.0, np.inf, -np.inf, np.nan, 2.0**-62 * (1 - 2**-18), 2.0**-62 * (1 - 2**-17),
                  f24.MAX_VALUE + 2.0**46, f24.MAX_VALUE + 2.0**46 - 2.0**20, 1e300, -1e300, 5e-324]),
    ])
    got = f24.from_float(x)
    exp = np.array([ref.from_float(float(v)) for v in x], dtype=np.uint32)
    bad = np.nonzero(got != exp)[0]
    print(f"VECTORS model from_float: {len(x)} vectors, {len(bad)} mismatches")
    report.record("model.f24", "from_float vs MPFR", len(x), len(bad))
    assert len(bad) == 0, [(float(x[i]), hex(int(got[i])), hex(int(exp[i]))) for i in bad[:10]]


def test_to_float_round_trip() -> None:
    """Every finite, non-NaN pattern decodes and re-encodes to itself (all 2^24 patterns)."""
    b = np.arange(1 << 24, dtype=np.uint32)
    x = f24.to_float(b)
    back = f24.from_float(x)
    zero = (b >> 16 & 0x7F) == 0
    nan = f24.is_nan(b)
    canon = np.where(zero, b & np.uint32(f24.SIGN_BIT), b)
    assert (back[~nan] == canon[~nan]).all()
    assert (back[nan] == f24.NAN).all()
    print(f"VECTORS model to_float/from_float round trip: {len(b)} patterns, 0 mismatches")
    report.record("model.f24", "decode/encode round trip", len(b), 0)


def test_reference_selfcheck() -> None:
    """The reference itself on hand-worked cases, so a broken reference cannot pass silently."""
    one, two = 0x3F0000, 0x400000
    assert ref.add(one, one) == two
    assert ref.add(one, 0x2F0000) == 0x3F0001  # 0x2f0000 = 2^-16 is one ulp of 1.0
    assert ref.add(0x3F0001, 0x2E0000) == 0x3F0002  # 1+ulp + half ulp: tie to even goes up
    assert ref.add(one, 0x2E0000) == one  # 1 + half ulp: tie to even stays
    assert ref.add(one, one | 0x800000) == 0  # x + (-x) = +0
    assert ref.add(0x800000, 0x800000) == 0x800000
    assert ref.mul(0x7EFFFF, 0x400000) == 0x7F0000  # overflow
    assert ref.mul(0x010000, 0x3E0000) == 0  # 2^-62 * 0.5 flushes
    assert ref.div(one, 0) == 0x7F0000 and ref.div(0, 0) == 0x7F8000
    assert ref.sqrt(0x800000) == 0x800000 and ref.sqrt(0xBF0000) == 0x7F8000


def test_round_value_matches_from_float(rng: np.random.Generator) -> None:
    """The fast float64-domain rounding equals from_float + to_float (random and directed)."""
    x = np.concatenate([
        rng.standard_normal(N) * np.exp2(rng.integers(-70, 70, N)),
        f24.to_float(vec.rand_finite(rng, N // 4)) * (1 + 2.0**-17 * rng.choice([1, -1, 0.5], N // 4)),
        np.array([0.0, -0.0, np.inf, -np.inf, np.nan, f24.MAX_VALUE * (1 + 2.0**-18),
                  2.0**-62 * (1 - 2.0**-18), -2.0**-62 * (1 - 2.0**-17), 1e300, -1e-300]),
    ])
    got = f24.round_value(x)
    exp = f24.to_float(f24.from_float(x))
    same = (got == exp) & (np.signbit(got) == np.signbit(exp)) | (np.isnan(got) & np.isnan(exp))
    print(f"VECTORS model round_value: {len(x)} vectors, {int((~same).sum())} mismatches")
    report.record("model.f24", "round_value vs from_float", len(x), int((~same).sum()))
    assert same.all(), x[~same][:10]
