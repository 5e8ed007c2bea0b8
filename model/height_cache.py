# SPDX-License-Identifier: Apache-2.0
"""Clock-accurate model of the height cache (rtl/cache/height_cache.sv).

The model holds the same state as the RTL (directory, pseudo-LRU bits, MSHRs, AR queue, lookup
pipeline, statistics) and advances one clock per :meth:`HeightCacheModel.step`, given every input
of that clock.  :meth:`outputs` gives the outputs during the clock (before the edge), so a test can
compare the RTL with it clock by clock.  The behaviour (see the RTL header for the full text):

- lookups answer LOOKUP_LAT = 3 clocks later; hit = tag match in a valid way of the set, unless a
  line fill wrote that set in the clock the lookup was presented, or wrote the lookup's own line
  in the clock after (then: miss, no allocation);
- reset clears the valid bits by a sweep of SETS clocks after it (one set a clock): a lookup
  presented during the sweep answers a miss and allocates nothing, like one that meets a fill;
- a miss to a line held by an MSHR, or to the line of the miss in stage 3, merges; else the miss
  goes to stage 3, where the lowest free MSHR (then) is allocated and its AR queued; with every
  MSHR busy there the miss is not recorded;
- replacement: the lowest invalid way, else round robin per set (the way after the one last filled
  in the set; only fills move it);
- a line whose read had an AXI error is not cached; its MSHR answers rs_err to the first lookup of
  the line and to those of the next ERR_HOLD clocks, then frees;
- arid = {epoch, MSHR index}; the epoch advances at each reset; beats of other epochs are ignored.

The RTL's epoch starts at an arbitrary value: the model learns it from the first AR it sees
(:meth:`learn_epoch`); until then it accepts no R beat (none can arrive before an AR).
"""
from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field


FREE, WAIT, FILL, ERR = 0, 1, 2, 3


def clog2(x: int) -> int:
    return max(0, (x - 1).bit_length())


@dataclass(frozen=True)
class CacheConfig:
    """The RTL's parameters."""

    addr_w: int = 32
    data_w: int = 64
    line_bytes: int = 32
    sets: int = 64
    ways: int = 2
    mshrs: int = 4
    id_w: int = 4
    err_hold: int = 64

    @property
    def off_w(self) -> int:
        return clog2(self.line_bytes)

    @property
    def set_w(self) -> int:
        return clog2(self.sets)

    @property
    def beats(self) -> int:
        return self.line_bytes * 8 // self.data_w

    @property
    def beat_bytes(self) -> int:
        return self.data_w // 8

    @property
    def midx_w(self) -> int:
        return clog2(self.mshrs) if self.mshrs > 1 else 1

    @property
    def epoch_w(self) -> int:
        return self.id_w - self.midx_w

    def params(self) -> dict[str, int]:
        """As RTL parameters."""
        return {"ADDR_W": self.addr_w, "DATA_W": self.data_w, "LINE_BYTES": self.line_bytes,
                "SETS": self.sets, "WAYS": self.ways, "MSHRS": self.mshrs, "ID_W": self.id_w,
                "ERR_HOLD": self.err_hold}


@dataclass
class Mshr:
    state: int = FREE
    la: int = 0
    beat: int = 0
    rerr: bool = False
    errc: int = 0
    buf: list[int] = field(default_factory=list)


@dataclass
class Inputs:
    """Every input of one clock."""

    rst_n: int = 1
    lk_valid: int = 0
    lk_addr: int = 0
    lk_wide: int = 0
    arready: int = 0
    rvalid: int = 0
    rid: int = 0
    rdata: int = 0
    rresp: int = 0
    rlast: int = 0
    clr_stats: int = 0


@dataclass
class Outputs:
    rs_valid: int
    rs_hit: int
    rs_err: int
    rs_data: int
    arvalid: int
    araddr: int | None  # None while arvalid is 0
    arid: int | None    # None while arvalid is 0 or the epoch is not known yet
    ar_idx: int | None  # the MSHR index part of arid


