# SPDX-License-Identifier: Apache-2.0
"""traverse_level_decide against model.traverse.crossing_step and descent_level, bit for bit.

The module is combinational with two independent parts (loop stages S10 and S11); each cocotb test
drives one part and holds the other's inputs.

- Crossing: the neighbour and the level-up of every policy (none, tevs, drobot, selective,
  coherent: every method's), root levels 0 .. 15, levels 0 .. n, cells of the level anywhere
  (0, the padded level's last cell, a non-square map's edge, random), every exit combination (u,
  v, corner, none) and direction (+, -, not moving), prev_cross both ways, P1 on the node, on its
  neighbours, one or two nodes away, random and at the ends of the 20-bit index range.
- Descent: one, multi and xor with 0 .. 3 levels per descent (every method's policy among them),
  levels 0 (no descent: 0) to 15, crossed both ways, the two ends of the ray inside the node, on
  its edges and corners, the same cell (the XOR gives level 0) and outside the node (clipped).

The enum codes the module takes are read from rtl/traverse/traverse_pkg.sv and must name exactly
the model's policies (model.traverse.LEVEL_UP_POLICIES, DESCENT_POLICIES).

Environment: SEED, VECTORS (random vectors per part, default 50,000), WAVES=1.
"""
from __future__ import annotations

import re
from pathlib import Path

import cocotb
import numpy as np

from model import traverse
from model.traverse import METHODS
from tb.common import fp_unit, report, runner
from tb.common.comb_unit import apply

HERE = Path(__file__).resolve().parent
IDX_W = 20        # traverse_pkg::IDX_W: floor of a position (f24_to_index)
IDX_LO, IDX_HI = -(1 << (IDX_W - 1)), (1 << (IDX_W - 1)) - 1
CELL_MASK = 0xFFFF  # traverse_pkg::CELL_W
CROSS_OUT = ("xk_o", "xcx_o", "xcy_o", "up_o")
DESC_OUT = ("dk_o",)


def enum_codes(prefix: str, width: int) -> dict[str, int]:
    """Policy name (model spelling) -> code, from a traverse_pkg.sv enum (UP_TEVS = 3'd1, ...)."""
    pkg = (runner.RTL / "traverse" / "traverse_pkg.sv").read_text()
    return {m[0].lower(): int(m[1]) for m in re.findall(
        rf"\b{prefix}_(\w+)\s*=\s*{width}'d(\d+)", pkg)}


UP_CODE = enum_codes("UP", 3)
DESC_CODE = enum_codes("DESC", 2)


def hold(dut, names: tuple[str, ...]) -> None:
    for k in names:
        getattr(dut, k).value = 0


def compare(dut, unit_what: str, v: dict[str, np.ndarray], got: dict[str, np.ndarray],
            exp: dict[str, np.ndarray]) -> tuple[int, int]:
    bad = np.zeros(len(next(iter(v.values()))), dtype=bool)
    for k in exp:
        bad |= got[k] != exp[k]
    for i in np.nonzero(bad)[0][:10]:
        dut._log.error("%s -> got %s, model %s", {k: int(x[i]) for k, x in v.items()},
                       {k: int(got[k][i]) for k in exp}, {k: int(exp[k][i]) for k in exp})
    report.record("traverse_level_decide", unit_what, len(bad), int(bad.sum()))
    return len(bad), int(bad.sum())


def dir_fields(rng: np.random.Generator, m: int) -> np.ndarray:
    """Random dir_t {mv, neg} as 2-bit values (mostly moving; neg is random when not)."""
    mv = rng.random(m) < 0.85
    neg = rng.random(m) < 0.5
    return (mv.astype(np.int64) << 1) | neg


