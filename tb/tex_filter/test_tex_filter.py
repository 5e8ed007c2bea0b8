# SPDX-License-Identifier: Apache-2.0
"""tex_filter against model.texture.filter_texels in the f24 engine, bit for bit.

Texels are driven as the little-endian 32-bit words of their memory bytes (R in bits 7:0, G 15:8,
B 23:16, A 31:24); the model gets the codes.  The unit takes a lookup on an edge with valid_i &&
ready_o (ready_o = en_i and every other enabled clock: its float units serve two clocks'
operations); the driver here (HandshakePipe) offers each lookup until it is taken, in segments of
random en_i gaps and valid bubbles and of lookups offered back to back (the next one offered in
the clock after a take, so ready_o's gating decides), drives junk with a random valid_i on stalled
clocks, and checks every clock: ready_o alternates over enabled clocks and is 0 while en_i is 0;
valid_o shows the take TEX_FILTER_LAT enabled edges earlier; the outputs hold while stalled.
Stimulus:
  lookups      the real path: random textures (37 x 100, 100 x 37, 1 x 1, 16 x 16), lookups at
               random u, v, every level, scale 1 and != 1 through model.texture.lookup_addresses;
               the texel words read from Texture.memory_image at the four addresses; the expected
               value must also equal model.texture.sample (the composition is the model's lookup)
  centres      the same at texel centres and halfway points (weights 0 and 0.5)
  random       random texel words, weights uniform in [0, 1] (and exact 0, 1, 0.5, k / 2^16)
  extremes     codes 0 and 255 mixed, equal texels, one texel different
  specials     NaN / Inf / zero / subnormal / negative / above-1 / huge weights, random patterns
and directed: a lookup offered while ready_o is 0 (in the clock after a take, and again across
a stall) is held and taken at the next ready, exactly once, its result at the fixed latency; a
reset of a full pipeline while stalled.  ALPHA = 1 checks all four channels; the ALPHA = 0 build
checks R, G, B and that a_o is 0.

Every configuration is at one pair of float-unit depths (ADD_LAT, MUL_LAT) of
tb/common/depths.py: the package defaults (3, 2) (built with no depth parameter, so the defaults
are checked too), and under ``make test-long`` (TB_LONG=1) the paper's (2, 1) and, for ALPHA = 1,
(2, 2), the depths without m's parity delay; the latency the driver expects is
pipe_pkg::tex_filter_lat(ADD_LAT, MUL_LAT), which must equal this file's mirror of the schedule
(and TEX_FILTER_LAT at the defaults); the stimulus and the bit-exact checks are the same at
every depth.

The configurations of CASES (ALPHA = 1; dm_pipeline's ALPHA = 0 with a 1-bit tag and 4,000
vectors) and, under make test-long, LONG_CASES (both at (2, 1), ALPHA = 1 at (2, 2)) are built
once, side by side, in the wrapper ``tex_filter_tb`` (one instance each, own ports and reset, a
shared clock; its parameter LONG adds LONG_CASES), and each cocotb test runs on all of them at
once, each with its own random stream from the printed seed and its own checks; a failure names
the configuration.
"""
from __future__ import annotations

import collections
from pathlib import Path
from typing import Any, Callable, Coroutine, Mapping, NamedTuple

import cocotb
import numpy as np
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from model import f24, f24_vectors as vec, texture
from model.arith import ENGINES
from tb.common import cases, depths, fp_unit, report, runner
from tb.common.valid_pipe import ValidPipe
from tb.harness import sv_params

def tex_filter_lat(add_lat: int, mul_lat: int) -> int:
    """The schedule's latency (the module header's stage table): from_unorm, the rows (sub, mul,
    add; the bottom row a clock later), the last adder's operand register, sub, mul, m's parity
    delay (the last adder's two operations an odd number of clocks apart), the register, add."""
    unorm = sv_params.value("pipe_pkg", "F24_FROM_UNORM_LAT")
    rows = add_lat + mul_lat + add_lat + 1
    apart = add_lat + mul_lat + 1          # bot - top to top + m through the operand registers
    apart += 1 - apart % 2                 # made odd
    return unorm + rows + 1 + apart + add_lat


