# SPDX-License-Identifier: Apache-2.0
"""traverse_addr against the model's memory layout, bit for bit.

The module is combinational (loop stage S0) from its inputs and its level-offset table, which
each map's vectors find written through hlt_* (a clock per level, in random order, after junk
writes).  Its configuration comes from ``tb.harness.traverse_words.config`` (what the traverse
unit is given), the expected address from
``model.traverse.texel_offset`` over ``Pyramid.level_offsets`` (model/heightmap.py's layout: the
same function the model's trace reads its heights through), and, for every map small enough, the
byte(s) at that address of ``Pyramid.memory_image`` must be the texel's code in ``pyr.levels``:
the address really points at the node the loop asked for.

Maps from 1x1 to 16385x16300 (root level 0 .. 15), square and not, unorm8 and unorm16, base
addresses at 0, random and close to 2^32 (the sum wraps); random nodes (level 0 .. n, any cell of
the level) plus directed ones (levels 0 and n, cells at 0, at the map's edge and at the padded
level's edge).

Environment: SEED, VECTORS (random vectors, default 50,000), WAVES=1.
"""
from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge

from model import heightmap, traverse
from tb.harness import traverse_words
from model.traverse import EXACT_METHODS
from tb.common import fp_unit, report, runner
from tb.common.comb_unit import apply
from tb.common.tables import write_table

HERE = Path(__file__).resolve().parent
ADDR_MASK = (1 << traverse_words.ADDR_W) - 1
#: (height, width, unorm bits, base): base None = random.
MAPS = [(1, 1, 8, 0), (1, 1, 16, None), (2, 2, 8, None), (3, 5, 16, None), (7, 5, 8, 0),
        (37, 61, 8, None), (64, 17, 16, None), (100, 128, 8, None), (128, 128, 16, 0xFFFF_FFC0),
        (256, 200, 8, None), (1, 1000, 16, None), (1024, 1024, 8, 0xFFF0_0000),
        (2049, 3, 16, None), (16385, 16300, 16, None), (16385, 16300, 8, 0xC000_0000)]
#: Maps whose padded square has at most this many texels get a real pyramid and the memory-image
#: check.
REAL_TEXELS = 1 << 22
OUTPUTS = ("addr_o", "wide_o")


def pyramid(rng: np.random.Generator, h: int, w: int, bits: int) -> heightmap.Pyramid:
    """A real pyramid of random codes, or (large maps) one of broadcast constant levels: the layout
    depends only on the shape and the code size."""
    n = max(0, int(np.ceil(np.log2(max(h, w)))))   # heightmap.build's root level
    if 1 << (2 * n) <= REAL_TEXELS:
        return heightmap.build(rng.integers(0, 1 << bits, (h, w)).astype(np.uint16), bits)
    levels = [np.broadcast_to(np.uint16(7), ((1 << n) >> k,) * 2) for k in range(n + 1)]
    return heightmap.Pyramid(codes=np.broadcast_to(np.uint16(7), (h, w)), bits=bits,
                             levels=levels)


