"""tex_filter against model.texture.filter_texels in the f24 engine, bit for bit.

Texels are driven as the little-endian 32-bit words of their memory bytes (R in bits 7:0, G 15:8,
B 23:16, A 31:24); the model gets the codes.  Stimulus, streamed with random en_i gaps and valid
bubbles (tb/common/valid_pipe.py):
  lookups      the real path: random textures (37 x 100, 100 x 37, 1 x 1, 16 x 16), lookups at
               random u, v, every level, scale 1 and != 1 through model.texture.lookup_addresses;
               the texel words read from Texture.memory_image at the four addresses; the expected
               value must also equal model.texture.sample (the composition is the model's lookup)
  centres      the same at texel centres and halfway points (weights 0 and 0.5)
  random       random texel words, weights uniform in [0, 1] (and exact 0, 1, 0.5, k / 2^16)
  extremes     codes 0 and 255 mixed, equal texels, one texel different
  specials     NaN / Inf / zero / subnormal / negative / above-1 / huge weights, random patterns
and a reset of a full pipeline while stalled.  ALPHA = 1 checks all four channels; the ALPHA = 0
build checks R, G, B and that a_o is 0.
"""
from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np

from model import f24, f24_vectors as vec, texture
from model.arith import ENGINES
from tb.common import fp_unit, runner
from tb.common.valid_pipe import ValidPipe

LATENCY = 11  # pipe_pkg::TEX_FILTER_LAT
TEXELS = ["t00_i", "t01_i", "t10_i", "t11_i"]
INS = TEXELS + ["fx_i", "fy_i"]
OUTS = ["r_o", "g_o", "b_o", "a_o"]
AR = ENGINES["f24"]


def words_of(codes: np.ndarray) -> np.ndarray:
    """(N, 4 reads, 4 channels) codes -> (N, 4) texel words, R in bits 7:0."""
    c = codes.astype(np.uint64)
    return (c[..., 0] | c[..., 1] << 8 | c[..., 2] << 16 | c[..., 3] << 24).astype(np.uint64)


def codes_of(words: np.ndarray) -> np.ndarray:
    w = words.astype(np.uint64)
    return np.stack([(w >> np.uint64(8 * c)) & np.uint64(255) for c in range(4)],
                    axis=-1).astype(np.uint8)


def f24w(x) -> np.ndarray:
    return f24.from_float(np.asarray(x, dtype=np.float64)).astype(np.uint32)


