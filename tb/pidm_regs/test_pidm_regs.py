# SPDX-License-Identifier: Apache-2.0
"""The generated register block (rtl/top/pidm_regs.sv from rtl/top/pidm_regs.rdl) with pidm_cfg
behind it, driven over AXI4-Lite by cocotbext-axi's master as the driver (sw/pidm.c) drives it.

- frame_config: a frame packed by tb/harness/pidm_frame.py (the rocks scene) written register by
  register, in random order, with random gaps: every cfg_* port of pidm_cfg equals the port value
  the pipeline harness would drive (tb/harness/pipeline_words.config), the table writes come out
  on tt_we_o / tt_waddr_o / tt_wdata_o one per TT_WRITE write in order, each write of a level
  register HEIGHT.LEVEL_OFF[k], TEX[x].LEVEL_OFF[k] / LEVEL_SIZE[k] as one lvt_we_o pulse with
  lvt_waddr_o {kind, x, k} (kind 1, 2, 3; x 0 for HEIGHT) and lvt_wdata_o the word written, in
  order (the tables end up holding the harness's level-table writes,
  tb/harness/pipeline_words.config's lvt_writes), and every register reads back what was written
  (the write-only tables LEVEL_OFF and LEVEL_SIZE read 0); the frame descriptor reaches its ports;
- level_tables: random writes to the 80 level registers (HEIGHT.LEVEL_OFF, TEX[x] LEVEL_OFF and
  LEVEL_SIZE, external registers of the block), back to back and with gaps, mixed with writes
  to the stored table PYR.LEVEL_OFF, other registers and unmapped words beside the level
  tables, and with reads of the level registers: exactly one lvt_we_o pulse per level-register
  write, in order, with its {kind, x, k} and data, none for any other write; every read of them
  returns 0 with OKAY;
- control_status_interrupts: CTRL bits are one-clock pulses and read 0; ERROR flags are set by
  the hardware, kept, and cleared by writing 1 (only the bits written); INTR_STATE is set by the
  hardware events and by INTR_TEST, the interrupt line follows INTR_STATE & INTR_ENABLE, writing 1
  clears; ID, VERSION, HWCFG, STATUS, PROGRESS and the 48-bit statistics read what the hardware
  gives (random values, seed printed); a one-byte write writes the whole word (WSTRB is
  ignored); an unmapped address reads 0 with OKAY.
"""
from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge, ReadOnly, RisingEdge
from cocotbext.axi import AxiLiteBus, AxiLiteMaster

from tb.common import fp_unit, report, runner
from tb.harness import dm_pipeline, pidm_frame, pidm_regmap, pipeline_words, sv_params

R = pidm_regmap.reg
#: rtl/pipe/pipe_pkg.sv: the level table address {kind [1:0], texture, level}.
TEX_LVL_W, LVT_ADDR_W = sv_params.values("pipe_pkg", "TEX_LVL_W", "LVT_ADDR_W")
LVT_HEIGHT_OFF, LVT_TEX_OFF, LVT_TEX_SIZE = (pipeline_words.LVT_HEIGHT_OFF,
                                             pipeline_words.LVT_TEX_OFF,
                                             pipeline_words.LVT_TEX_SIZE)
#: The level registers (external registers of the block) as (name, kind, texture).
LEVEL_TABLES = (("HEIGHT.LEVEL_OFF", LVT_HEIGHT_OFF, 0),
                *((f"TEX[{x}].{n}", kind, x) for x in range(2)
                  for n, kind in (("LEVEL_OFF", LVT_TEX_OFF), ("LEVEL_SIZE", LVT_TEX_SIZE))))


