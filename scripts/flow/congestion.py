#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Which blocks the top's routing congestion belongs to, from router2's heatmaps.

`scripts/flow/synth.py --heatmap` has nextpnr's router2 write, for every routing iteration N,
`<out>/heatmap/top_congestion_by_net_N.csv` (net name, overused wires on it) and
`top_congestion_by_coordinate_N.csv` (a grid of overused wires per tile).  This script sums the
per-net file by instance path (`u_pipe.u_trav.u_cache`, ... down to --depth levels, array
indices folded), prints the shares and, with the coordinate file of the same iteration, how much
of the overuse sits in the hottest sixteenth of the chip.  It writes the numbers as JSON.

    scripts/flow/congestion.py out/synth/heatmap --iteration 12 --depth 3
"""
from __future__ import annotations

import csv
import json
import re
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

from model.cli import Parser


def read_by_net(path: Path) -> dict[str, int]:
    """net name -> overused wires, from a top_congestion_by_net_N.csv file."""
    out: dict[str, int] = {}
    with path.open(newline="") as f:
        for row in csv.reader(f):
            if len(row) >= 2 and row[1].strip().isdigit():
                out[row[0]] = out.get(row[0], 0) + int(row[1])
    return out


def read_grid(path: Path) -> list[list[int]]:
    """The per-tile overuse grid of a top_congestion_by_coordinate_N.csv file."""
    with path.open(newline="") as f:
        return [[int(v) for v in row if v.strip() != ""] for row in csv.reader(f)]


def block_of(net: str, depth: int) -> str:
    """The instance path of a net's name, `depth` levels deep, array indices folded to []."""
    parts = re.sub(r"\[\d+\]", "[]", net).split(".")
    if len(parts) == 1:  # a top-level net: port, constant, wrapper register
        return "(top level) " + parts[0].lstrip("$").split("$")[0]
    return ".".join(parts[:min(depth, len(parts) - 1)])


def by_block(nets: dict[str, int], depth: int) -> Counter[str]:
    c: Counter[str] = Counter()
    for n, v in nets.items():
        c[block_of(n, depth)] += v
    return c


def hottest_share(grid: list[list[int]], parts: int = 4) -> tuple[float, int]:
    """The share of all overuse in the hottest of parts x parts equal regions of the grid, and
    that region's overuse."""
    h = len(grid)
    w = max((len(r) for r in grid), default=0)
    total = sum(map(sum, grid))
    if not total or not w:
        return 0.0, 0
    reg: Counter[tuple[int, int]] = Counter()
    for i, row in enumerate(grid):
        for j, v in enumerate(row):
            reg[(i * parts // h, j * parts // w)] += v
    top = max(reg.values())
    return top / total, top


def latest_iteration(hdir: Path) -> int | None:
    its = [int(m.group(1)) for p in hdir.glob("*congestion_by_net_*.csv")
           if (m := re.search(r"_(\d+)\.csv$", p.name))]
    return max(its) if its else None


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog="congestion.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("heatmap_dir", type=Path, help="the directory of the CSV files "
                    "(out/synth/heatmap after `scripts/flow/synth.py --heatmap`)")
    ap.add_argument("--iteration", type=int, default=None,
                    help="router2 iteration to read (default: the last one written)")
    ap.add_argument("--depth", type=int, default=3, help="instance path levels (default 3)")
    ap.add_argument("--top", type=int, default=15, help="blocks to print (default 15)")
    ap.add_argument("--json", type=Path, default=None,
                    help="write the numbers here (default <heatmap_dir>/congestion_N.json)")
    a = ap.parse_args(argv)

    def fail(msg: str) -> int:
        print(f"congestion.py: error: {msg}", file=sys.stderr)
        return 2

    if not a.heatmap_dir.is_dir():
        return fail(f"{a.heatmap_dir}: no such directory (run scripts/flow/synth.py --heatmap)")
    if a.depth < 1:
        return fail("--depth must be at least 1")
    it = a.iteration if a.iteration is not None else latest_iteration(a.heatmap_dir)
    if it is None:
        return fail(f"{a.heatmap_dir}: no *congestion_by_net_N.csv files")
    nets_f = next(iter(sorted(a.heatmap_dir.glob(f"*congestion_by_net_{it}.csv"))), None)
    if nets_f is None:
        return fail(f"{a.heatmap_dir}: no congestion_by_net file for iteration {it}")
    try:
        nets = read_by_net(nets_f)
    except (OSError, UnicodeDecodeError) as e:
        return fail(f"{nets_f}: {e}")
    total = sum(nets.values())
    blocks = by_block(nets, a.depth)
    result: dict = {"iteration": it, "file": str(nets_f), "overused_wires_by_net_sum": total,
                    "depth": a.depth,
                    "blocks": [{"block": b, "overuse": v,
                                "share": round(v / total, 4) if total else 0.0}
                               for b, v in blocks.most_common()]}
    lines = [f"congestion: iteration {it}: {total} overused wire-net pairs over {len(nets)} "
             f"nets ({nets_f.name})"]
    lines += [f"  {100.0 * v / total if total else 0.0:5.1f}%  {v:7d}  {b}"
              for b, v in blocks.most_common(a.top)]
    coord = next(iter(sorted(a.heatmap_dir.glob(f"*congestion_by_coordinate_{it}.csv"))), None)
    if coord is not None:
        try:
            share, top = hottest_share(read_grid(coord))
        except (OSError, UnicodeDecodeError, ValueError) as e:
            return fail(f"{coord}: not a router2 coordinate heatmap ({e})")
        result["hottest_sixteenth_share"] = round(share, 4)
        lines.append(f"congestion: the hottest sixteenth of the chip holds {100.0 * share:.0f}% "
                     f"of the overuse ({top} wires; {coord.name})")
    out = a.json or a.heatmap_dir / f"congestion_{it}.json"
    try:
        out.write_text(json.dumps(result, indent=1) + "\n")
    except OSError as e:
        return fail(f"cannot write {out}: {e}")
    # nothing is printed before every check has passed: an error is the only line
    print("\n".join(lines + [f"congestion: wrote {out}"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
