# SPDX-License-Identifier: Apache-2.0
"""Behavioural model of the texture / normal-map cache (rtl/cache/tex_cache.sv).

- :func:`passes`: how a request (four texel byte addresses c00, c01, c10, c11) is split into
  passes and which line each sub-cache looks up in each pass, exactly as the RTL does: the row bit
  of a texel is bit j of its row's first address (c00 or c10), j a function of the pitch
  R = addr[2] - addr[0] (:func:`row_bit_position`; 0 when R = 0); sub-cache = (row bit, line
  parity); a pass is the greedy subset (texel order) of the remaining texels whose lines are in
  distinct sub-caches or equal, and, within one line, in the window the sub-cache reads: a
  sub-cache reads one window of ``win_words`` + 1 words of its line per pass (window k: words k *
  win_words .. (k + 1) * win_words, the last shared with window k + 1), the window of the pass's
  first texel in that sub-cache (:func:`window_fits`). A quad's horizontal pair (words w, w + 1 of
  one line) always fits one window, so real quads never split for it. So the RTL's
  ``stat_lookups_o`` equals the sum of ``len(lines)`` over the passes. ``stat_texel_hits_o``
  counts the texels (four per request) whose pass's lookup in their sub-cache hit.
- :class:`TexCacheDirectory`: the directory exactly as the RTL decides on it, pass by pass in
  request order: XOR-folded sets, a hit on a valid tag (a line in flight is valid), else the
  victim is the lowest unreferenced invalid way (never allocated, or its line came back with an
  error), else tree pseudo-LRU among the unreferenced ways (:func:`plru_pick`); every lookup, hit
  or miss, marks its way most recently used; a pass takes a reference to each slot it reads, the
  pass's read at the head of the request FIFO releases it.  What depends on timing is only when a
  release (or a line's error) happens; given those events, the hit / miss / victim sequence is a
  pure function.  :class:`TexCacheTimedModel` feeds it the events of the RTL's clocks with the
  RTL's visibility: a release or an error fill in clock t is seen by the decisions of clock
  t + 2 on (the directory is read a clock before the decision, from LUT RAM written at the end
  of clock t).  tb/tex_cache compares every decision of every stream with it.
- :class:`TexCacheModel`: the directory without timing (no reference ever held: each pass is
  released at once), for choosing sizes and estimating the hit rates of an access stream; the
  RTL's misses differ from it only where a reference made a victim differ.
"""
from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from typing import Iterable, Sequence

from .height_cache import CacheConfig, clog2


def plru_victim(cfg: CacheConfig, bits: int) -> int:
    """The way a tree pseudo-LRU state ``bits`` points at (node n = 1 .. WAYS-1 is bit n-1,
    children 2n and 2n+1; 0: the next victim is in the left subtree)."""
    n = 1
    for _ in range(clog2(cfg.ways)):
        n = 2 * n + ((bits >> (n - 1)) & 1)
    return n - cfg.ways


def plru_pick(cfg: CacheConfig, bits: int, mask: int) -> int:
    """The RTL's victim among the ways in ``mask`` (bit w = way w may be chosen): follow the
    tree's direction unless that subtree has no candidate (then the other one)."""
    n, lo, span = 1, 0, cfg.ways
    for _ in range(clog2(cfg.ways)):
        half = span // 2
        l_has = any((mask >> w) & 1 for w in range(lo, lo + half))
        r_has = any((mask >> w) & 1 for w in range(lo + half, lo + span))
        go_r = r_has if (bits >> (n - 1)) & 1 else not l_has
        n = 2 * n + int(go_r)
        if go_r:
            lo += half
        span = half
    return lo


def plru_touch(cfg: CacheConfig, bits: int, way: int) -> int:
    """``bits`` with way ``way`` marked most recently used (every node on its path points away)."""
    n = way + cfg.ways
    for _ in range(clog2(cfg.ways)):
        p = n >> 1
        bit = 1 if n % 2 == 0 else 0  # point away from the accessed child
        bits = (bits & ~(1 << (p - 1))) | (bit << (p - 1))
        n = p
    return bits


