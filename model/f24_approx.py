# SPDX-License-Identifier: Apache-2.0
"""Approximate units: reciprocal square root and log2 (bit-exact models of f24_rsqrt, f24_log2).

Both units are piecewise-linear interpolation over a table indexed by the top bits of the 16-bit
fraction, evaluated with integer arithmetic only, then rounded once to f24 (round to nearest, ties
to even).  The model computes the same integers as the RTL (numpy ``int64``, vectorised) and
rounds them with :func:`model.f24.from_float`; the fixed-point values are below 2^53, so the
conversion to float64 is exact and ``from_float`` performs exactly the RTL's RNE.  The tables
below are what ``scripts/flow/gen_f24_tables.py`` writes into ``rtl/fp/f24_approx_pkg.sv``.

Common structure
----------------
* The fraction ``f = a[15:0]`` is split into a segment index ``i = f[15:9]`` (:data:`SEG_BITS` = 7,
  128 segments of width h = 2^-7 in the significand m = 1 + f/2^16) and a position
  ``r = f[8:0]`` (:data:`POS_BITS` = 9 bits) inside the segment.
* Table nodes are the exact function at the segment ends, m_i = 1 + i/128 (i = 0..128), rounded to
  the nearest integer in units of 2^-:data:`TAB_FRAC` (22 fractional bits).  The RTL stores, per
  segment, the node value ``base[i] = N[i]`` and the step ``N[i+1] - N[i]`` (as a magnitude), so it
  reads one table word per operation and needs no subtractor before the multiplier.
* Interpolation: ``acc = base[i] * 2^9 +/- step[i] * r``, an exact integer with 31 = 22 + 9
  fractional bits (:data:`ACC_FRAC`): it equals ((512 - r) N[i] + r N[i+1]) / 512, the chord
  through the two rounded nodes, with no intermediate rounding.  ``acc`` is then normalised and
  rounded once to 17 significant bits, RNE (``f24_round_pack`` in the RTL).

Reciprocal square root (``rsqrt``)
----------------------------------
x = 2^E * m, E = e - 63, m in [1, 2).  With k = floor(E/2):

* E even: x^-1/2 = 2^(-k-1) * 2/sqrt(m),       2/sqrt(m)   in (sqrt 2, 2]   (table 0)
* E odd:  x^-1/2 = 2^(-k-1) * 2/sqrt(2m),      2/sqrt(2m)  in (1, sqrt 2]   (table 1)

so the exponent parity (``E odd`` = ``a[16] == 0``) selects the table and the result is
2^(-k-1) * T(m) with T in (1, 2].  The biased exponent of 2^(-k-1) is ``(188 - e) >> 1``
(31..93: rsqrt never overflows or underflows).  Table words: ``RSQRT_BASE[{odd, i}]`` (24 bits,
T0(1) = 2.0 is 2^23) and ``RSQRT_DEC[{odd, i}] = N[i] - N[i+1]`` (15 bits, T decreases).

T is convex, so the chord lies above it: chord error in [0, h^2/8 * max T''] = [0, 0.75 ulp]
(T0'' = 1.5 m^-5/2 <= 1.5; an ulp is 2^-16 in T's units, T in [1, 2]).  A constant
:data:`RSQRT_BIAS` = 0.375 ulp (3 * 2^12 units of 2^-31) is subtracted to centre that error:

    acc = RSQRT_BASE << 9  -  RSQRT_DEC * r  -  RSQRT_BIAS,          acc in (2^30, 2^32)

(the acc < 2^31 case, T just below 1.0, only happens near m = 2 of table 1; the RTL normalises
by one bit).  Error before the final rounding: chord - bias in [-0.375, +0.375] ulp plus node
rounding (<= 2^-23 = 2^-7 ulp):  |acc/2^31 - T| <= :data:`RSQRT_PRE_ULP` = 0.375 + 2^-7 ulp.
After RNE (<= 0.5 ulp more) the result y satisfies

    |y - x^-1/2| <= 0.8828 ulp < 1 ulp   (ulp = 2^(floor(log2 x^-1/2) - 16))

so y is *faithfully rounded*: one of the two f24 values around the exact result, hence the
correctly rounded result or its neighbour.  Documented bound :data:`RSQRT_MAX_ULP` = 1:
y differs from the correctly rounded result by at most one f24 step, and |y - exact| < 1 ulp.
Exact cases: rsqrt(4^j) = 2^-j exactly (node T0(1) = 2, bias < half an ulp).  The result is
monotone non-increasing in x (monotone nodes, chord, RNE; T0(2) = T1(1)).

Specials: +0 and positive subnormal patterns -> +Inf; -0 (and negative subnormal patterns)
-> -Inf; negative nonzero (including -Inf) -> NaN; +Inf -> +0; NaN -> NaN (0x7F8000).

log2
----
x = 2^E * m, m = 1 + f/2^16: log2 x = E + log2(m), log2(m) in [0, 1).  Table words:
``LOG2_BASE[i] = N[i]`` (22 bits, N = round(2^22 log2(m_i))) and ``LOG2_INC[i] = N[i+1] - N[i]``
(16 bits).  The fixed-point sum (signed, 31 fractional bits, |S| < 2^37)

    S = E * 2^31  +  LOG2_BASE << 9  +  LOG2_INC * r

is rounded once to f24 (RNE).  S = 0 only for x = 1.0, giving +0; for f = 0 the sum is exactly E,
so log2(2^k) = k exactly.  log2(m) is concave, so the chord lies below it; chord error
<= h^2/8 * max|log2''| = 2^-17 / ln 2 = 0.7213 * 2^-16, plus node rounding <= 2^-23:

    |S/2^31 - log2 x| <= LOG2_MAX_ABS_ERR = 0.75 * 2^-16  (= 1.144e-5)

relative to the exact real log2 of the (flushed) input.  The delivered f24 result y adds its own
rounding:  |y - log2 x| <= LOG2_MAX_ABS_ERR + ulp(y)/2, ulp(y) = 2^(floor(log2|y|) - 16).  For
|y| < 1 that is at most 0.75 * 2^-16 + 2^-18 = 2^-16; at |y| >= 1 the rounding term is already
2^-17 and for |y| >= 2 (ulp(y)/2 >= 2^-16) the f24 rounding of the result dominates.  The result
is monotone non-decreasing in x.  Results never overflow or underflow.

Specials: +-0 (and subnormal patterns) -> -Inf; negative nonzero (including -Inf) -> NaN;
+Inf -> +Inf; NaN -> NaN (0x7F8000).

Hardware (rtl/fp/f24_rsqrt.sv, f24_log2.sv)
-------------------------------------------
Ports clk_i, en_i, a_i[23:0], y_o[23:0]; latency 2 enabled clocks, one operation per clock,
registers advance only while en_i = 1.  Stage 1: unpack, classify, table read, one multiply
(rsqrt 15 x 9 bits, log2 16 x 9 bits); stage 2: add, normalise (rsqrt: 1 bit; log2: negate and
leading-zero count over 37 bits), round (RNE), pack.  Tables (f24_approx_pkg): rsqrt 256 words
of 24 + 15 bits (9,984 bits), log2 128 words of 22 + 16 bits (4,864 bits).

Measured (tests/test_f24_approx_model.py, exhaustive over all 8,257,536 positive normal inputs):
rsqrt max |y - exact| = 0.8733 ulp, before rounding 0.3827 ulp, 78.65 % correctly rounded, the
rest one step away; log2 max error before rounding 0.7120 * 2^-16, max |y - log2 x| - ulp(y)/2 =
0.7116 * 2^-16.  (Without the rsqrt bias 81.6 % would be correctly rounded but the worst error
would be 1.24 ulp, i.e. not faithful.)
"""
from __future__ import annotations