def lvt_write(addr: int, value: int) -> tuple[int, int] | None:
    """The level-table write (lvt_waddr_o, lvt_wdata_o) a register write makes: a write of
    HEIGHT.LEVEL_OFF[k] is {LVT_HEIGHT_OFF, 0, k} with the word, of TEX[x].LEVEL_OFF[k]
    {LVT_TEX_OFF, x, k}, of TEX[x].LEVEL_SIZE[k] {LVT_TEX_SIZE, x, k}; None for any other
    address."""
    for name, kind, x in LEVEL_TABLES:
        base = R(f"{name}[0]").addr
        k = (addr - base) // 4
        if addr % 4 == 0 and 0 <= k < 1 << TEX_LVL_W:
            assert R(f"{name}[{k}]").addr == addr
            w = pipeline_words.lvt_addr(kind, x, k)
            assert w < 1 << LVT_ADDR_W
            return w, value & 0xFFFFFFFF
    return None


def watch_writes(dut, port: str, seen: list[tuple[int, int]]) -> None:
    """Record every table write of pidm_cfg's port ``port`` (tt, lvt): each <port>_we_o pulse's
    (<port>_waddr_o, <port>_wdata_o), in ``seen``."""
    we, waddr, wdata = (getattr(dut, f"{port}_{s}_o") for s in ("we", "waddr", "wdata"))

    async def mon() -> None:
        while True:
            await RisingEdge(dut.clk_i)
            await ReadOnly()
            if int(we.value):
                seen.append((int(waddr.value), int(wdata.value)))

    cocotb.start_soon(mon())


async def setup(dut) -> AxiLiteMaster:
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    dut.busy_i.value = 0
    dut.idle_i.value = 1
    dut.error_set_i.value = 0
    dut.intr_event_i.value = 0
    dut.progress_i.value = 0
    dut.stats_i.value = 0
    dut.hwcfg_i.value = 0
    dut.pyr_status_i.value = 0
    dut.pyr_info_i.value = 0
    axil = AxiLiteMaster(AxiLiteBus.from_prefix(dut, "s_axil"), dut.clk_i, dut.rst_ni,
                         reset_active_level=False)
    dut.rst_ni.value = 0
    await ClockCycles(dut.clk_i, 4)
    dut.rst_ni.value = 1
    await ClockCycles(dut.clk_i, 2)
    return axil


async def write(axil: AxiLiteMaster, addr: int, value: int) -> None:
    resp = await axil.write(addr, int(value).to_bytes(4, "little"))
    assert int(resp.resp) == 0, f"write {addr:#x}: response {resp.resp}"


async def read(axil: AxiLiteMaster, addr: int) -> int:
    resp = await axil.read(addr, 4)
    assert int(resp.resp) == 0, f"read {addr:#x}: response {resp.resp}"
    return int.from_bytes(resp.data, "little")