class HeightCacheModel:
    """See the module docstring.  Call :meth:`step` once per clock, reset included."""

    def __init__(self, cfg: CacheConfig = CacheConfig()):
        self.cfg = cfg
        self.epoch: int | None = None
        self.in_rst = False
        self.ram: list[list[tuple[int, bytes] | None]] = [[None] * cfg.sets
                                                          for _ in range(cfg.ways)]
        self._clear()

    def _clear(self) -> None:
        c = self.cfg
        self.valid = [[False] * c.ways for _ in range(c.sets)]
        self.rr = [0] * c.sets  # round-robin pointer per set: the next victim among valid ways
        self.last_fill_set: int | None = None  # the set of the previous clock's fill
        self.mshr = [Mshr(buf=[0] * c.beats) for _ in range(c.mshrs)]
        self.arq: deque[int] = deque()
        self.fill_q = False
        self.fill_idx = 0
        self.sweep = c.sets  # clocks of the valid bits' reset sweep still to run
        # stages 1 and 2: (addr, wide, vbits, conflict, rd, swept) while s1_valid / s2_valid;
        # conflict: a fill wrote the set in the lookup's clock (stage 1), or that or the lookup's
        # own line in the next clock (stage 2); swept: the lookup came during the reset sweep
        self.s1_valid = False
        self.s1: tuple[int, int, list[bool], bool, list[tuple[int, bytes] | None], bool] | None \
            = None
        self.s2_valid = False
        self.s2: tuple[int, int, list[bool], bool, list[tuple[int, bytes] | None], bool] | None \
            = None
        self.s3_miss: int | None = None  # stage 3: the line address of a miss to allocate for
        self.rs = (0, 0, 0, 0)
        self.stats = {"hits": 0, "misses": 0, "bytes": 0, "lines": 0}
        self.st_ev = (False, False)  # stage 2's hit and miss, a clock before the counters

    # ------------------------------------------------------------------ helpers
    def _split(self, addr: int) -> tuple[int, int, int, int]:
        c = self.cfg
        off = addr & (c.line_bytes - 1)
        la = addr >> c.off_w
        st = la & (c.sets - 1)
        tag = la >> c.set_w
        return la, st, tag, off

    def learn_epoch(self, arid: int) -> None:
        if self.epoch is None:
            self.epoch = arid >> self.cfg.midx_w

    def outputs(self, rst_n: int = 1) -> Outputs:
        c = self.cfg
        arvalid = int(bool(rst_n) and len(self.arq) > 0)
        araddr = arid = idx = None
        if arvalid:
            idx = self.arq[0]
            araddr = self.mshr[idx].la << c.off_w
            if self.epoch is not None:
                arid = (self.epoch << c.midx_w) | idx
        return Outputs(*self.rs, arvalid, araddr, arid, idx)

    def busy_lines(self) -> int:
        """MSHRs in use (reads outstanding or errors held)."""
        return sum(m.state != FREE for m in self.mshr)

    # ------------------------------------------------------------------ one clock
    def _fill_target(self) -> tuple[int, int, int]:
        """(set, tag, way) of the pending fill, from the state before the edge."""
        c = self.cfg
        m = self.mshr[self.fill_idx]
        _, st, tag, _ = self._split(m.la << c.off_w)
        way = self.rr[st]
        for w in range(c.ways - 1, -1, -1):
            if not self.valid[st][w]:
                way = w
        return st, tag, way

    def step(self, i: Inputs) -> dict[str, bool]:
        """Advance one clock with inputs ``i``; returns what happened (for the test's counts)."""
        c = self.cfg
        ev = {"alloc": False, "ar": False, "beat": False, "fill": False, "err_line": False,
              "conflict": False, "merge": False, "full": False, "stale_beat": False,
              "hit_fill_set": False, "fill_fill_set": False, "sweep": False}
        fill = self._fill_target() if self.fill_q else None
        if not i.rst_n:
            if not self.in_rst and self.epoch is not None:
                self.epoch = (self.epoch + 1) % (1 << c.epoch_w)
            self.in_rst = True
            self._clear()  # (a pending fill still writes the RAM; its way stays invalid)
            return ev
        self.in_rst = False
        swept = self.sweep > 0  # the valid bits' reset sweep runs in this clock
        if swept:
            self.sweep -= 1
            ev["sweep"] = True

        # ---- stage 0: the RAM read sees the contents before this edge's fill write
        new_s1 = None
        if i.lk_valid:
            _, set0, _, _ = self._split(i.lk_addr)
            new_s1 = (i.lk_addr, i.lk_wide, list(self.valid[set0]),
                      fill is not None and fill[0] == set0,
                      [self.ram[w][set0] for w in range(c.ways)], swept)

        # ---- stage 1: the RAM reads copied; a fill of the lookup's line in this clock is a
        # conflict too
        new_s2 = None
        if self.s1_valid:
            assert self.s1 is not None
            addr1, wide1, vbits1, conflict1, rd1, swept1 = self.s1
            _, set1, tag1, _ = self._split(addr1)
            same_line = fill is not None and fill[0] == set1 and fill[1] == tag1
            new_s2 = (addr1, wide1, vbits1, conflict1 or same_line, rd1, swept1)

        # ---- stage 2
        hit = err = miss = False
        data = hit_way = s2set = la = 0
        match = [False] * c.mshrs
        if self.s2_valid:
            assert self.s2 is not None
            addr, wide, vbits, fill_conflict, rd, s2_swept = self.s2
            conflict = fill_conflict or s2_swept
            la, s2set, tag, off = self._split(addr)
            way_hit = [bool(vbits[w]) and rd[w] is not None and rd[w][0] == tag
                       for w in range(c.ways)]
            for w in range(c.ways):
                if way_hit[w]:
                    hit_way = w
            hit = (not conflict) and any(way_hit)
            if hit:
                line = rd[hit_way][1]
                if wide:
                    o = off & ~1
                    data = line[o] | (line[o + 1] << 8)
                else:
                    data = line[off]
            match = [m.state != FREE and m.la == la for m in self.mshr]
            err = (not hit) and any(mt and m.state == ERR for mt, m in zip(match, self.mshr))
            same3 = self.s3_miss == la
            miss = (not conflict) and not any(way_hit) and not any(match) and not same3
            ev["conflict"] = fill_conflict
            ev["merge"] = not hit and (any(match) or (not conflict and same3))

        # ---- stage 3: the miss allocates the lowest free MSHR
        alloc = False
        alloc_idx = la3 = 0
        if self.s3_miss is not None:
            la3 = self.s3_miss
            free = [k for k, m in enumerate(self.mshr) if m.state == FREE]
            alloc = bool(free)
            if alloc:
                alloc_idx = free[0]
            ev["full"] = not free

        # ---- R channel
        r_idx = i.rid & ((1 << c.midx_w) - 1)
        r_epoch = i.rid >> c.midx_w
        r_acc = bool(i.rvalid) and self.epoch is not None and r_epoch == self.epoch \
            and r_idx < c.mshrs and self.mshr[r_idx].state == WAIT
        r_last = r_bad = False
        if r_acc:
            m = self.mshr[r_idx]
            r_last = m.beat == c.beats - 1
            r_bad = bool(i.rresp & 2) or m.rerr
            if bool(i.rlast) != r_last:
                raise AssertionError("model: rlast on a beat other than the last")
        ar_pop = len(self.arq) > 0 and bool(i.arready)

        # ---- fill and directory
        if fill is not None:
            fset, ftag, fway = fill
            m = self.mshr[self.fill_idx]
            self.ram[fway][fset] = (ftag, b"".join(int(d).to_bytes(c.beat_bytes, "little")
                                                   for d in m.buf))
            self.rr[fset] = (fway + 1) % c.ways
            self.valid[fset][fway] = True
            ev["fill"] = True
            # a hit and a fill on the same set in one clock
            ev["hit_fill_set"] = hit and fset == s2set
            # a fill on the set the previous clock's fill wrote (the RTL forwards that write)
            ev["fill_fill_set"] = self.last_fill_set == fset
            self.last_fill_set = fset
        else:
            self.last_fill_set = None

        # ---- MSHRs
        for k, m in enumerate(self.mshr):
            if m.state == WAIT:
                if r_acc and r_idx == k:
                    m.buf[m.beat] = i.rdata
                    m.beat += 1
                    m.rerr = r_bad
                    if r_last:
                        m.beat = 0
                        m.state = ERR if r_bad else FILL
                        m.errc = 0
                        ev["err_line"] = r_bad
            elif m.state == FILL:
                m.state = FREE
            elif m.state == ERR:
                if m.errc != 0:
                    if m.errc == 1:
                        m.state = FREE
                    m.errc -= 1
                elif self.s2_valid and match[k]:
                    m.errc = c.err_hold
            if alloc and alloc_idx == k:
                m.state = WAIT
                m.beat = 0
                m.rerr = False
                m.la = la3
        self.fill_q = r_acc and r_last and not r_bad
        self.fill_idx = r_idx if r_acc else self.fill_idx

        # ---- AR queue
        if ar_pop:
            self.arq.popleft()
            ev["ar"] = True
        if alloc:
            self.arq.append(alloc_idx)
            ev["alloc"] = True

        # ---- statistics
        if i.clr_stats:
            self.stats = {"hits": 0, "misses": 0, "bytes": 0, "lines": 0}
            self.st_ev = (False, False)
        else:
            self.stats["hits"] += int(self.st_ev[0])
            self.stats["misses"] += int(self.st_ev[1])
            self.st_ev = (bool(hit), bool(self.s2_valid and not hit))
            self.stats["lines"] += int(ar_pop)
            self.stats["bytes"] += c.beat_bytes if r_acc else 0
        ev["beat"] = r_acc
        ev["stale_beat"] = bool(i.rvalid) and not r_acc

        # ---- pipeline registers
        self.rs = (int(self.s2_valid), int(hit), int(err), data if hit else 0)
        self.s3_miss = la if miss else None
        self.s2_valid = self.s1_valid
        if new_s2 is not None:
            self.s2 = new_s2
        self.s1_valid = bool(i.lk_valid)
        if new_s1 is not None:
            self.s1 = new_s1
        return ev
