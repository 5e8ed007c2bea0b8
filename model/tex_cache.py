"""Behavioural model of the texture / normal-map cache (rtl/cache/tex_cache.sv).

Not clock-accurate: it gives what is a pure function of the request stream in the RTL, and an
estimate of the rest.

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
- :class:`TexCacheModel`: the directory without timing (XOR-folded sets, tree pseudo-LRU, an
  invalid way first, a line allocated at lookup).  The RTL also skips ways that queued requests
  still reference, which depends on timing, so its miss count is close to, not equal to, the
  model's; the model serves to choose sizes and to estimate hit rates of an access stream.
"""
from __future__ import annotations

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


class TexCacheModel:
    """Directory of the four sub-caches without timing (see the module docstring)."""

    def __init__(self, cfg: TexCacheConfig):
        self.cfg = cfg
        n = cfg.sets
        self.tags = [[[None] * cfg.ways for _ in range(n)] for _ in range(4)]
        self.plru = [[0] * n for _ in range(4)]
        self.stats = {"requests": 0, "quad_hits": 0, "lookups": 0, "line_misses": 0,
                      "texel_hits": 0, "passes": 0}

    def lookup(self, c: int, la: int) -> bool:
        """One line lookup in sub-cache c; True on a hit (the line is allocated on a miss)."""
        cfg = self.cfg
        s = set_of(la, cfg)
        tag = la >> (1 + cfg.set_w)
        ways = self.tags[c][s]
        if tag in ways:
            w = ways.index(tag)
            hit = True
        else:
            w = ways.index(None) if None in ways else plru_victim(cfg, self.plru[c][s])
            ways[w] = tag
            hit = False
        self.plru[c][s] = plru_touch(cfg, self.plru[c][s], w)
        return hit

    def access(self, addrs: Sequence[int]) -> bool:
        """One request; True when every line lookup hit."""
        st = self.stats
        st["requests"] += 1
        all_hit = True
        for p in passes(addrs, self.cfg):
            st["passes"] += 1
            for c, la in p.lines.items():
                st["lookups"] += 1
                hit = self.lookup(c, la)
                # the texels of this pass in sub-cache c share its lookup's outcome
                st["texel_hits"] += hit * sum((p.mask >> t) & 1 and p.sub[t] == c
                                              for t in range(4))
                if not hit:
                    st["line_misses"] += 1
                    all_hit = False
        st["quad_hits"] += all_hit
        return all_hit

    def run(self, stream: Iterable[Sequence[int]]) -> dict[str, int]:
        for q in stream:
            self.access(q)
        return dict(self.stats)
