# SPDX-License-Identifier: Apache-2.0
"""model/f24_approx.py (rsqrt, log2): documented error bounds, exact cases, specials, tables.

The bounds are checked exhaustively: every fraction at the biased exponents of :data:`EXPONENTS`
(both parities, both range ends) against MPFR (gmpy2) for the correctly rounded rsqrt, and every
positive normal input (all 126 exponents) against float64 math (error ~1e-16 relative, far below
the bounds).  The measured maxima are printed (run with ``-s``).
"""
from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import gmpy2
import numpy as np
import pytest

import f24_mpfr as ref
from model import f24, f24_approx as A
from tb.common import report

ROOT = Path(__file__).resolve().parents[1]
#: Biased exponents swept over all 2^16 fractions (both parities and the ends of the range).
EXPONENTS = (1, 2, 62, 63, 64, 65, 125, 126)
FRACS = np.arange(1 << f24.FRAC_BITS, dtype=np.uint32)


def _inputs(exps) -> np.ndarray:
    return np.concatenate([f24.pack(0, e, FRACS) for e in exps]).astype(np.uint32)


def _ulp_of(z: np.ndarray) -> np.ndarray:
    """ulp of a positive real z in the f24 format: 2^(floor(log2 z) - 16)."""
    _, ex = np.frexp(z)
    return np.ldexp(1.0, ex.astype(np.int64) - 1 - f24.FRAC_BITS)


ALL_POS = _inputs(range(1, 127))  # every positive normal pattern, in increasing order of value


# ---- documented constants --------------------------------------------------------------------

def test_documented_constants() -> None:
    """The bounds are the constants stated in the docstring (from the analysis, not measured)."""
    assert A.RSQRT_MAX_ULP == 1 and f24.RSQRT_MAX_ULP == A.RSQRT_MAX_ULP
    assert A.RSQRT_PRE_ULP == 0.375 + 2.0**-7
    assert A.RSQRT_ERR_ULP == A.RSQRT_PRE_ULP + 0.5 < A.RSQRT_MAX_ULP  # faithful rounding
    assert A.LOG2_MAX_ABS_ERR == 0.75 * 2.0**-16 and f24.LOG2_MAX_ABS_ERR == A.LOG2_MAX_ABS_ERR
    # The analysis behind LOG2_MAX_ABS_ERR: chord error h^2/8 * max|log2''| plus node rounding.
    assert 2.0**-14 / 8 / math.log(2) + 2.0**-(A.TAB_FRAC + 1) <= A.LOG2_MAX_ABS_ERR
    # ... and behind RSQRT_PRE_ULP: chord error of 2/sqrt(m) (<= 1.5 h^2/8 = 0.75 ulp), centred.
    assert 1.5 * 2.0**-14 / 8 / 2.0**-16 == 2 * A.RSQRT_BIAS * 2.0**-A.ACC_FRAC / 2.0**-16


# ---- rsqrt -----------------------------------------------------------------------------------

def _mpfr_rsqrt(b: int) -> int:
    ref._ctx()
    return ref.encode(gmpy2.rec_sqrt(ref.decode(b)))


def test_rsqrt_bound_vs_mpfr() -> None:
    """Every fraction at EXPONENTS: within RSQRT_MAX_ULP f24 steps of the MPFR-rounded result."""
    x = _inputs(EXPONENTS)
    y = f24.rsqrt(x)
    cr = np.array([_mpfr_rsqrt(int(b)) for b in x], dtype=np.int64)
    dist = np.abs(y.astype(np.int64) - cr)  # results are positive: pattern order = value order
    worst = int(dist.max())
    print(f"\nrsqrt vs MPFR at biased exponents {EXPONENTS}: {len(x)} inputs, max distance from "
          f"the correctly rounded result {worst} step(s) (bound {A.RSQRT_MAX_ULP}), "
          f"{np.mean(dist == 0):.2%} correctly rounded")
    report.record("model.f24_approx", "rsqrt within RSQRT_MAX_ULP of MPFR", len(x),
                  int(np.count_nonzero(dist > A.RSQRT_MAX_ULP)))
    assert worst <= A.RSQRT_MAX_ULP