def latency(pair: tuple[int, int]) -> int:
    """The latency under test: pipe_pkg::tex_filter_lat at the instance's depths ``pair``,
    checked against the mirror above (and TEX_FILTER_LAT at the defaults)."""
    return depths.latency("tex_filter_lat", tex_filter_lat, "TEX_FILTER_LAT", pair=pair)


class Case(NamedTuple):
    """One instance of tex_filter_tb: its parameters and its random vectors (``vectors``: None
    for fp_unit.vectors(VECTORS_COMPOSITE), i.e. VECTORS=... or the default)."""
    ADD_LAT: int
    MUL_LAT: int
    TAG_W: int
    ALPHA: int
    vectors: int | None

    def name(self) -> str:
        """How a failure names the configuration."""
        return (f"tex_filter ADD_LAT {self.ADD_LAT}, MUL_LAT {self.MUL_LAT}, TAG_W {self.TAG_W}, "
                f"ALPHA {self.ALPHA}")


_OTHER = [p for p in depths.PAIRS if p != depths.DEFAULT]
#: The instances g_case[0 ..] of tex_filter_tb (the wrapper's table): all four channels;
#: dm_pipeline's build (R, G, B) with a 1-bit tag.
CASES = [Case(*depths.DEFAULT, 8, 1, None), Case(*depths.DEFAULT, 1, 0, 4000)]
#: The instances after CASES in the make test-long build (the wrapper's LONG = 1): ALPHA = 1 at
#: the other depths of depths.PAIRS (the paper's (2, 1)) and at (2, 2), where ADD_LAT + MUL_LAT
#: is even and m goes to the last adder's operand register without a delay; dm_pipeline's build
#: at the other depths of depths.PAIRS.
LONG_CASES = ([Case(a, m, 8, 1, None) for a, m in _OTHER + [(2, 2)]]
              + [Case(a, m, 1, 0, 4000) for a, m in _OTHER])


def build_cases() -> list[Case]:
    """The instances of the build: CASES, and LONG_CASES under TB_LONG=1."""
    return CASES + (LONG_CASES if runner.long_stimulus() else [])

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