def nodes(rng: np.random.Generator, pyr: heightmap.Pyramid, m: int) -> tuple[np.ndarray, ...]:
    """Directed nodes (levels 0 and n and each level's corners and map edges) and m random ones."""
    n, w, h = pyr.n, pyr.width, pyr.height
    dk, dx, dy = [], [], []
    for k in range(n + 1):
        side = (1 << n) >> k
        xs = np.unique([0, ((w - 1) >> k), min(w >> k, side - 1), side - 1])
        ys = np.unique([0, ((h - 1) >> k), min(h >> k, side - 1), side - 1])
        gx, gy = (a.ravel() for a in np.meshgrid(xs, ys, indexing="ij"))
        dk += [np.full(len(gx), k)]
        dx += [gx]
        dy += [gy]
    k = rng.integers(0, n + 1, m)
    k[: m // 8] = 0          # many at level 0 and at the root
    k[m // 8: m // 4] = n
    side = (1 << n) >> k
    in_map = rng.random(m) < 0.7   # mostly over the map itself, else anywhere in the padded level
    cx = np.where(in_map, rng.integers(0, ((w - 1) >> k) + 1), rng.integers(0, side))
    cy = np.where(in_map, rng.integers(0, ((h - 1) >> k) + 1), rng.integers(0, side))
    return (np.concatenate(dk + [k]), np.concatenate(dx + [cx]), np.concatenate(dy + [cy]),
            sum(len(a) for a in dk))


@cocotb.test()
async def addr_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    per_map = max(1, fp_unit.vectors() // len(MAPS))
    cols: dict[str, list[np.ndarray]] = {k: [] for k in (
        "base_i", "bits16_i", "k_i", "nk_i", "cx_i", "cy_i")}
    exp: dict[str, list[np.ndarray]] = {k: [] for k in OUTPUTS}
    got: dict[str, list[np.ndarray]] = {k: [] for k in OUTPUTS}
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    dut.hlt_we_i.value = 0
    await FallingEdge(dut.clk_i)
    image_checked = image_bad = directed = 0
    for h, w, bits, base in MAPS:
        pyr = pyramid(rng, h, w, bits)
        if base is None:
            base = int(rng.integers(0, 1 << 32)) & ~63
        cfg = traverse_words.config(pyr, EXACT_METHODS[int(rng.integers(len(EXACT_METHODS)))], base)
        k, cx, cy, nd = nodes(rng, pyr, per_map)
        directed += nd
        # the model: level k's byte offset (heightmap layout) + row-major position x texel bytes
        off = traverse.texel_offset(pyr.level_offsets(), pyr.n, k, cx, cy, bits // 8)
        addr = (cfg.base + off) & ADDR_MASK
        if 1 << (2 * pyr.n) <= REAL_TEXELS:   # the address holds the node's code in the image
            img = np.frombuffer(pyr.memory_image(), dtype=np.uint8)
            rel = (addr - cfg.base) & ADDR_MASK
            code = img[rel].astype(np.int64)
            if bits == 16:
                code |= img[rel + 1].astype(np.int64) << 8
            want = np.array([pyr.levels[a][c, b] for a, b, c in zip(k, cx, cy)])
            image_checked += len(k)
            image_bad += int(np.count_nonzero(code != want))
        m = len(k)
        vm = {"base_i": np.full(m, cfg.base, dtype=object), "bits16_i": np.full(m, cfg.bits16),
              "k_i": k, "nk_i": cfg.root_level - k,   # n - k: the ring registers it with the node
              "cx_i": cx, "cy_i": cy}
        for name, col in vm.items():
            cols[name].append(col)
        exp["addr_o"].append(addr)
        exp["wide_o"].append(np.full(m, int(bits == 16)))
        # the level-offset table: junk in some entries first, then every level in random order
        writes = cfg.hlt_writes()
        junk = [(a, int(rng.integers(0, 1 << 32))) for a, _ in writes if rng.random() < 0.5]
        await write_table(dut, dut.clk_i, "hlt", junk + [writes[i] for i in
                                                        rng.permutation(len(writes))])
        gm = await apply(dut, vm, OUTPUTS)
        for name in OUTPUTS:
            got[name].append(gm[name])
    assert image_bad == 0, f"{image_bad} model addresses do not hold the node's code"
    v = {k: np.concatenate(x) for k, x in cols.items()}
    e = {k: np.concatenate(x) for k, x in exp.items()}
    got = {k: np.concatenate(x) for k, x in got.items()}
    bad = np.zeros(len(v["k_i"]), dtype=bool)
    for k in OUTPUTS:
        bad |= got[k] != e[k]
    for i in np.nonzero(bad)[0][:10]:
        dut._log.error("base 0x%08x n %d bits16 %d node (%d, %d, %d): got 0x%08x, model 0x%08x",
                       v["base_i"][i], v["nk_i"][i] + v["k_i"][i], v["bits16_i"][i], v["k_i"][i],
                       v["cx_i"][i], v["cy_i"][i], got["addr_o"][i], e["addr_o"][i])
    n, nbad = len(bad), int(bad.sum())
    report.record("traverse_addr", "RTL vs model.traverse.texel_offset (heightmap layout)", n, nbad)
    dut._log.info("VECTORS traverse_addr: %d (%d directed), %d mismatches; %d model addresses "
                  "checked against the memory image", n, directed, nbad, image_checked)
    assert nbad == 0, f"{nbad} of {n} vectors differ from the model"


def test_traverse_addr():
    runner.run("traverse_addr", "test_traverse_addr", HERE)