def test_rsqrt_error_all_inputs() -> None:
    """Every positive normal input: |y - x^-1/2| and the pre-rounding error, in ulps."""
    xv = f24.to_float(ALL_POS)
    z = 1.0 / np.sqrt(xv)
    ulp = _ulp_of(z)
    yb = f24.rsqrt(ALL_POS)
    y = f24.to_float(yb)
    err = np.abs(y - z) / ulp
    acc, scale = A.rsqrt_fixed(ALL_POS)
    pre = np.abs(np.ldexp(acc.astype(np.float64), scale) - z) / ulp
    cr = f24.from_float(z)  # float64-rounded reference; near-ties are covered by the MPFR test
    print(f"\nrsqrt, all {len(ALL_POS)} positive normal inputs: "
          f"max |y - exact| = {err.max():.4f} ulp "
          f"(bound {A.RSQRT_ERR_ULP:.4f} < {A.RSQRT_MAX_ULP}), max error before rounding = "
          f"{pre.max():.5f} ulp (bound {A.RSQRT_PRE_ULP:.5f}), "
          f"{np.mean(yb == cr):.2%} correctly rounded")
    report.record("model.f24_approx", "rsqrt error bound (all positive inputs)", len(ALL_POS),
                  int(np.count_nonzero(err > A.RSQRT_ERR_ULP)))
    assert pre.max() <= A.RSQRT_PRE_ULP
    assert err.max() <= A.RSQRT_ERR_ULP < A.RSQRT_MAX_ULP


def test_rsqrt_exact_and_monotone() -> None:
    k = np.arange(-31, 32)
    x = f24.from_float(np.ldexp(1.0, 2 * k))  # 4^k, every one in range
    assert (f24.to_float(f24.rsqrt(x)) == np.ldexp(1.0, -k)).all()
    assert f24.rsqrt(np.uint32(f24.ONE)) == f24.ONE
    y = f24.to_float(f24.rsqrt(ALL_POS))
    assert (np.diff(y) <= 0).all(), "rsqrt must not increase with x"


def test_rsqrt_specials() -> None:
    cases = {
        0x000000: f24.POS_INF, 0x00ffff: f24.POS_INF,   # +0, positive subnormal pattern
        0x800000: f24.NEG_INF, 0x80ffff: f24.NEG_INF,   # -0, negative subnormal pattern
        0x7f0000: f24.POS_ZERO,                          # +Inf
        0xff0000: f24.NAN,                               # -Inf
        0xbf0000: f24.NAN, 0x810000: f24.NAN, 0xfeffff: f24.NAN,  # negative nonzero
        0x7f8000: f24.NAN, 0x7f0001: f24.NAN, 0xffffff: f24.NAN, 0xff8000: f24.NAN,  # NaNs
    }
    got = f24.rsqrt(np.array(list(cases), dtype=np.uint32))
    for (a, exp), g in zip(cases.items(), got):
        assert int(g) == exp, f"rsqrt(0x{a:06x}) = 0x{int(g):06x}, expected 0x{exp:06x}"


# ---- log2 ------------------------------------------------------------------------------------

def test_log2_bound_all_inputs() -> None:
    """Every positive normal input (includes EXPONENTS): |S - log2 x| <= LOG2_MAX_ABS_ERR before
    rounding and |y - log2 x| <= LOG2_MAX_ABS_ERR + ulp(y)/2 after it."""
    xv = f24.to_float(ALL_POS)
    z = np.log2(xv)
    y = f24.to_float(f24.log2(ALL_POS))
    s_acc, scale = A.log2_fixed(ALL_POS)
    pre = np.abs(np.ldexp(s_acc.astype(np.float64), scale) - z)
    ay = np.abs(y)
    half_ulp = np.where(ay > 0, _ulp_of(np.where(ay > 0, ay, 1.0)) / 2, 0.0)
    err = np.abs(y - z)
    excess = err - half_ulp
    sel = _inputs(EXPONENTS)
    at = np.isin(ALL_POS, sel)
    small = ay < 1
    print(f"\nlog2, all {len(ALL_POS)} positive normal inputs: max error before rounding = "
          f"{pre.max() / 2.0**-16:.4f} * 2^-16 (bound LOG2_MAX_ABS_ERR = "
          f"{A.LOG2_MAX_ABS_ERR / 2.0**-16} * 2^-16); max (|y - log2 x| - ulp(y)/2) = "
          f"{excess.max() / 2.0**-16:.4f} * 2^-16; max |y - log2 x| for |y| < 1: "
          f"{err[small].max() / 2.0**-16:.4f} * 2^-16; at biased exponents {EXPONENTS}: "
          f"{pre[at].max() / 2.0**-16:.4f} * 2^-16 before rounding")
    report.record("model.f24_approx", "log2 error bound (all positive inputs)", len(ALL_POS),
                  int(np.count_nonzero(excess > A.LOG2_MAX_ABS_ERR)))
    assert pre.max() <= A.LOG2_MAX_ABS_ERR
    assert excess.max() <= A.LOG2_MAX_ABS_ERR


