#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Check (or add) the SPDX licence line at the top of every source file of the repository.

    python scripts/flow/spdx.py            # list files without the line; exit 1 if any
    python scripts/flow/spdx.py --fix      # add it where it is missing

The line goes first, or second after a ``#!`` line or a FuseSoC ``CAPI=2:`` line.  Files that cannot
carry a comment (JSON, images, the licence text itself) and Markdown are not checked.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from model.cli import Parser

ROOT = Path(__file__).resolve().parents[2]
LICENSE_ID = "Apache-2.0"
TAG = "SPDX-License-Identifier:"

#: comment leader per file suffix (or whole name for suffix-less files)
LEADERS: dict[str, str] = {
    ".sv": "//", ".svh": "//", ".v": "//", ".cpp": "//", ".h": "//", ".c": "//", ".rdl": "//",
    ".py": "#", ".tcl": "#", ".sdc": "#", ".xdc": "#", ".lpf": "#", ".core": "#", ".ini": "#",
    ".toml": "#", ".txt": "#", ".sby": "#", ".yml": "#", ".yaml": "#", ".sh": "#", ".gtkw": "[*]",
    "Makefile": "#", ".gitignore": "#", "run": "#",
}


def leader(path: Path) -> str | None:
    """The comment leader of ``path``, or None when the file is not checked."""
    return LEADERS.get(path.name) or LEADERS.get(path.suffix)


def tracked_files() -> list[Path]:
    """The repository's files (git ls-files, or a walk when git is not there)."""
    try:
        out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True, capture_output=True).stdout
        return [ROOT / p for p in out.decode().split("\0") if p]
    except (OSError, subprocess.CalledProcessError):
        skip = {".git", ".venv", "build", "out"}
        return [p for p in ROOT.rglob("*") if p.is_file() and not skip & set(p.relative_to(ROOT).parts)]


def has_tag(text: str) -> bool:
    """True when one of the first three lines carries the SPDX tag."""
    return any(TAG in line for line in text.splitlines()[:3])


def add_tag(text: str, lead: str) -> str:
    """``text`` with the SPDX line inserted at its top (after a shebang or CAPI line)."""
    line = f"{lead} {TAG} {LICENSE_ID}\n"
    first, sep, rest = text.partition("\n")
    if first.startswith("#!") or first.startswith("CAPI="):
        return first + sep + line + rest
    return line + text


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog="spdx.py", description=__doc__.splitlines()[0])
    ap.add_argument("--fix", action="store_true", help="add the line where it is missing")
    args = ap.parse_args(argv)
    missing = []
    for path in tracked_files():
        lead = leader(path)
        if lead is None or not path.is_file():
            continue
        text = path.read_text(encoding="utf-8")
        if has_tag(text):
            continue
        if args.fix:
            path.write_text(add_tag(text, lead), encoding="utf-8")
        missing.append(path.relative_to(ROOT))
    verb = "added to" if args.fix else "missing in"
    for p in missing:
        print(f"spdx: {verb} {p}")
    print(f"spdx: {len(missing)} file(s) {verb}")
    return 0 if (args.fix or not missing) else 1


if __name__ == "__main__":
    sys.exit(main())