import math
from decimal import ROUND_HALF_EVEN, Decimal, localcontext

import numpy as np
import numpy.typing as npt

U32 = npt.NDArray[np.uint32]
I64 = npt.NDArray[np.int64]

# Format constants (restated here: model.f24 imports this module while it is being initialised, so
# model.f24 itself is imported lazily inside the functions).
_FRAC_BITS = 16
_BIAS = 63
_EXP_MAX = 127
_POS_ZERO = 0x000000
_POS_INF = 0x7F0000
_NEG_INF = 0xFF0000
_NAN = 0x7F8000

#: Segment-index bits (the top fraction bits): 2^7 = 128 segments per table.
SEG_BITS = 7
#: Position-in-segment bits (the remaining fraction bits), the multiplier's second operand.
POS_BITS = _FRAC_BITS - SEG_BITS
#: Fractional bits of every table entry.
TAB_FRAC = 22
#: Fractional bits of the interpolated fixed-point value (table bits + position bits).
ACC_FRAC = TAB_FRAC + POS_BITS
#: Number of segments.
NSEG = 1 << SEG_BITS

#: Word widths of the generated tables (checked against the tables below).
RSQRT_BASE_W = 24
RSQRT_DEC_W = 15
LOG2_BASE_W = 22
LOG2_INC_W = 16