@dataclass(frozen=True)
class TexCacheConfig(CacheConfig):
    """The RTL's parameters (the height cache's, other defaults, plus the request FIFO and the
    side-band width; ``err_hold`` does not apply)."""

    sets: int = 32
    ways: int = 4
    mshrs: int = 16
    id_w: int = 6
    fifo_depth: int = 64
    tag_w: int = 8
    win_words: int = 2

    @property
    def window_words(self) -> int:
        """Words per data-RAM window (WIN_WORDS, at most the line's words)."""
        return min(self.win_words, self.line_bytes // 4)

    @property
    def capacity(self) -> int:
        """Bytes of line storage (four sub-caches)."""
        return 4 * self.sets * self.ways * self.line_bytes

    def params(self) -> dict[str, int]:
        """As RTL parameters."""
        return {"ADDR_W": self.addr_w, "DATA_W": self.data_w, "LINE_BYTES": self.line_bytes,
                "SETS": self.sets, "WAYS": self.ways, "MSHRS": self.mshrs,
                "FIFO_DEPTH": self.fifo_depth, "ID_W": self.id_w, "TAG_W": self.tag_w,
                "WIN_WORDS": self.win_words}


#: Bits below a candidate row-bit position that judge it (the RTL's ROW_P).
ROW_P = 3


def row_bit_position(pitch: int, cfg: TexCacheConfig) -> int | None:
    """The address bit j used as row bit for a quad of row pitch ``pitch`` (None: pitch 0).

    Among j = log2(4 * window_words) .. ADDR_W - 1, the j where the pitch is closest to an odd
    multiple of 2^j, judged by the ROW_P bits below j: e = pitch[j-1 -: ROW_P] if pitch[j] else
    its complement; the smallest e, the lowest j on ties. Bits below the line size are candidates
    so that the two rows of a small level, which share a line, go to two sub-caches when they are
    in different windows of it; the line parity bit is one too (for a pitch of one line) because
    the row bit is taken per row."""
    if pitch == 0:
        return None
    best = None
    lo = clog2(4 * cfg.window_words)
    for j in range(lo, cfg.addr_w):
        f = (pitch >> (j - ROW_P)) & ((1 << ROW_P) - 1)
        e = f if (pitch >> j) & 1 else (1 << ROW_P) - 1 - f
        if best is None or e < best[0]:
            best = (e, j)
    assert best is not None
    return best[1]


def row_bits(addrs: Sequence[int], cfg: TexCacheConfig) -> list[int]:
    """The row bit of each texel: bit j (:func:`row_bit_position` of the pitch addr[2] - addr[0])
    of its row's first texel, c00 for c00 and c01, c10 for c10 and c11; 0 when the pitch is 0."""
    mask = (1 << cfg.addr_w) - 1
    j = row_bit_position((addrs[2] - addrs[0]) & mask, cfg)
    if j is None:
        return [0, 0, 0, 0]
    top, bottom = (addrs[0] >> j) & 1, (addrs[2] >> j) & 1
    return [top, top, bottom, bottom]


@dataclass
class Pass:
    mask: int                               # texels served (bit t = texel t)
    lines: dict[int, int] = field(default_factory=dict)  # sub-cache -> line address
    sub: list[int] = field(default_factory=list)         # sub-cache of each texel (all four)
    win: dict[int, int] = field(default_factory=dict)    # sub-cache -> window read


def window_fits(word: int, win: int, cfg: TexCacheConfig) -> bool:
    """Whether word ``word`` of a line lies in its read window ``win`` (words win * W ..
    (win + 1) * W, W = window_words)."""
    ww = cfg.window_words
    return word // ww == win or word == (win + 1) * ww


def passes(addrs: Sequence[int], cfg: TexCacheConfig) -> list[Pass]:
    """The RTL's passes for one request."""
    rows = row_bits(addrs, cfg)
    la = [a >> cfg.off_w for a in addrs]
    word = [(a >> 2) & ((cfg.line_bytes >> 2) - 1) for a in addrs]
    sub = [(rows[t] << 1) | (la[t] & 1) for t in range(4)]
    todo = 0xF
    out: list[Pass] = []
    while todo:
        p = Pass(0, {}, sub, {})
        for t in range(4):
            if not (todo >> t) & 1:
                continue
            c = sub[t]
            if c in p.lines and (p.lines[c] != la[t]
                                 or not window_fits(word[t], p.win[c], cfg)):
                continue
            if c not in p.lines:
                p.lines[c] = la[t]
                p.win[c] = word[t] // cfg.window_words
            p.mask |= 1 << t
        todo &= ~p.mask
        out.append(p)
    return out


def set_of(la: int, cfg: TexCacheConfig) -> int:
    """XOR-folded set index (bit 0 of the line address selects the sub-cache)."""
    s = cfg.set_w
    la_w = cfg.addr_w - cfg.off_w
    lo = (la >> 1) & ((1 << s) - 1)
    hi = (la >> (1 + s)) & ((1 << s) - 1) if 1 + s < la_w else 0
    return lo ^ hi


@dataclass
class Slot:
    """One line slot of the directory: its tag (None: not allocated since the reset), whether the
    line is valid (allocated, in flight or present) or came back with an error, and the
    references that passes in the request FIFO hold on it."""

    tag: int | None = None
    valid: bool = False
    err: bool = False
    refs: int = 0


@dataclass
class Lookup:
    """The outcome of one sub-cache's lookup in a pass: hit or miss, the way (the hit way or the
    victim) and the set."""

    sub: int
    set: int
    way: int
    hit: bool
    la: int


class Blocked(Exception):
    """Every way of a set a pass missed is referenced: the RTL cannot decide the pass now."""


class TexCacheDirectory:
    """The four sub-caches' directories with reference counts, decided pass by pass (see the
    module docstring)."""

    def __init__(self, cfg: TexCacheConfig):
        self.cfg = cfg
        self.slots = [[[Slot() for _ in range(cfg.ways)] for _ in range(cfg.sets)]
                      for _ in range(4)]
        self.plru = [[0] * cfg.sets for _ in range(4)]

    def victim(self, c: int, s: int) -> int:
        """The way the RTL allocates in set ``s`` of sub-cache ``c`` (raises :class:`Blocked`
        when every way is referenced)."""
        ways = self.slots[c][s]
        free = [not (x.valid or x.err) or x.refs == 0 for x in ways]
        if not any(free):
            raise Blocked(f"sub-cache {c} set {s}: every way referenced")
        for w, x in enumerate(ways):
            if free[w] and not x.valid:
                return w
        return plru_pick(self.cfg, self.plru[c][s], sum(f << w for w, f in enumerate(free)))

    def enter(self, p: Pass) -> list[Lookup]:
        """Decide pass ``p`` (every sub-cache it reads), take its references; the outcome in
        sub-cache order (:meth:`release` takes it back).  Raises :class:`Blocked` (with nothing
        changed) when a missed set has no unreferenced way."""
        cfg = self.cfg
        out: list[Lookup] = []
        for c in sorted(p.lines):
            la = p.lines[c]
            s = set_of(la, cfg)
            tag = la >> (1 + cfg.set_w)
            ways = self.slots[c][s]
            hit = [w for w, x in enumerate(ways) if x.valid and x.tag == tag]
            out.append(Lookup(c, s, hit[0], True, la) if hit
                       else Lookup(c, s, self.victim(c, s), False, la))
        for lk in out:
            x = self.slots[lk.sub][lk.set][lk.way]
            if not lk.hit:
                x.tag, x.valid, x.err, x.refs = lk.la >> (1 + cfg.set_w), True, False, 0
            x.refs += 1
            self.plru[lk.sub][lk.set] = plru_touch(cfg, self.plru[lk.sub][lk.set], lk.way)
        return out

    def release(self, lookups: Iterable[Lookup]) -> None:
        """The pass's read at the head: its references go."""
        for lk in lookups:
            x = self.slots[lk.sub][lk.set][lk.way]
            if x.refs <= 0:
                raise AssertionError(f"model: reference count underflow at {lk}")
            x.refs -= 1

    def error(self, c: int, la: int) -> None:
        """Line ``la`` of sub-cache ``c`` came back with an error: its slot is no longer valid
        (the passes waiting for it still hold their references)."""
        cfg = self.cfg
        s = set_of(la, cfg)
        tag = la >> (1 + cfg.set_w)
        for x in self.slots[c][s]:
            if x.valid and x.tag == tag:
                x.valid, x.err = False, True
                return
        raise AssertionError(f"model: error fill of line {la:#x} in sub-cache {c}, not held")


def texel_hits(p: Pass, out: Iterable[Lookup]) -> int:
    """Texels of pass ``p`` whose sub-cache's lookup hit."""
    hit = {lk.sub: lk.hit for lk in out}
    return sum(1 for t in range(4) if (p.mask >> t) & 1 and hit[p.sub[t]])


class TexCacheTimedModel:
    """The directory driven by the RTL's clocks (see the module docstring).  Per clock, in this
    order: :meth:`step` (once; ``clear``: clr_stats_i in this clock), then what happened in the
    clock: :meth:`decide` for the pass that enters the FIFO, :meth:`pop` for the head's read,
    :meth:`error` for a line completed with an error.  :meth:`reset` for a clock in reset.
    ``stats`` counts like the RTL's counters: a decision in the clock after it (the commit
    clock), nothing in a clock with clr_stats_i."""

    #: Clocks from a release / error fill to the first decision that sees it.
    DELAY = 2

    def __init__(self, cfg: TexCacheConfig):
        self.cfg = cfg
        self.reset()
        self.stats = {"quad_hits": 0, "lookups": 0, "line_misses": 0, "texel_hits": 0}

    def reset(self) -> None:
        """A clock in reset: the directory empties, queued passes are dropped, counts cleared."""
        self.dir = TexCacheDirectory(self.cfg)
        self.now = 0
        self.later: deque[tuple[int, str, object]] = deque()
        self.fifo: deque[list[Lookup]] = deque()
        self.missed = False      # an earlier pass of the current request missed
        self.count: dict[str, int] | None = None  # the last decision's counts, counted next clock
        self.stats = {"quad_hits": 0, "lookups": 0, "line_misses": 0, "texel_hits": 0}

    def step(self, clear: bool = False) -> None:
        """Start of a clock: events of clock now - DELAY + 1 and earlier become visible; the
        previous clock's decision is counted (unless ``clear``: then the counts restart)."""
        self.now += 1
        while self.later and self.later[0][0] <= self.now:
            _, kind, arg = self.later.popleft()
            if kind == "release":
                self.dir.release(arg)  # type: ignore[arg-type]
            else:
                c, la = arg  # type: ignore[misc]
                self.dir.error(c, la)
        if clear:
            self.stats = {k: 0 for k in self.stats}
        elif self.count:
            for k, v in self.count.items():
                self.stats[k] += v
        self.count = None

    def decide(self, p: Pass, last: bool) -> list[Lookup]:
        """Pass ``p`` (``last``: its request's last pass) enters the FIFO in this clock."""
        out = self.dir.enter(p)
        self.fifo.append(out)
        miss = any(not lk.hit for lk in out)
        self.count = {"lookups": len(out), "line_misses": sum(not lk.hit for lk in out),
                      "texel_hits": texel_hits(p, out),
                      "quad_hits": int(last and not miss and not self.missed)}
        self.missed = not last and (self.missed or miss)
        return out

    def pop(self) -> None:
        """The head's pass reads its lines in this clock."""
        if not self.fifo:
            raise AssertionError("model: head read with no pass queued")
        self.later.append((self.now + self.DELAY, "release", self.fifo.popleft()))

    def error(self, c: int, la: int) -> None:
        """Line ``la`` of sub-cache ``c`` completes with an error in this clock."""
        self.later.append((self.now + self.DELAY, "error", (c, la)))


class TexCacheModel:
    """Directory of the four sub-caches without timing (see the module docstring)."""

    def __init__(self, cfg: TexCacheConfig):
        self.cfg = cfg
        self.dir = TexCacheDirectory(cfg)
        self.stats = {"requests": 0, "quad_hits": 0, "lookups": 0, "line_misses": 0,
                      "texel_hits": 0, "passes": 0}

    def access(self, addrs: Sequence[int]) -> bool:
        """One request; True when every line lookup hit."""
        st = self.stats
        st["requests"] += 1
        all_hit = True
        for p in passes(addrs, self.cfg):
            st["passes"] += 1
            out = self.dir.enter(p)
            self.dir.release(out)
            st["lookups"] += len(out)
            st["texel_hits"] += texel_hits(p, out)
            miss = sum(not lk.hit for lk in out)
            st["line_misses"] += miss
            all_hit = all_hit and not miss
        st["quad_hits"] += all_hit
        return all_hit

    def run(self, stream: Iterable[Sequence[int]]) -> dict[str, int]:
        for q in stream:
            self.access(q)
        return dict(self.stats)