class HandshakePipe:
    """tex_filter under test (``dut``: an instance's scope, ``clk``: the running clock, ``lat``:
    its latency) with its valid / ready handshake; checks every clock: ready_o is 0 while en_i is
    0 and alternates over enabled clocks (1 on the first enabled clock after a reset); valid_o
    after an enabled edge is the take ``lat`` enabled edges earlier (a take: an edge with
    valid_i && ready_o, en_i is part of ready_o); every output holds over a stalled edge."""

    def __init__(self, dut, clk, lat: int) -> None:
        self.dut = dut
        self.clk = clk
        self.latency = lat
        self.tag_w = len(dut.tag_i)
        self.in_sigs = {k: getattr(dut, k) for k in INS}
        self.out_sigs = {k: getattr(dut, k) for k in ["valid_o", "tag_o"] + OUTS}
        self.hist: collections.deque = collections.deque([-1] * lat, maxlen=lat)
        self.last_ready = 0   # ready_o on the last enabled clock (after a reset: as if 0)
        self.cyc = 0
        self.prev = self.sample()

    def sample(self) -> dict[str, int]:
        return {k: int(s.value) for k, s in self.out_sigs.items()}

    async def reset(self, cycles: int = 2) -> None:
        """rst_ni low for ``cycles`` edges with en_i = 0 and valid_i = 1 (the reset does not wait
        for en_i and nothing is taken): ValidPipe's reset, then this driver's state."""
        # (uses only self.dut and self.clk)
        await ValidPipe.reset(self, cycles)  # type: ignore[arg-type]
        self.hist.extend([-1] * self.latency)
        self.last_ready = 0
        self.prev = self.sample()

    async def step(self, en: bool, valid: int, data: Mapping[str, int], tag: int,
                   ident: int = -1) -> tuple[bool, dict[str, int], int]:
        """One clock from a falling edge: drive, check ready_o, clock, check the outputs.
        ``ident`` names the lookup offered (>= 0 with valid = 1).  Returns (taken, outputs after
        the edge, the ident of the lookup whose result shows, or -1)."""
        d = self.dut
        for name, s in self.in_sigs.items():
            s.value = data[name]
        d.valid_i.value = valid
        d.tag_i.value = tag
        d.en_i.value = int(en)
        await Timer(1, unit="ns")
        ready = int(d.ready_o.value)
        self.cyc += 1
        if not en:
            if ready:
                raise AssertionError(f"ready_o = 1 while en_i = 0 (clock {self.cyc})")
        else:
            if ready == self.last_ready:
                raise AssertionError(f"ready_o = {ready} on two enabled clocks in a row (clock "
                                     f"{self.cyc}): a lookup every other enabled clock")
            self.last_ready = ready
        taken = bool(en and valid and ready)
        await RisingEdge(self.clk)
        await FallingEdge(self.clk)
        now = self.sample()
        out = -1
        if en:
            self.hist.append(ident if taken else -1)
            out = self.hist[0]
            if now["valid_o"] != int(out >= 0):
                raise AssertionError(f"valid_o = {now['valid_o']} at clock {self.cyc}, expected "
                                     f"{int(out >= 0)}")
        elif now != self.prev:
            raise AssertionError(f"outputs changed while en_i = 0 (clock {self.cyc}): "
                                 f"{self.prev} -> {now}")
        self.prev = now
        return taken, now, out

    async def run(self, what: str, inputs: Mapping[str, np.ndarray],
                  outputs: Mapping[str, np.ndarray], rng: np.random.Generator,
                  describe: Callable[[int], str] | None = None) -> int:
        """Offer the lookups ``inputs[name][k]`` in order, each until taken, and compare every
        result with ``outputs[name][k]`` (and tag_o with the tag offered) bit for bit.  Clocks
        come in segments (50 to 400 clocks) of one of four kinds: random en_i gaps and bubbles,
        back to back (en_i = 1, the next lookup offered at once), back to back with stalls, and
        sparse.  On a stalled clock a pending lookup is held or junk is driven with a random
        valid_i.  Raises after the stream on any mismatch (up to 10 reported per output).
        Returns the count checked."""
        d = self.dut
        n = len(next(iter(inputs.values())))
        in_lists = {k: [int(x) for x in inputs[k]] for k in INS}
        tags = rng.integers(0, 1 << self.tag_w, n)
        kinds = ((0.8, 0.2), (1.0, 0.0), (0.75, 0.0), (0.9, 0.6))  # (P(en_i), P(bubble))
        m = 4 * n + 4 * self.latency + 64
        u_en = rng.random(m).tolist()
        u_bub = rng.random(m).tolist()
        hold = (rng.random(m) < 0.5).tolist()
        junk_idx = rng.integers(0, n, m).tolist()
        junk_valid = rng.integers(0, 2, m).tolist()
        junk_tag = rng.integers(0, 1 << self.tag_w, m).tolist()
        got: dict[str, list[int]] = {k: [] for k in ["tag_o"] + OUTS}
        got_idx: list[int] = []
        issued = 0          # the next lookup to offer
        offered = False     # lookup `issued` is being offered (until taken)
        waits = 0           # enabled clocks a lookup was offered while ready_o was 0
        seg_left = 0
        p_en, p_bub = kinds[0]
        c0 = self.cyc
        j = 0
        while len(got_idx) < n:
            if seg_left == 0:
                seg_left = int(rng.integers(50, 401))
                p_en, p_bub = kinds[int(rng.integers(0, len(kinds)))]
            seg_left -= 1
            jj = j % m
            j += 1
            en = u_en[jj] < p_en
            if en and not offered and issued < n and u_bub[jj] >= p_bub:
                offered = True
            if offered and (en or hold[jj]):
                k, valid, tag, ident = issued, 1, int(tags[issued]), issued
            else:
                k = junk_idx[jj]
                valid = 0 if en else junk_valid[jj]
                tag, ident = junk_tag[jj], -1
            data = {name: in_lists[name][k] for name in INS}
            taken, now, out = await self.step(en, valid, data, tag, ident)
            if en and offered and not taken:
                waits += 1
            if taken:
                issued += 1
                offered = False
            if out >= 0:
                got_idx.append(out)
                for name in got:
                    got[name].append(now[name])
        d.valid_i.value = 0
        d.en_i.value = 0
        order = np.array(got_idx)
        assert np.array_equal(order, np.arange(n)), f"{what}: lookups out of order or lost"
        expect = dict(outputs)
        expect["tag_o"] = tags
        mism = []
        bad_any = np.zeros(n, dtype=bool)
        for name in got:
            g = np.array(got[name], dtype=np.int64)
            e = np.asarray(expect[name], dtype=np.int64)
            bad = np.nonzero(g != e)[0]
            bad_any |= g != e
            for b in bad[:10]:
                desc = describe(int(b)) if describe else str(int(b))
                mism.append(f"{what}: {name}: {desc}: got 0x{int(g[b]):06x} "
                            f"expected 0x{int(e[b]):06x}")
            if len(bad):
                mism.append(f"{what}: {name}: {len(bad)} mismatches of {n}")
        nbad = int(bad_any.sum())
        report.record("tex_filter", "RTL vs model.texture.filter_texels (f24)", n, nbad)
        d._log.info("%s: %d lookups in %d clocks (latency %d, %d enabled clocks offered while "
                    "not ready), %d mismatches", what, n, self.cyc - c0, self.latency, waits, nbad)
        if mism:
            raise AssertionError("\n".join(mism))
        assert waits > 0, f"{what}: no lookup was ever offered while ready_o was 0"
        return n

    async def flush_check(self, rng: np.random.Generator, data: Mapping[str, int]) -> None:
        """Fill the pipeline (a lookup offered on every clock), reset it while stalled: nothing
        may come out, and ready_o is 1 on the first enabled clock after the reset."""
        d = self.dut
        d.rst_ni.value = 1
        shown = False
        for _ in range(self.latency + 2):
            _, now, _ = await self.step(True, 1, data, int(rng.integers(0, 1 << self.tag_w)), 0)
            shown |= bool(now["valid_o"])
        assert shown, "valid_o should show the first lookup taken"
        assert any(x >= 0 for x in self.hist), "the pipeline should hold lookups"
        d.en_i.value = 0
        d.valid_i.value = 1
        d.rst_ni.value = 0
        await RisingEdge(self.clk)
        await FallingEdge(self.clk)
        assert int(d.valid_o.value) == 0, "rst_ni with en_i = 0 did not clear valid_o"
        d.rst_ni.value = 1
        self.hist.extend([-1] * self.latency)
        self.last_ready = 0
        self.prev = self.sample()
        for _ in range(self.latency + 2):
            await self.step(True, 0, data, 0)  # step checks valid_o = 0 and ready_o's phase


