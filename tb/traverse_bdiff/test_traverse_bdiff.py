# SPDX-License-Identifier: Apache-2.0
"""traverse_bdiff against the model: every result is f24.add(f24.from_int(b), -u), the word of
model.traverse.crossing_time's ar.sub(ar.from_int(b), p0), for boundaries 0 <= b < 2^16 and
positions u a non-negative f24 below 2^16 (the unit's range, traverse_bdiff's header).

Stimulus (seed printed, SEED=... to repeat): directed edge cases (b = 0 and u with bits below
2^-19, u = +-0, b = u, b and u one ulp apart, halfway cases of the rounding at every exponent,
the range ends), then random (b, u) pairs, u drawn with a uniform exponent.  The two boundary
ports take different b for one u (the ring's entry and exit).  fp_unit.check_pipeline drops
en_i at random and checks the latency (3), the hold while en_i = 0 and every result bit.
test_bdiff_every_u (plain Python) runs a bit-exact mirror of the unit's algorithm over every u in
the range for a set of b (two in make test, eight in make test-long; the mirror's own equality
with the RTL is what the cocotb test checks on its vectors).
"""
from __future__ import annotations

import os
import random
from pathlib import Path

import cocotb
import numpy as np

from model import f24
from tb.common import fp_unit, runner

HERE = Path(__file__).parent
LATENCY = 3
#: Sign-0 f24 patterns below 2^16 (exponent field up to 63 + 15 = 78), and -0.
U_MAX = 79 << 16
NEG_ZERO = 1 << 23


def expected(b: np.ndarray, u: np.ndarray) -> np.ndarray:
    """f24_add(f24_from_int(b), -u): the model's boundary - position."""
    return f24.add(f24.from_int(b, 20), f24.neg(u.astype(np.uint32)))


def directed() -> tuple[np.ndarray, np.ndarray]:
    """(b, u) edge cases."""
    bs: list[int] = []
    us: list[int] = []
    tiny = [1 << 16, (1 << 16) | 1, (2 << 16) | 0xFFFF, (40 << 16) | 0x1234, (59 << 16) | 1,
            (60 << 16) | 1, (60 << 16) | 0xFFFF, (61 << 16) | 1]
    # (-0 with a fraction: a zero whatever its fraction holds)
    for u in [0, NEG_ZERO, NEG_ZERO | 5, 7] + tiny:
        for b in (0, 1, 2, 3, 1 << 15, (1 << 16) - 1):
            bs.append(b)
            us.append(u)
    for e in range(44, 79):
        for frac in (0, 1, 0x8000, 0xFFFF, 0x7FFF, 0x5555):
            u = (e << 16) | frac
            val = float(f24.to_float(np.array([u], dtype=np.uint32))[0])
            for b in {int(np.floor(val)), int(np.floor(val)) + 1, int(np.ceil(val)) + 2,
                      max(int(val) - 1, 0), 0, 1, (1 << 16) - 1}:
                if 0 <= b < (1 << 16):
                    bs.append(b)
                    us.append(u)
    return np.array(bs, dtype=np.int64), np.array(us, dtype=np.int64)


def random_pairs(rng: np.random.Generator, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Random b in [0, 2^16) and u with a uniform exponent field in [0, 78]."""
    b = rng.integers(0, 1 << 16, n, dtype=np.int64)
    # half of the boundaries near the position (the cancelling cases)
    u = (rng.integers(0, 79, n, dtype=np.int64) << 16) | rng.integers(0, 1 << 16, n,
                                                                       dtype=np.int64)
    uf = f24.to_float(u.astype(np.uint32))
    near = rng.random(n) < 0.5
    b = np.where(near, np.clip(np.floor(uf).astype(np.int64) + rng.integers(-1, 3, n), 0,
                               (1 << 16) - 1), b)
    return b, u


@cocotb.test()
async def bdiff_directed_random(dut):
    rng = np.random.default_rng(fp_unit.seed())
    b_d, u_d = directed()
    b_r, u_r = random_pairs(rng, fp_unit.vectors())
    b0 = np.concatenate([b_d, b_r])
    u = np.concatenate([u_d, u_r])
    # the second port: another boundary of the same u (random within one of b0's neighbours)
    b1 = np.clip(b0 + rng.integers(-2, 3, len(b0)), 0, (1 << 16) - 1)
    mask = (1 << 20) - 1
    n = await fp_unit.check_pipeline(
        dut, LATENCY, {"b0_i": b0 & mask, "b1_i": b1 & mask, "u_i": u},
        {"y0_o": expected(b0, u), "y1_o": expected(b1, u)}, rng,
        describe=lambda i: f"b0={int(b0[i])} b1={int(b1[i])} u=0x{int(u[i]):06x}",
        label="RTL vs model f24 add(from_int(b), -u)")
    dut._log.info("VECTORS traverse_bdiff: %d (%d directed, %d random), 0 mismatches", n,
                  len(b_d), len(b_r))


def mirror(b: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The unit's algorithm (traverse_bdiff's three stages) in numpy, bit for bit."""
    e = (u >> 16) & 0x7F
    m = (1 << 16) | (u & 0xFFFF)
    sa = 78 - e
    tz = np.full_like(m, 16)
    for i in range(15, -1, -1):
        tz = np.where((m >> i) & 1, i, tz)
    v = np.where(sa >= 40, 0, (m << 18) >> np.minimum(sa, 39))
    st = (e != 0) & (sa > 18 + tz)
    ux = np.where(e == 0, 0, v | st)
    bs = b << 19
    neg = bs < ux
    mag = np.abs(bs - ux)
    lead = np.zeros_like(mag)
    for i in range(35):
        lead = np.where((mag >> i) & 1, i, lead)
    lz = 34 - lead
    n = (mag << lz) & ((1 << 35) - 1)
    up = ((n >> 17) & 1) & (((n & ((1 << 17) - 1)) != 0) | ((n >> 18) & 1))
    y = (((78 - lz) << 16) | ((n >> 18) & 0xFFFF)) + up
    y = np.where(neg, y | (1 << 23), y)
    y = np.where(mag == 0, 0, y)
    y = np.where((b == 0) & st, (1 << 23) | (u & 0x7FFFFF), y)
    return y.astype(np.uint32)


def test_bdiff_every_u():
    """The mirror against the model for every u in the range (and -0), a set of b: b = 0 (the
    unit's special case) and one random b in make test; 1, 3, 2^15, 2^16 - 1 and two more random
    ones too in make test-long."""
    seed = int(os.environ.get("SEED", random.randrange(1 << 31)))
    print(f"SEED={seed}")
    rng = np.random.default_rng(seed)
    u = np.concatenate([np.arange(0, U_MAX, dtype=np.int64), [NEG_ZERO]])
    bs = [0] + [int(x) for x in rng.integers(0, 1 << 16, 3)]
    bs = bs + [1, 3, 1 << 15, (1 << 16) - 1] if runner.long_stimulus() else bs[:2]
    for b in bs:
        bb = np.full(u.shape, b, dtype=np.int64)
        got, exp = mirror(bb, u), expected(bb, u)
        bad = np.nonzero(got != exp)[0]
        assert bad.size == 0, (f"b={b}: {bad.size} mismatches, first u=0x{int(u[bad[0]]):06x}: "
                               f"0x{int(got[bad[0]]):06x} != 0x{int(exp[bad[0]]):06x}")


def test_traverse_bdiff():
    runner.run("tb_traverse_bdiff", "test_traverse_bdiff", HERE, rtl_top="traverse_bdiff",
               extra_sources=[str(HERE / "tb_traverse_bdiff.sv")])