#: Constant subtracted from the rsqrt accumulator: 0.375 ulp = 3/8 * 2^-16 in units of 2^-31.
RSQRT_BIAS = 3 << (ACC_FRAC - _FRAC_BITS - 3)

#: Documented rsqrt bound (from the analysis above, not measured): the result is within one f24
#: step of the correctly rounded result, and |y - x^-1/2| < 1 ulp (faithful rounding).
RSQRT_MAX_ULP = 1
#: Documented bound on the rsqrt fixed-point value before the final rounding, in ulps of T.
RSQRT_PRE_ULP = 0.375 + 2.0**-7
#: Documented bound on the final rsqrt error |y - exact| in ulps (RSQRT_PRE_ULP + 1/2).
RSQRT_ERR_ULP = RSQRT_PRE_ULP + 0.5

#: Documented log2 bound (from the analysis above, not measured): |S - log2 x| before the final
#: rounding, and |y - log2 x| <= LOG2_MAX_ABS_ERR + ulp(y)/2 for the f24 result y.
LOG2_MAX_ABS_ERR = 0.75 * 2.0**-16


def _round_half_even(d: Decimal) -> int:
    return int(d.quantize(Decimal(1), rounding=ROUND_HALF_EVEN))


def _rsqrt_nodes(odd: int) -> list[int]:
    """round(2^22 * 2/sqrt(m_i)) (even exponent) or round(2^22 * 2/sqrt(2 m_i)) (odd), exactly.

    2^22 * 2/sqrt(m) = sqrt(2^46 * 128 / (128 + i)) (times 1/sqrt 2 for odd): the nearest integer
    to sqrt(z) is (isqrt(4 floor(z)) + 1) // 2 (floor(sqrt(floor z)) = floor(sqrt z)).
    """
    out = []
    for i in range(NSEG + 1):
        num = (1 << (2 * TAB_FRAC + 2)) * NSEG
        den = (NSEG + i) * (2 if odd else 1)
        q = math.isqrt(4 * num // den)
        out.append((q + 1) // 2)
    return out


def _log2_nodes() -> list[int]:
    """round(2^22 * log2(1 + i/128)), correctly rounded (60-digit decimal logarithms)."""
    out = []
    with localcontext() as ctx:
        ctx.prec = 60
        ln2 = Decimal(2).ln()
        for i in range(NSEG + 1):
            v = (Decimal(NSEG + i) / NSEG).ln() / ln2 * (1 << TAB_FRAC)
            out.append(_round_half_even(v))
    return out


def _build_tables() -> dict[str, np.ndarray]:
    r0, r1 = _rsqrt_nodes(0), _rsqrt_nodes(1)
    lg = _log2_nodes()
    assert r0[0] == 2 << TAB_FRAC and r1[NSEG] == 1 << TAB_FRAC and r0[NSEG] == r1[0]
    assert lg[0] == 0 and lg[NSEG] == 1 << TAB_FRAC
    rs = [r0, r1]
    t = {
        # Index {odd, i}: entries 0..127 even exponent (table 0), 128..255 odd (table 1).
        "RSQRT_BASE": np.array([n[i] for n in rs for i in range(NSEG)], dtype=np.int64),
        "RSQRT_DEC": np.array([n[i] - n[i + 1] for n in rs for i in range(NSEG)], dtype=np.int64),
        "LOG2_BASE": np.array(lg[:NSEG], dtype=np.int64),
        "LOG2_INC": np.array([lg[i + 1] - lg[i] for i in range(NSEG)], dtype=np.int64),
    }
    widths = {"RSQRT_BASE": RSQRT_BASE_W, "RSQRT_DEC": RSQRT_DEC_W,
              "LOG2_BASE": LOG2_BASE_W, "LOG2_INC": LOG2_INC_W}
    for name, w in widths.items():
        assert t[name].min() >= 0 and t[name].max() < (1 << w), name
    return t


#: The generated tables (int64 arrays); the RTL package holds the same words.
TABLES = _build_tables()
RSQRT_BASE = TABLES["RSQRT_BASE"]
RSQRT_DEC = TABLES["RSQRT_DEC"]
LOG2_BASE = TABLES["LOG2_BASE"]
LOG2_INC = TABLES["LOG2_INC"]


def _split(a: npt.ArrayLike) -> tuple[I64, I64, I64, I64, I64]:
    """(sign, biased exponent, fraction, segment index, position) as int64 arrays."""
    b = np.asarray(a).astype(np.int64) & 0xFFFFFF
    s, e, f = b >> 23, (b >> 16) & _EXP_MAX, b & ((1 << _FRAC_BITS) - 1)
    return s, e, f, f >> POS_BITS, f & ((1 << POS_BITS) - 1)


def rsqrt_fixed(a: npt.ArrayLike) -> tuple[I64, I64]:
    """rsqrt datapath before rounding: (acc, scale), value = acc * 2^scale (for finite x > 0)."""
    _, e, _, i, r = _split(a)
    odd = (e & 1) == 0  # E = e - 63 odd
    idx = (odd.astype(np.int64) << SEG_BITS) | i
    acc = (RSQRT_BASE[idx] << POS_BITS) - RSQRT_DEC[idx] * r - RSQRT_BIAS
    res_e = (188 - e) >> 1  # biased exponent of 2^(-k-1), k = floor(E/2)
    return acc, res_e - _BIAS - ACC_FRAC


def rsqrt(a: npt.ArrayLike) -> U32:
    """Reciprocal square root, bit-exact with ``f24_rsqrt`` (bound: :data:`RSQRT_MAX_ULP`)."""
    from .f24 import from_float  # lazy: model.f24 imports this module
    s, e, f, _, _ = _split(a)
    acc, scale = rsqrt_fixed(a)
    y = from_float(np.ldexp(acc.astype(np.float64), scale))
    zero, nan = e == 0, (e == _EXP_MAX) & (f != 0)
    inf = (e == _EXP_MAX) & (f == 0)
    y = np.where(inf, np.uint32(_POS_ZERO), y)
    y = np.where(s == 1, np.uint32(_NAN), y)
    y = np.where(zero, np.where(s == 1, np.uint32(_NEG_INF), np.uint32(_POS_INF)), y)
    y = np.where(nan, np.uint32(_NAN), y)
    return y.astype(np.uint32)


def log2_fixed(a: npt.ArrayLike) -> tuple[I64, int]:
    """The log2 datapath before rounding: (S, scale) with value = S * 2^scale (finite x > 0)."""
    _, e, _, i, r = _split(a)
    s_acc = ((e - _BIAS) << ACC_FRAC) + (LOG2_BASE[i] << POS_BITS) + LOG2_INC[i] * r
    return s_acc, -ACC_FRAC


def log2(a: npt.ArrayLike) -> U32:
    """Base-2 logarithm, bit-exact with ``f24_log2`` (bound: :data:`LOG2_MAX_ABS_ERR`)."""
    from .f24 import from_float  # lazy: model.f24 imports this module
    s, e, f, _, _ = _split(a)
    acc, scale = log2_fixed(a)
    y = from_float(np.ldexp(acc.astype(np.float64), scale))
    zero, nan = e == 0, (e == _EXP_MAX) & (f != 0)
    inf = (e == _EXP_MAX) & (f == 0)
    y = np.where(inf, np.uint32(_POS_INF), y)
    y = np.where(s == 1, np.uint32(_NAN), y)
    y = np.where(zero, np.uint32(_NEG_INF), y)
    y = np.where(nan, np.uint32(_NAN), y)
    return y.astype(np.uint32)
