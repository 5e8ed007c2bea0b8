# SPDX-License-Identifier: Apache-2.0
"""model.pyramid_bus: the bus bound of a full pyramid rebuild against the model's pyramid."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from model import heightmap, pyramid_bus


@pytest.mark.parametrize("w,h", [(1, 1), (2, 1), (3, 5), (7, 300), (256, 256), (1, 1024),
                                 (1000, 600)])
@pytest.mark.parametrize("bits", [8, 16])
def test_bytes_match_the_model(w: int, h: int, bits: int) -> None:
    """Bytes read = the map's codes; bytes written = levels 1..n of model.heightmap's pyramid."""
    pyr = heightmap.build(np.zeros((h, w), dtype=np.uint16), bits)
    b = pyramid_bus.full_rebuild(w, h, bits, 64)
    assert pyramid_bus.root_level(w, h) == pyr.n
    assert b.bytes_read == w * h * bits // 8
    assert b.bytes_written == sum(lv.size for lv in pyr.levels[1:]) * bits // 8
    assert b.clocks == -(-max(b.bytes_read, b.bytes_written) // 8)


def test_issue_example() -> None:
    """256 x 256 unorm8 on a 64-bit bus: 64 KiB read, 21,845 B written, 8,192 clocks."""
    b = pyramid_bus.full_rebuild(256, 256, 8, 64)
    assert (b.bytes_read, b.bytes_written, b.clocks) == (65536, 21845, 8192)
    assert pyramid_bus.full_rebuild(256, 256, 8, 32).clocks == 16384


def test_cli_errors() -> None:
    for args in (["0", "3"], ["3", "x"], ["4", "4", "--bus-bits", "12"]):
        p = subprocess.run([sys.executable, "-m", "model.pyramid_bus", *args],
                           capture_output=True, text=True)
        assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, (args, p.stderr)