@cocotb.test()
async def frame_config(dut):
    rng = np.random.default_rng(fp_unit.seed())
    axil = await setup(dut)
    frame, cam = dm_pipeline.scene_frame("rocks", 32, "oblique", 16, "park")
    packed = pidm_frame.pack(frame, cam, frag_base=0x1_2345_6740, fb_base=0x2_0000_0100,
                             status_base=0x3_0000_0000)
    cfg = dm_pipeline.frame_image(frame).cfg
    tt = R("TT_WRITE").addr
    regs = [(a, v) for a, v in packed.config if a != tt]
    tri = [(a, v) for a, v in packed.config if a == tt]
    # the table writes are watched on tt_we_o
    seen: list[tuple[int, int]] = []
    watch_writes(dut, "tt", seen)
    lvt_seen: list[tuple[int, int]] = []
    lvt_want: list[tuple[int, int]] = []
    watch_writes(dut, "lvt", lvt_seen)
    order = rng.permutation(len(regs))
    for i in order:
        a, v = regs[int(i)]
        await write(axil, a, v)
        if (w := lvt_write(a, v)) is not None:
            lvt_want.append(w)
        if rng.random() < 0.2:
            await ClockCycles(dut.clk_i, int(rng.integers(1, 4)))
    for a, v in tri:
        await write(axil, a, v)
    for a, v in packed.frame_writes:
        await write(axil, a, v)
    await ClockCycles(dut.clk_i, 3)
    await FallingEdge(dut.clk_i)
    bad = []
    for name, _bits in dm_pipeline.CFG_PORTS:
        got = int(getattr(dut, name[:-2] + "_o").value)
        if got != cfg.ports[name]:
            bad.append(f"{name}: {got:#x} != {cfg.ports[name]:#x}")
    if seen != cfg.tri_writes:
        bad.append(f"table writes {seen[:4]}... ({len(seen)}) != {cfg.tri_writes[:4]}... "
                   f"({len(cfg.tri_writes)})")
    # one level-table write per HEIGHT.LEVEL_OFF, TEX[x].LEVEL_OFF / LEVEL_SIZE write, in order;
    # the tables end up holding what the pipeline harness writes into them
    if lvt_seen != lvt_want:
        i = next((i for i, (g, w) in enumerate(zip(lvt_seen, lvt_want)) if g != w),
                 min(len(lvt_seen), len(lvt_want)))
        bad.append(f"level-table writes: {len(lvt_seen)} for {len(lvt_want)}, first difference "
                   f"at {i}: {lvt_seen[i:i + 2]} != {lvt_want[i:i + 2]}")
    if dict(lvt_seen) != dict(cfg.lvt_writes):
        bad.append("the level tables do not hold the harness's level-table writes")
    d = packed.descriptor
    for port, want in (("frag_base_o", d["frag_base"]), ("frag_count_o", d["frag_count"]),
                       ("fb_base_o", d["fb_base"]), ("fb_pitch_o", d["fb_pitch"]),
                       ("status_base_o", d["status_base"]), ("xbits_o", d["xbits"]),
                       ("status_en_o", d["status_en"])):
        if int(getattr(dut, port).value) != want:
            bad.append(f"{port}: {int(getattr(dut, port).value):#x} != {want:#x}")
    # read back every register written (the last value of TT_WRITE); the write-only tables
    # (LEVEL_OFF, LEVEL_SIZE) read 0
    last = dict(regs + tri[-1:] + packed.frame_writes)
    n_wo = 0
    for a, v in last.items():
        got = await read(axil, a)
        if not pidm_regmap.by_address()[a].readable:
            n_wo += 1
            v = 0
        if got != v:
            bad.append(f"read {pidm_regmap.by_address()[a].path} ({a:#x}): {got:#x} != {v:#x}")
    n = len(dm_pipeline.CFG_PORTS) + len(cfg.tri_writes) + len(lvt_want) + len(last)
    report.record(dut._name, "configuration ports, table writes, read-back", n, len(bad))
    dut._log.info("VECTORS pidm_regs frame_config: %d register writes, %d table writes, %d "
                  "level-table writes, %d checks (%d write-only reads), %d mismatches",
                  len(regs), len(tri), len(lvt_want), n, n_wo, len(bad))
    assert n_wo > 0, "the frame wrote no write-only register"
    assert len(lvt_want) == (1 + 2 * 2) << TEX_LVL_W == len(cfg.lvt_writes), \
        "the frame wrote not every level register"
    assert not bad, "\n".join(bad[:20])