Check = Callable[[Any, HandshakePipe, Case, np.random.Generator], Coroutine[Any, Any, None]]


async def each_case(top, check: Check) -> None:
    """Start the clock, then reset every instance of tex_filter_tb and run ``check`` on it (all
    at once, each with its own random stream: :func:`cases.streams`); fail naming every
    configuration whose check failed."""
    async def one(dut, case: Case, rng: np.random.Generator) -> None:
        pipe = HandshakePipe(dut, top.clk_i, latency((case.ADD_LAT, case.MUL_LAT)))
        await pipe.reset()
        await check(dut, pipe, case, rng)

    await cases.run_each(top, build_cases(), Case.name, one)


@cocotb.test()
async def tex_filter_random_and_directed(dut):
    """The stimulus of the module docstring (:func:`random_and_directed`), every instance."""
    await each_case(dut, random_and_directed)


async def random_and_directed(dut, pipe: HandshakePipe, case: Case,
                              rng: np.random.Generator) -> None:
    """The stimulus classes in two parts, a reset of a full pipeline between them, on one
    instance ``dut`` driven by ``pipe``."""
    alpha = bool(int(dut.ALPHA.value))
    ins, counts = stimulus(rng, case.vectors or fp_unit.vectors(fp_unit.VECTORS_COMPOSITE))
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
            await pipe.flush_check(rng, {n: int(v[0]) for n, v in ins.items()})
    dut._log.info("VECTORS tex_filter: %d lookups (%s; ADD_LAT, MUL_LAT = %s, latency %d), "
                  "0 mismatches", total, ", ".join(f"{k} {v}" for k, v in counts.items()),
                  (case.ADD_LAT, case.MUL_LAT), pipe.latency)


