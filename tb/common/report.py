# SPDX-License-Identifier: Apache-2.0
"""Count the vectors each test checked, so `make test` can print how many ran.

Tests call :func:`record`; it appends one JSON line to ``build/vectors/<pid>.jsonl`` (the
directory can be moved with VECTOR_LOG).  ``scripts/bench/vector_summary.py`` adds them up.
"""
from __future__ import annotations

import json
import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def log_dir() -> Path:
    return Path(os.environ.get("VECTOR_LOG", ROOT / "build" / "vectors"))


def record(unit: str, what: str, vectors: int, mismatches: int) -> None:
    """Append one line: which unit / model function, what was compared, how many, how many bad."""
    d = log_dir()
    d.mkdir(parents=True, exist_ok=True)
    with open(d / f"{os.getpid()}.jsonl", "a") as f:
        f.write(json.dumps({"unit": unit, "what": what, "vectors": int(vectors),
                            "mismatches": int(mismatches)}) + "\n")