@cocotb.test()
async def level_tables(dut):
    rng = np.random.default_rng(fp_unit.seed())
    axil = await setup(dut)
    seen: list[tuple[int, int]] = []
    watch_writes(dut, "lvt", seen)
    lvl = [R(f"{name}[{k}]").addr for name, _, _ in LEVEL_TABLES for k in range(1 << TEX_LVL_W)]
    # writes that must not reach the level tables: the stored table PYR.LEVEL_OFF, other
    # registers of HEIGHT, TEX and elsewhere, unmapped words beside the level tables
    others = ([R(f"PYR.LEVEL_OFF[{k}]").addr for k in (0, 9, 15)]
              + [R(f"TEX[{x}].{n}").addr for x in range(2) for n in ("SU", "SV", "BASE")]
              + [R(f"HEIGHT.{n}").addr for n in ("MODE", "BASE", "DEPTH")]
              + [R("FRAME.FRAG_COUNT").addr,
                 0x214, 0x23C, 0x280, 0x2FC,
                 0x40C, 0x43C, 0x4C0, 0x4FC, 0x50C, 0x53C, 0x5C0, 0x5FC])
    want: list[tuple[int, int]] = []
    reads = 0

    def value() -> int:
        return int(rng.integers(0, 1 << 32, dtype=np.uint64))

    # every entry once, back to back (the master's writes queued together)
    events = []
    for a in rng.permutation(lvl):
        v = value()
        events.append(axil.init_write(int(a), v.to_bytes(4, "little")))
        want.append(lvt_write(int(a), v))
    for e in events:
        await e.wait()
        assert int(e.data.resp) == 0, "write response"
    # random writes (level or other, some back to back) mixed with reads of the level registers,
    # with gaps
    for _ in range(300):
        r = rng.random()
        if r < 0.15:
            a = int(rng.choice(lvl))
            got = await read(axil, a)
            reads += 1
            assert got == 0, f"read of {pidm_regmap.by_address()[a].path} ({a:#x}): {got:#x}"
            continue
        burst = int(rng.integers(1, 4))
        events = []
        for _ in range(burst):
            a = int(rng.choice(lvl)) if rng.random() < 0.7 else int(rng.choice(others))
            v = value()
            events.append(axil.init_write(a, v.to_bytes(4, "little")))
            if (w := lvt_write(a, v)) is not None:
                want.append(w)
        if rng.random() < 0.3:   # a read issued while the writes are in flight
            a = int(rng.choice(lvl))
            got = await read(axil, a)
            reads += 1
            assert got == 0, f"read of {a:#x} beside writes: {got:#x}"
        for e in events:
            await e.wait()
            assert int(e.data.resp) == 0, "write response"
        if rng.random() < 0.3:
            await ClockCycles(dut.clk_i, int(rng.integers(1, 4)))
    await ClockCycles(dut.clk_i, 4)
    bad = [f"pulse {i}: (waddr, data) {s!r} != {w!r}"
           for i, (s, w) in enumerate(zip(seen, want)) if s != w]
    if len(seen) != len(want):
        bad.append(f"{len(seen)} lvt_we_o pulses for {len(want)} level-table writes")
    kinds = {(w[0] >> (TEX_LVL_W + 1), (w[0] >> TEX_LVL_W) & 1) for w in want}
    assert kinds == {(LVT_HEIGHT_OFF, 0)} | {(kind, x) for kind in (LVT_TEX_OFF, LVT_TEX_SIZE)
                                             for x in range(2)}, \
        "the height offsets and both kinds of both textures"
    report.record(dut._name, "level-table writes and reads", len(want) + reads, len(bad))
    dut._log.info("VECTORS pidm_regs level_tables: %d level-table writes, %d reads, %d "
                  "mismatches", len(want), reads, len(bad))
    assert not bad, "\n".join(bad[:20])


async def pulse_seen(dut, port: str, action) -> list[int]:
    """Run ``action`` and record ``port`` every clock until 6 clocks after it."""
    values: list[int] = []
    done = False

    async def mon() -> None:
        while not done:
            await RisingEdge(dut.clk_i)
            await ReadOnly()
            values.append(int(getattr(dut, port).value))

    task = cocotb.start_soon(mon())
    await action()
    await ClockCycles(dut.clk_i, 6)
    done = True
    await task
    await FallingEdge(dut.clk_i)
    return values