def test_log2_exact_and_monotone() -> None:
    assert f24.log2(np.uint32(f24.ONE)) == f24.POS_ZERO  # exactly +0
    k = np.arange(-62, 64)
    x = f24.pack(0, k + f24.BIAS, 0)
    assert (f24.to_float(f24.log2(x)) == k).all()  # log2(2^k) = k exactly
    y = f24.to_float(f24.log2(ALL_POS))
    assert (np.diff(y) >= 0).all(), "log2 must not decrease with x"
    assert (np.sign(y) == np.sign(f24.to_float(ALL_POS) - 1.0)).all(), "sign of log2 x"


def test_log2_specials() -> None:
    cases = {
        0x000000: f24.NEG_INF, 0x800000: f24.NEG_INF,   # +-0
        0x00ffff: f24.NEG_INF, 0x80ffff: f24.NEG_INF,   # subnormal patterns read as zero
        0x7f0000: f24.POS_INF,                           # +Inf
        0xff0000: f24.NAN,                               # -Inf
        0xbf0000: f24.NAN, 0x810000: f24.NAN, 0xfeffff: f24.NAN,  # negative nonzero
        0x7f8000: f24.NAN, 0x7f0001: f24.NAN, 0xffffff: f24.NAN, 0xff8000: f24.NAN,  # NaNs
    }
    got = f24.log2(np.array(list(cases), dtype=np.uint32))
    for (a, exp), g in zip(cases.items(), got):
        assert int(g) == exp, f"log2(0x{a:06x}) = 0x{int(g):06x}, expected 0x{exp:06x}"


# ---- model internals -------------------------------------------------------------------------

def _rne_int(acc: int, scale: int) -> float:
    """acc * 2^scale (acc != 0) rounded to 17 significant bits, ties to even, in plain integers."""
    s, m = (acc < 0), abs(acc)
    drop = max(m.bit_length() - 17, 0)
    q, rem = m >> drop, m & ((1 << drop) - 1)
    half = (1 << drop) >> 1
    if drop and (rem > half or (rem == half and q & 1)):
        q += 1
    v = math.ldexp(q, scale + drop)
    return -v if s else v


@pytest.mark.parametrize("fn", ["rsqrt", "log2"])
def test_model_rounding_matches_integer_rne(fn: str, rng: np.random.Generator) -> None:
    """The model rounds its exact fixed-point value with from_float; compare with integer RNE."""
    x = np.concatenate([f24.pack(0, rng.integers(1, 127, 20000), rng.integers(0, 1 << 16, 20000)),
                        _inputs((63, 64))[::7]]).astype(np.uint32)
    acc, scale = getattr(A, f"{fn}_fixed")(x)
    scale = np.broadcast_to(scale, acc.shape)
    exp = [_rne_int(int(a), int(s)) if a else 0.0 for a, s in zip(acc, scale)]
    got = f24.to_float(getattr(f24, fn)(x))
    assert (got == np.array(exp)).all()


def test_tables_are_rounded_exact_function() -> None:
    """Nodes are the exact function rounded to 2^-22 (float64 check, ties are impossible here)."""
    m = 1.0 + np.arange(A.NSEG + 1) / A.NSEG
    one = 2.0**A.TAB_FRAC
    last = A.NSEG - 1
    node = {
        "rsqrt0": np.append(A.RSQRT_BASE[:A.NSEG], A.RSQRT_BASE[last] - A.RSQRT_DEC[last]),
        "rsqrt1": np.append(A.RSQRT_BASE[A.NSEG:], A.RSQRT_BASE[-1] - A.RSQRT_DEC[-1]),
        "log2": np.append(A.LOG2_BASE, A.LOG2_BASE[-1] + A.LOG2_INC[-1]),
    }
    exact = {"rsqrt0": one * 2 / np.sqrt(m), "rsqrt1": one * 2 / np.sqrt(2 * m),
             "log2": one * np.log2(m)}
    for k in node:
        assert np.abs(node[k] - exact[k]).max() <= 0.5 + 1e-6, k
    assert (np.diff(node["rsqrt0"]) < 0).all() and (np.diff(node["log2"]) > 0).all()


def test_committed_package_is_generated() -> None:
    """rtl/fp/f24_approx_pkg.sv equals what scripts/flow/gen_f24_tables.py generates now."""
    spec = importlib.util.spec_from_file_location("gen_f24_tables",
                                                  ROOT / "scripts" / "flow" / "gen_f24_tables.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    committed = (ROOT / "rtl" / "fp" / "f24_approx_pkg.sv").read_text()
    assert committed == gen.render(), "stale package: run python scripts/flow/gen_f24_tables.py"
    assert "generated by scripts/flow/gen_f24_tables.py" in committed.splitlines()[2].lower()