def level_and_cells(rng: np.random.Generator, m: int, kmin: int) -> tuple[np.ndarray, ...]:
    """Root level n, a level k in [kmin, n] (many at the ends), cells of level k: random, 0, the
    padded level's last cell, or a non-square map's edge."""
    n = rng.integers(0, 16, m)
    n = np.maximum(n, kmin)
    k = rng.integers(kmin, n + 1)
    end = rng.random(m)
    k = np.where(end < 0.1, kmin, np.where(end < 0.2, n, k))
    side = (1 << n) >> k
    edge = ((rng.integers((1 << n) // 2 + 1, (1 << n) + 1) - 1) >> k)  # (W - 1) >> k
    cells = []
    for _ in range(2):
        c = rng.integers(0, side)
        pick = rng.random(m)
        c = np.where(pick < 0.1, 0, np.where(pick < 0.2, side - 1, np.where(pick < 0.3, edge, c)))
        cells.append(c)
    return n, k, cells[0], cells[1]


def near(rng: np.random.Generator, c: np.ndarray, k: np.ndarray, far: float) -> np.ndarray:
    """A level-0 index relative to node c of level k: inside it, on its edges, in the next or the
    one after, or (fraction `far`) anywhere in the index range."""
    lo, size = c << k, 1 << k
    kind = rng.integers(0, 6, len(c))
    x = np.select([kind == 0, kind == 1, kind == 2, kind == 3, kind == 4],
                  [lo + rng.integers(0, size), lo, lo + size - 1,
                   lo + rng.integers(-size, 2 * size), lo + rng.integers(-3 * size, 4 * size)],
                  lo + rng.integers(-2, 3, len(c)))
    wild = rng.random(len(c)) < far
    x = np.where(wild, rng.integers(IDX_LO, IDX_HI + 1, len(c)), x)
    return np.clip(x, IDX_LO, IDX_HI)


def crossing_vectors(rng: np.random.Generator, count: int) -> dict[str, np.ndarray]:
    pols = list(traverse.LEVEL_UP_POLICIES)
    m = count
    n, k, cx, cy = level_and_cells(rng, m, 0)
    sx = dir_fields(rng, m)
    sy = dir_fields(rng, m)
    ex = rng.integers(0, 4, m)           # 0: u exit, 1: v exit, 2: corner, 3: neither
    v = {"level_up_i": np.array([UP_CODE[pols[i]] for i in rng.integers(0, len(pols), m)]),
         "n_i": n, "xk_i": k, "xcx_i": cx, "xcy_i": cy,
         "eqx_i": ((ex == 0) | (ex == 2)).astype(np.int64),
         "eqy_i": ((ex == 1) | (ex == 2)).astype(np.int64),
         "sx_i": sx, "sy_i": sy, "prev_cross_i": rng.integers(0, 2, m),
         "p1x_i": near(rng, cx, k, 0.05), "p1y_i": near(rng, cy, k, 0.05)}
    # directed: every policy x root levels 0, 1, 15 x level 0 and n x cells at both ends x
    # every exit and direction, P1 on the node and one / two nodes ahead, prev_cross both ways
    rows = []
    for pol in pols:
        for nn in (0, 1, 4, 15):
            for kk in sorted({0, nn}):
                side = (1 << nn) >> kk
                for c in sorted({0, side - 1}):
                    for e in range(4):
                        for s in (0b10, 0b11, 0b00):
                            for d1 in (0, 1, 2):
                                for pc in (0, 1):
                                    p1 = ((c + (d1 if s == 0b10 else -d1)) << kk)
                                    rows.append((UP_CODE[pol], nn, kk, c, c, int(e in (0, 2)),
                                                 int(e in (1, 2)), s, s, pc, p1, p1))
    d = np.array(rows, dtype=np.int64)
    keys = list(v)
    return {key: np.concatenate([d[:, i], v[key]]) for i, key in enumerate(keys)}, len(rows)


def crossing_expected(v: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """model.traverse.crossing_step, per (policy, n) (it takes those as scalars)."""
    m = len(v["n_i"])
    out = {key: np.zeros(m, dtype=np.int64) for key in CROSS_OUT}
    name = {c: p for p, c in UP_CODE.items()}
    s_of = {0b00: 0, 0b01: 0, 0b10: 1, 0b11: -1}  # dir_t {mv, neg}
    sx = np.vectorize(s_of.get)(v["sx_i"])
    sy = np.vectorize(s_of.get)(v["sy_i"])
    stepx = np.where(v["eqx_i"] == 1, sx, 0)
    stepy = np.where(v["eqy_i"] == 1, sy, 0)
    for code in np.unique(v["level_up_i"]):
        for n in np.unique(v["n_i"]):
            sel = (v["level_up_i"] == code) & (v["n_i"] == n)
            if not sel.any():
                continue
            k, cx, cy, up = traverse.crossing_step(
                name[int(code)], int(n), v["xk_i"][sel], v["xcx_i"][sel], v["xcy_i"][sel],
                stepx[sel], stepy[sel], v["prev_cross_i"][sel] == 1, v["p1x_i"][sel],
                v["p1y_i"][sel])
            out["xk_o"][sel] = k
            out["xcx_o"][sel] = cx & CELL_MASK
            out["xcy_o"][sel] = cy & CELL_MASK
            out["up_o"][sel] = up
    return out


def descent_policies() -> list[tuple[str, int]]:
    """(descent, levels): every method's, then every other combination of the RTL's fields."""
    mine = [(m.descent, m.descent_levels) for m in METHODS.values()]
    rest = [(d, lv) for d in traverse.DESCENT_POLICIES for lv in range(4)]
    return list(dict.fromkeys(mine + rest))


def descent_vectors(rng: np.random.Generator, count: int) -> dict[str, np.ndarray]:
    pols = descent_policies()
    m = count
    _, k, cx, cy = level_and_cells(rng, m, 1)
    k[rng.random(m) < 0.02] = 0          # not a descending ray: 0
    pi = rng.integers(0, len(pols), m)
    ax = near(rng, cx, k, 0.03)
    ay = near(rng, cy, k, 0.03)
    same = rng.random(m) < 0.1           # both ends in one texel: the XOR gives level 0
    bx = np.where(same, ax, near(rng, cx, k, 0.03))
    by = np.where(same, ay, near(rng, cy, k, 0.03))
    v = {"descent_i": np.array([DESC_CODE[pols[i][0]] for i in pi]),
         "levels_i": np.array([pols[i][1] for i in pi]),
         "dk_i": k, "dcx_i": cx, "dcy_i": cy, "crossed_i": rng.integers(0, 2, m),
         "ax_i": ax, "ay_i": ay, "bx_i": bx, "by_i": by}
    # directed: every policy x levels 0, 1, 2, 3, 15 x crossed x the ends on the node's corners
    rows = []
    for d, lv in pols:
        for kk in (0, 1, 2, 3, 15):
            c = 0 if kk == 15 else 5
            lo, hi = c << kk, ((c + 1) << kk) - 1
            for cr in (0, 1):
                for a, b in ((lo, lo), (lo, hi), (hi, lo), (lo + (hi - lo) // 2, hi),
                             (lo - 1, hi + 1), (IDX_LO, IDX_HI)):
                    rows.append((DESC_CODE[d], lv, kk, c, c, cr, a, a, b, lo))
    dd = np.array(rows, dtype=np.int64)
    return {key: np.concatenate([dd[:, i], v[key]]) for i, key in enumerate(v)}, len(rows)


def descent_expected(v: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """model.traverse.descent_level, per (descent, levels)."""
    name = {c: p for p, c in DESC_CODE.items()}
    out = np.zeros(len(v["dk_i"]), dtype=np.int64)
    for code in np.unique(v["descent_i"]):
        for lv in np.unique(v["levels_i"]):
            sel = (v["descent_i"] == code) & (v["levels_i"] == lv)
            if not sel.any():
                continue
            out[sel] = traverse.descent_level(
                name[int(code)], int(lv), v["dk_i"][sel], v["crossed_i"][sel] == 1,
                v["dcx_i"][sel], v["dcy_i"][sel], v["ax_i"][sel], v["ay_i"][sel], v["bx_i"][sel],
                v["by_i"][sel])
    return {"dk_o": out}


@cocotb.test()
async def policy_codes_match_the_model(dut):
    """traverse_pkg's level-up and descent enums name exactly the model's policies."""
    assert set(UP_CODE) == set(traverse.LEVEL_UP_POLICIES), UP_CODE
    assert set(DESC_CODE) == set(traverse.DESCENT_POLICIES), DESC_CODE
    assert all(METHODS[m].level_up in UP_CODE and METHODS[m].descent in DESC_CODE
               for m in METHODS)


@cocotb.test()
async def crossing_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    hold(dut, ("descent_i", "levels_i", "dk_i", "dcx_i", "dcy_i", "crossed_i", "ax_i", "ay_i",
               "bx_i", "by_i"))
    v, nd = crossing_vectors(rng, fp_unit.vectors())
    exp = crossing_expected(v)
    got = await apply(dut, v, CROSS_OUT)
    n, nbad = compare(dut, "crossing: RTL vs model.traverse.crossing_step", v, got, exp)
    ups = {p: int(exp["up_o"][v["level_up_i"] == c].sum()) for p, c in UP_CODE.items()}
    dut._log.info("level-ups per policy (model): %s", ups)
    dut._log.info("VECTORS traverse_level_decide crossing: %d (%d directed), %d mismatches",
                  n, nd, nbad)
    assert nbad == 0, f"{nbad} of {n} vectors differ from the model"


@cocotb.test()
async def descent_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    hold(dut, ("level_up_i", "n_i", "xk_i", "xcx_i", "xcy_i", "eqx_i", "eqy_i", "sx_i", "sy_i",
               "prev_cross_i", "p1x_i", "p1y_i"))
    v, nd = descent_vectors(rng, fp_unit.vectors())
    exp = descent_expected(v)
    got = await apply(dut, v, DESC_OUT)
    n, nbad = compare(dut, "descent: RTL vs model.traverse.descent_level", v, got, exp)
    drop = v["dk_i"] - exp["dk_o"]
    dut._log.info("levels descended (model): %s", np.bincount(drop[v["dk_i"] > 0]).tolist())
    dut._log.info("VECTORS traverse_level_decide descent: %d (%d directed), %d mismatches",
                  n, nd, nbad)
    assert nbad == 0, f"{nbad} of {n} vectors differ from the model"


def test_traverse_level_decide():
    runner.run("traverse_level_decide", "test_traverse_level_decide", HERE)