@cocotb.test()
async def control_status_interrupts(dut):
    rng = np.random.default_rng(fp_unit.seed())
    axil = await setup(dut)
    checks = 0

    def check(cond: bool, msg: str) -> None:
        nonlocal checks
        checks += 1
        assert cond, msg

    check(await read(axil, R("ID").addr) == 0x5049444D, "ID")
    check(await read(axil, R("VERSION").addr) == 0x00010002, "VERSION")
    hw = int(rng.integers(0, 1 << 32))
    dut.hwcfg_i.value = hw
    check(await read(axil, R("HWCFG").addr) == hw, "HWCFG")
    # CTRL: each bit one clock high, reads 0
    ctrl = R("CTRL")
    ports = ("start_o", "soft_reset_o", "clear_stats_o", "pyr_start_o")
    for field, port in (("start", "start_o"), ("soft_reset", "soft_reset_o"),
                        ("clear_stats", "clear_stats_o"), ("pyr_start", "pyr_start_o")):
        v = await pulse_seen(dut, port, lambda f=field: write(axil, ctrl.addr, ctrl.value(**{f: 1})))
        check(sum(v) == 1, f"CTRL.{field}: high {sum(v)} clocks")
        for other in ports:
            if other != port:
                check(int(getattr(dut, other).value) == 0, f"CTRL.{field} pulsed {other}")
        check(await read(axil, ctrl.addr) == 0, f"CTRL reads 0 after {field}")
    v = await pulse_seen(dut, "start_o", lambda: write(axil, ctrl.addr, 0))
    check(sum(v) == 0, "CTRL write of 0 pulses nothing")
    # STATUS, PROGRESS, statistics: what the hardware gives
    for busy, idle in ((1, 0), (0, 1), (1, 1)):
        dut.busy_i.value, dut.idle_i.value = busy, idle
        check(await read(axil, R("STATUS").addr) == busy | idle << 1, "STATUS")
    dut.busy_i.value, dut.idle_i.value = 0, 1
    for pst in (0b000001, 0b000010, 0b101110, 0b111111, 0):
        dut.pyr_status_i.value = pst
        want = R("STATUS").value(busy=0, idle=1, pyr_busy=pst & 1, pyr_done=pst >> 1 & 1,
                                 pyr_err_code=pst >> 2)
        check(await read(axil, R("STATUS").addr) == want, f"STATUS pyr fields {pst:#b}")
    for info in (0b10101, 0b00001, 0):
        dut.pyr_info_i.value = info
        check(R("PYR.INFO").fields_of(await read(axil, R("PYR.INFO").addr))
              == {"present": info & 1, "max_lg": info >> 1}, f"PYR.INFO {info:#b}")
    prog = int(rng.integers(0, 1 << 32))
    dut.progress_i.value = prog
    check(await read(axil, R("PROGRESS").addr) == prog, "PROGRESS")
    stats = [int(rng.integers(0, 1 << 48)) for _ in range(11)]
    stats[3] = (1 << 48) - 1
    dut.stats_i.value = sum(s << (48 * i) for i, s in enumerate(stats))
    names = ("cycles", "pixels", "iters", "h_hits", "h_misses", "h_bytes", "t_requests",
             "t_quad_hits", "t_line_misses", "t_texel_hits", "t_bytes")
    for i, name in enumerate(names):
        lo = await read(axil, R(f"STATS.{name}.LO").addr)
        hi = await read(axil, R(f"STATS.{name}.HI").addr)
        check(lo | hi << 32 == stats[i], f"STATS.{name}: {lo | hi << 32:#x} != {stats[i]:#x}")
    # ERROR: set by hardware (one clock), sticky, write 1 to clear only those bits
    err = R("ERROR")
    dut.error_set_i.value = 0b10110
    await RisingEdge(dut.clk_i)
    dut.error_set_i.value = 0
    await ClockCycles(dut.clk_i, 3)
    check(await read(axil, err.addr) == 0b10110, "ERROR after hwset")
    check(int(dut.error_o.value) == 0b10110, "ERROR to hardware")
    await write(axil, err.addr, 0)
    check(await read(axil, err.addr) == 0b10110, "ERROR write 0 keeps")
    await write(axil, err.addr, 0b00110)
    check(await read(axil, err.addr) == 0b10000, "ERROR W1C")
    await write(axil, err.addr, 0b11111)
    check(await read(axil, err.addr) == 0, "ERROR cleared")
    dut.error_set_i.value = 0b101100000
    await RisingEdge(dut.clk_i)
    dut.error_set_i.value = 0
    await ClockCycles(dut.clk_i, 3)
    check(R("ERROR").fields_of(await read(axil, err.addr))
          == {**{f: 0 for f in err.fields}, "pyr_read": 1, "pyr_write": 1, "start_refused": 1},
          "ERROR pyramid bits after hwset")
    check(int(dut.error_o.value) == 0b101100000, "ERROR pyramid bits to hardware")
    await write(axil, err.addr, 0x1FF)
    check(await read(axil, err.addr) == 0, "ERROR pyramid bits cleared")
    # Interrupts
    st, en, ts = R("INTR_STATE").addr, R("INTR_ENABLE").addr, R("INTR_TEST").addr
    check(await read(axil, st) == 0 and int(dut.intr_o.value) == 0, "INTR idle")
    dut.intr_event_i.value = 0b01
    await RisingEdge(dut.clk_i)
    dut.intr_event_i.value = 0
    await ClockCycles(dut.clk_i, 2)
    check(await read(axil, st) == 0b01, "INTR_STATE frame_done set by the event")
    check(int(dut.intr_o.value) == 0, "no interrupt while disabled")
    await write(axil, en, 0b10)
    await ClockCycles(dut.clk_i, 2)
    check(int(dut.intr_o.value) == 0, "frame_done not enabled")
    await write(axil, en, 0b11)
    await ClockCycles(dut.clk_i, 2)
    check(int(dut.intr_o.value) == 1, "interrupt when enabled")
    check(await read(axil, en) == 0b11, "INTR_ENABLE reads back")
    await write(axil, st, 0b01)
    await ClockCycles(dut.clk_i, 2)
    check(int(dut.intr_o.value) == 0 and await read(axil, st) == 0, "W1C drops the line")
    await write(axil, ts, 0b10)
    await ClockCycles(dut.clk_i, 2)
    check(await read(axil, st) == 0b10 and int(dut.intr_o.value) == 1, "INTR_TEST sets axi_error")
    check(await read(axil, ts) == 0, "INTR_TEST reads 0")
    await write(axil, st, 0b11)
    dut.intr_event_i.value = 0b100
    await RisingEdge(dut.clk_i)
    dut.intr_event_i.value = 0
    await ClockCycles(dut.clk_i, 2)
    check(await read(axil, st) == 0b100 and int(dut.intr_o.value) == 0,
          "INTR_STATE pyr_done set by the event, not enabled")
    await write(axil, en, 0b100)
    await ClockCycles(dut.clk_i, 2)
    check(int(dut.intr_o.value) == 1, "pyr_done interrupt when enabled")
    await write(axil, st, 0b100)
    await write(axil, ts, 0b100)
    await ClockCycles(dut.clk_i, 2)
    check(await read(axil, st) == 0b100 and int(dut.intr_o.value) == 1, "INTR_TEST sets pyr_done")
    await write(axil, st, 0b111)
    await write(axil, en, 0)
    # WSTRB is ignored: a one-byte write (strobe 0b0010, the other byte lanes 0) writes the whole
    # word, the bytes without a strobe too
    size = R("HEIGHT.SIZE")
    await write(axil, size.addr, 0xFFFFFFFF)
    resp = await axil.write(size.addr + 1, bytes([0xAB]))
    check(int(resp.resp) == 0, "one-byte write answered OKAY")
    check(await read(axil, size.addr) == 0x0000AB00, "a one-byte write writes the whole word")
    check(int(dut.cfg_width_o.value) == 0xAB00 and int(dut.cfg_height_o.value) == 0,
          "the whole word reaches cfg_width_o / cfg_height_o")
    # An unmapped address reads 0 with OKAY, a write there changes nothing
    for a in (0x00C, 0x02C, 0x0F0, 0x104, 0x280, 0x3FC, 0x4C0, 0x5C0, 0x628, 0x6C0, 0xFFC):
        await write(axil, a, 0xFFFFFFFF)
        check(await read(axil, a) == 0, f"unmapped {a:#x} reads 0")
    check(await read(axil, R("ID").addr) == 0x5049444D, "ID after unmapped writes")
    report.record(dut._name, "control, status, errors, interrupts", checks, 0)
    dut._log.info("VECTORS pidm_regs control_status_interrupts: %d checks, 0 mismatches", checks)


def test_pidm_regs():
    here = Path(__file__).parent
    runner.run("pidm_regs_tb", "test_pidm_regs", here, rtl_top="pidm_regs",
               extra_sources=[str(here / "pidm_regs_tb.sv")])
