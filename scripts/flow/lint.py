#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Lint every RTL module with Verilator (--lint-only -Wall), each as its own top, in parallel.

Prints one line per module with a problem and a summary; exit status 1 on any warning or error.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from model.cli import Parser
from tb.common.runner import is_bound_checker, rtl_files, rtl_index


# The one waiver: an output connected as `.port()` is how this RTL says "not needed here" (lowRISC
# style: unused outputs are named, not left out), so Verilator's PINCONNECTEMPTY would only flag
# the intent.  Leaving a port out entirely still warns (PINMISSING).
WAIVERS = ["-Wno-PINCONNECTEMPTY"]

#: Per-file waivers for generated code (rtl/top/pidm_regs*.sv from PeakRDL), each with its reason.
WAIVER_FILE = ROOT / "scripts" / "flow" / "lint_waivers.vlt"


def lint_one(verilator: str, top: str, files: list[Path]) -> tuple[str, int, str]:
    cmd = ([verilator, "--lint-only", "-Wall", *WAIVERS, "--quiet", "--top-module", top,
            str(WAIVER_FILE)] + [str(f) for f in files])
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    return top, p.returncode, (p.stdout + p.stderr).strip()


def main() -> int:
    ap = Parser(prog="lint.py", description=__doc__)
    ap.add_argument("modules", nargs="*", help="only these modules (default: all under rtl/)")
    args = ap.parse_args()
    verilator = shutil.which("verilator")
    if verilator is None:
        print("lint: verilator not found on PATH (run through make, or set VERILATOR=...)")
        return 2
    index = rtl_index()
    files = rtl_files()
    pkgs = [f for f in files if f.name.endswith("_pkg.sv")]
    others = [f for f in files if f not in pkgs]
    # Bound assertion files (<module>_assert.sv) are linted inside the modules they bind into.
    tops = args.modules or [m for m, f in index.items() if f in others and not is_bound_checker(f)]
    unknown = [m for m in tops if m not in index]
    if unknown:
        print(f"lint: unknown module(s): {', '.join(unknown)}")
        return 2
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as ex:
        results = list(ex.map(lambda m: lint_one(verilator, m, pkgs + others), tops))
    bad = [(m, out) for m, rc, out in results if rc != 0 or "%Warning" in out or "%Error" in out]
    for m, out in bad:
        print(f"lint: {m}: FAILED\n{out}\n")
    print(f"lint: {len(tops)} modules, Verilator --lint-only -Wall, {len(bad)} with findings")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
