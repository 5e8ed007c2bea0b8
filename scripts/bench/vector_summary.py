#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Print the vectors checked per unit in the last `make test` (from build/vectors/*.jsonl)."""
from __future__ import annotations

import json
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from model.cli import Parser


def main() -> int:
    ap = Parser(prog="vector_summary.py", description=__doc__)
    ap.add_argument("--dir", type=Path, default=ROOT / "build" / "vectors")
    ap.add_argument("--json", type=Path, help="also write the table as JSON here")
    args = ap.parse_args()
    rows: dict[tuple[str, str], list[int]] = defaultdict(lambda: [0, 0])
    for p in sorted(args.dir.glob("*.jsonl")) if args.dir.is_dir() else []:
        for line in p.read_text().splitlines():
            r = json.loads(line)
            rows[(r["unit"], r["what"])][0] += r["vectors"]
            rows[(r["unit"], r["what"])][1] += r["mismatches"]
    if not rows:
        print("vector summary: no vectors recorded")
        return 0
    w = max(len(u) + len(wh) + 3 for u, wh in rows)
    print(f"{'unit / comparison':<{w}} {'vectors':>12} {'mismatches':>11}")
    for (u, wh), (n, bad) in sorted(rows.items()):
        print(f"{u + ' / ' + wh:<{w}} {n:>12,} {bad:>11}")
    total = sum(v[0] for v in rows.values())
    bad = sum(v[1] for v in rows.values())
    print(f"{'total':<{w}} {total:>12,} {bad:>11}")
    if args.json:
        args.json.write_text(json.dumps([{"unit": u, "what": wh, "vectors": n, "mismatches": b}
                                         for (u, wh), (n, b) in sorted(rows.items())], indent=1))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