def from_texture(rng: np.random.Generator, tex: texture.Texture, map_w: int, map_h: int,
                 n: int, centres: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(words (n, 4), fx words, fy words) of real lookups: the reads from the memory image."""
    lvl = rng.integers(0, tex.n_levels, n)
    su, sv = tex.scale_for(AR, map_w, map_h)
    if centres:  # texel centres and halfway points in texture coordinates
        wl = np.array([tex.level_size(int(k))[0] for k in lvl])
        hl = np.array([tex.level_size(int(k))[1] for k in lvl])
        off = rng.choice([0.0, 0.5], (2, n))
        u = 2.0**lvl * (rng.integers(0, wl + 1) + off[0]) / su[0]
        v = 2.0**lvl * (rng.integers(0, hl + 1) + off[1]) / sv[0]
    else:
        u = rng.uniform(-0.1, 1.1, n) * map_w
        v = rng.uniform(-0.1, 1.1, n) * map_h
    u, v = AR.r(u), AR.r(v)
    la = texture.lookup_addresses(tex, AR, u, v, lvl, (su, sv))
    mem = np.frombuffer(tex.memory_image(), dtype="<u4")  # 4-byte aligned: addr / 4 indexes it
    assert (la.addr % 4 == 0).all()
    words = mem[la.addr // 4].astype(np.uint64)
    want = texture.sample(tex, AR, u, v, lvl, (su, sv)).value
    got = texture.filter_texels(AR, codes_of(words), la.fx, la.fy)
    assert np.array_equal(got, want, equal_nan=True), "model: filter(reads) != sample"
    return words, f24w(la.fx), f24w(la.fy)


def stimulus(rng: np.random.Generator, n_random: int) -> tuple[dict[str, np.ndarray],
                                                                dict[str, int]]:
    parts: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}
    texs = [(texture.build(rng.integers(0, 256, (37, 100, 4)).astype(np.uint8)), 100, 37),
            (texture.build(rng.integers(0, 256, (100, 37, 4)).astype(np.uint8)), 64, 64),
            (texture.build(rng.integers(0, 256, (1, 1, 4)).astype(np.uint8)), 64, 48),
            (texture.build(rng.random((16, 16, 3))), 7, 3)]
    for key, centres, n in (("lookups", False, n_random // 2), ("centres", True, 2000)):
        got = [from_texture(rng, t, mw, mh, n // len(texs) + 1, centres) for t, mw, mh in texs]
        parts[key] = tuple(np.concatenate([g[k] for g in got]) for k in range(3))
    # random texels and weights in [0, 1]
    m = n_random // 2
    fx = f24w(rng.uniform(0, 1, m))
    fy = f24w(rng.uniform(0, 1, m))
    exact = np.concatenate([f24w([0.0, 1.0, 0.5, 0.25, 0.75]),
                            f24w(rng.integers(0, 1 << 16, 20) / 65536.0)])
    pick = rng.random((2, m)) < 0.2
    fx[pick[0]] = rng.choice(exact, int(pick[0].sum()))
    fy[pick[1]] = rng.choice(exact, int(pick[1].sum()))
    parts["random"] = (rng.integers(0, 1 << 32, (m, 4), dtype=np.uint64), fx, fy)
    # extremes: codes 0 / 255 mixed, equal texels, one texel different
    m = 3000
    codes = rng.choice(np.array([0, 255, 1, 254, 128, 127], np.uint8), (m, 4, 4))
    same = rng.integers(0, 256, (m // 2, 1, 4)).astype(np.uint8)
    codes[: m // 2] = same
    one = rng.integers(0, 4, m // 2)
    codes[np.arange(m // 2), one] = rng.integers(0, 256, (m // 2, 4))
    parts["extremes"] = (words_of(codes), f24w(rng.uniform(0, 1, m)), f24w(rng.uniform(0, 1, m)))
    # special weights
    sp = np.concatenate([vec.SPECIALS, f24w([-0.5, -1.0, 1.5, 2.0, 1e10, -1e10, 2.0**19,
                                              1.0 + 2.0**-16, 1.0 - 2.0**-17, 2.0**-62])])
    m = 40 * sp.size
    fx = rng.choice(sp, m)
    fy = rng.choice(sp, m)
    keep = rng.random((2, m)) < 0.3
    fx[keep[0]] = f24w(rng.uniform(0, 1, int(keep[0].sum())))
    fy[keep[1]] = f24w(rng.uniform(0, 1, int(keep[1].sum())))
    parts["special weights"] = (rng.integers(0, 1 << 32, (m, 4), dtype=np.uint64), fx, fy)
    m = max(n_random // 20, 1000)
    parts["patterns"] = (rng.integers(0, 1 << 32, (m, 4), dtype=np.uint64),
                         vec.rand_bits(rng, m), vec.rand_bits(rng, m))
    words = np.concatenate([p[0] for p in parts.values()])
    ins = {name: words[:, k] for k, name in enumerate(TEXELS)}
    ins["fx_i"] = np.concatenate([p[1] for p in parts.values()]).astype(np.uint32)
    ins["fy_i"] = np.concatenate([p[2] for p in parts.values()]).astype(np.uint32)
    return ins, {k: len(p[0]) for k, p in parts.items()}


def expected(ins: dict[str, np.ndarray], alpha: bool) -> dict[str, np.ndarray]:
    """The model on the codes and the weights' values."""
    words = np.stack([ins[name] for name in TEXELS], axis=1)
    val = texture.filter_texels(AR, codes_of(words), f24.to_float(ins["fx_i"]),
                                f24.to_float(ins["fy_i"]))
    out = {name: f24.from_float(val[:, c]) for c, name in enumerate(OUTS)}
    if not alpha:
        out["a_o"] = np.zeros(len(words), dtype=np.uint32)
    return out


@cocotb.test()
async def tex_filter_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    alpha = bool(int(dut.ALPHA.value))
    pipe = ValidPipe(dut, LATENCY, INS, OUTS, "RTL vs model.texture.filter_texels (f24)")
    await pipe.reset()
    ins, counts = stimulus(rng, fp_unit.vectors(fp_unit.VECTORS_COMPOSITE))
    perm = rng.permutation(len(ins["fx_i"]))
    ins = {k: v[perm] for k, v in ins.items()}
    exp = expected(ins, alpha)
    half = len(perm) // 2
    total = 0
    for k, sl in enumerate((slice(0, half), slice(half, None))):
        part = {n: v[sl] for n, v in ins.items()}

        def describe(j: int, part=part) -> str:
            return " ".join(f"{n[:-2]}=0x{int(part[n][j]):0{8 if n in TEXELS else 6}x}"
                            for n in INS)

        nan = int(np.count_nonzero(f24.is_nan(exp["r_o"][sl])))
        total += await pipe.run(f"part {k + 1} of 2 (ALPHA={int(alpha)}, {nan} NaN results)",
                                part, {n: v[sl] for n, v in exp.items()}, rng,
                                describe=describe)
        if k == 0:
            await pipe.flush_check(rng)
    dut._log.info("VECTORS tex_filter: %d lookups (%s), 0 mismatches", total,
                  ", ".join(f"{k} {v}" for k, v in counts.items()))


def test_tex_filter():
    runner.run("tex_filter", "test_tex_filter", Path(__file__).parent, parameters={"ALPHA": 1})


def test_tex_filter_rgb_tag1():
    runner.run("tex_filter", "test_tex_filter", Path(__file__).parent,
               parameters={"ALPHA": 0, "TAG_W": 1}, extra_env={"VECTORS": "4000"})
