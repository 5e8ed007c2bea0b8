#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Generate the register block, the C header and the register docs from rtl/top/pidm_regs.rdl.

    python scripts/flow/regs.py            # write the committed outputs (make regs)
    python scripts/flow/regs.py --check    # regenerate into a temp dir; exit 1 if one is stale

PeakRDL (pinned in requirements.txt) does the work: peakrdl-regblock (AXI4-Lite, flattened ports,
synchronous active-low reset ``rst_n``, 12-bit address: the 4 KiB map, the read path retimed
with ``--rt-read-fanin``), peakrdl-cheader and peakrdl-markdown.  The retimed read path splits
the readback multiplexer into 32 groups with a register between them (a read answers one clock
later): without it the readback is one chain of a multiplexer per register, several hundred
cells deep, which YoWASP's Yosys cannot map (its XAIGER2 pass walks such a chain recursively and
runs out of WebAssembly stack: ``wasm trap: call stack exhausted``).  Each generated source file gets the SPDX line and a "generated, do not edit"
line on top.  One line of the register block is changed (``WHOLE_WORD``): its AXI4-Lite front
end ignores WSTRB, every write writes the whole 32-bit register (AXI4-Lite allows a slave to
ignore the write strobes).  Honouring the strobes costs a multiplexer per stored bit, about
4,000 of the block's LUT4s on the ECP5 (docs/system_top.md); software writes whole words.
Nothing else is changed.  Exit status 2 (one line) when PeakRDL is missing, rejects the .rdl
file, or its output no longer holds the line to change.
"""
from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from model.cli import Parser, fail

PROG = "regs.py"
RDL = Path("rtl/top/pidm_regs.rdl")
SPDX = "SPDX-License-Identifier: Apache-2.0"
NOTE = f"Generated from {RDL} by scripts/flow/regs.py (make regs): do not edit."


@dataclass(frozen=True)
class Output:
    """One generated file: its path in the repository and its comment leader (None: no header)."""

    path: Path
    leader: str | None


#: The register block's one changed line: the byte strobes as the bit enables, replaced by all
#: ones (WSTRB ignored: whole-word writes).
WHOLE_WORD = (Path("rtl/top/pidm_regs.sv"),
              "cpuif_wr_biten[i*8 +: 8] = {8{axil_wstrb[i]}};",
              "cpuif_wr_biten[i*8 +: 8] = '1;  // WSTRB ignored: whole-word writes "
              "(scripts/flow/regs.py)")

#: Every generated file, as committed.
OUTPUTS = (
    Output(Path("rtl/top/pidm_regs.sv"), "//"),
    Output(Path("rtl/top/pidm_regs_pkg.sv"), "//"),
    Output(Path("sw/pidm_regs.h"), "//"),
    Output(Path("docs/registers.md"), None),
)


def peakrdl() -> str:
    """The peakrdl command of this Python's environment (or on PATH)."""
    here = Path(sys.executable).parent / "peakrdl"
    if here.is_file():
        return str(here)
    found = shutil.which("peakrdl")
    if found is None:
        fail(PROG, "peakrdl not found (make setup installs it from requirements.txt)")
    return found


def run(cmd: list[str]) -> None:
    """Run one PeakRDL command; a failure ends the program with its first error line."""
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        lines = [ln for ln in (p.stderr + p.stdout).splitlines() if ln.strip()]
        first = next((ln for ln in lines if "error" in ln.lower()), lines[0] if lines else "")
        fail(PROG, f"{Path(cmd[0]).name} {cmd[1]} failed: {first.strip()}")


def generate(out: Path) -> None:
    """Write every output under ``out`` (the same relative paths as in the repository)."""
    tool = peakrdl()
    rdl = str(RDL)  # relative to ROOT (the cwd of every run): no machine path in the outputs
    for o in OUTPUTS:
        (out / o.path).parent.mkdir(parents=True, exist_ok=True)
    run([tool, "regblock", rdl, "-o", str(out / "rtl/top"), "--cpuif", "axi4-lite-flat",
         "--default-reset", "rst_n", "--type-style", "hier", "--addr-width", "12",
         "--rt-read-fanin"])
    run([tool, "c-header", rdl, "-o", str(out / "sw/pidm_regs.h"), "--std", "gnu11",
         "--type-style", "hier"])
    run([tool, "markdown", rdl, "-o", str(out / "docs/registers.md")])
    path, was, now = WHOLE_WORD
    text = (out / path).read_text()
    if text.count(was) != 1:
        fail(PROG, f"{path}: peakrdl-regblock's output has no line '{was}' to change")
    (out / path).write_text(text.replace(was, now))
    for o in OUTPUTS:
        path = out / o.path
        if o.leader is not None:
            text = path.read_text()
            path.write_text(f"{o.leader} {SPDX}\n{o.leader} {NOTE}\n{text}")


def check() -> int:
    """Regenerate into a temp dir and compare with the committed files."""
    with tempfile.TemporaryDirectory(prefix="regs-") as tmp:
        generate(Path(tmp))
        for o in OUTPUTS:
            fresh = (Path(tmp) / o.path).read_bytes()
            committed = ROOT / o.path
            if not committed.is_file() or committed.read_bytes() != fresh:
                print(f"regs: {o.path} is stale (run make regs)")
                return 1
    print(f"regs: {len(OUTPUTS)} generated files are current with {RDL}")
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true",
                    help="regenerate into a temp dir and exit 1 when a committed file differs")
    args = ap.parse_args(argv)
    if not (ROOT / RDL).is_file():
        fail(PROG, f"{RDL} not found")
    if args.check:
        return check()
    generate(ROOT)
    for o in OUTPUTS:
        print(f"regs: wrote {o.path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