@cocotb.test()
async def tex_filter_held_while_not_ready(dut):
    """Held lookups (:func:`held_while_not_ready`), every instance."""
    await each_case(dut, held_while_not_ready)


async def held_while_not_ready(dut, pipe: HandshakePipe, case: Case,
                               rng: np.random.Generator) -> None:
    """Directed: lookups offered while ready_o is 0 (the clock after a take; across a stall) are
    held, taken at the next ready exactly once, and come out at the fixed latency, right."""
    alpha = bool(int(dut.ALPHA.value))
    ins, _ = stimulus(rng, 200)
    pick = rng.choice(len(ins["fx_i"]), 4, replace=False)
    ins = {k: v[pick] for k, v in ins.items()}
    exp = expected(ins, alpha)
    tags = rng.integers(0, 1 << pipe.tag_w, 4).tolist()
    zero = {n: 0 for n in INS}
    # (en_i, lookup offered or -1): A at once; B in the clock after (not ready), held; C after B,
    # held over three stalled clocks; D after C, held over one stalled clock.
    plan = [(1, 0), (1, 1), (1, 1), (1, 2), (0, 2), (0, 2), (0, 2), (1, 2), (1, 3), (0, 3),
            (1, 3)] + [(1, -1)] * (pipe.latency + 2)
    takes, seen, outs = [], [], {k: [] for k in ["tag_o"] + OUTS}
    for clock, (en, q) in enumerate(plan, start=1):
        data = {n: int(ins[n][q]) for n in INS} if q >= 0 else zero
        taken, now, out = await pipe.step(bool(en), int(q >= 0), data, tags[q] if q >= 0 else 0,
                                          q)
        if taken:
            takes.append((clock, q))
        if out >= 0:
            seen.append(out)
            for name in outs:
                outs[name].append(now[name])
    assert takes == [(1, 0), (3, 1), (8, 2), (11, 3)], f"takes (clock, lookup): {takes}"
    assert seen == [0, 1, 2, 3], f"results came for lookups {seen}"
    expect = dict(exp)
    expect["tag_o"] = np.array(tags)
    for name, g in outs.items():
        assert [int(x) for x in expect[name]] == g, (
            f"{name}: got {[hex(x) for x in g]} expected {[hex(int(x)) for x in expect[name]]}")
    report.record("tex_filter", "RTL vs model.texture.filter_texels (f24), held lookups", 4, 0)
    dut._log.info("held while not ready: takes %s, 4 results at latency %d", takes,
                  pipe.latency)


def test_tex_filter() -> None:
    """Build tex_filter_tb once (the configurations of CASES; under make test-long, TB_LONG=1,
    with LONG = 1: LONG_CASES too) and run the cocotb tests on every instance."""
    here = Path(__file__).parent
    runner.run("tex_filter_tb", "test_tex_filter", here, rtl_top="tex_filter",
               parameters={"LONG": 1} if runner.long_stimulus() else {},
               extra_sources=[str(here / "tex_filter_tb.sv")])
