# SPDX-License-Identifier: Apache-2.0
"""tb/harness/sv_params.py: the integer constants the Python reads from the RTL packages.

Every constant the drivers and tests ask for is found (with the value the package's own text
gives, where that is a plain literal); expressions (other constants, imported packages,
``pkg::NAME``, ``$clog2``, sized literals, several lines, comments) evaluate as SystemVerilog
does; a missing name or package fails with a message that names it and the file.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from tb.harness import sv_params

#: (package, constant) pairs the Python reads (tb/harness/traverse_words.py, pipeline_words.py,
#: dm_pipeline.py, scripts/ray_steps.py, tb/height_cache, tb/tex_addr, tb/mip_level, tb/f24_div).
#: shade_pkg's SHADE_LAT is a constant function of the float units' latencies (its schedule),
#: which tb/shade_unit mirrors in Python rather than reading it here.
USED = [("traverse_pkg", n) for n in ("MAX_LEVELS", "DIM_W", "ITER_W", "ADDR_W", "LOOKUP_LAT",
                                      "LOOP_DEPTH", "SETUP_LAT")] + \
       [("pipe_pkg", n) for n in ("TEX_LEVELS", "TEX_DIM_W", "TEX_ADDR_W", "TEX_ADDR_LAT",
                                  "MIP_LAT")] + \
       [("cache_pkg", "LOOKUP_LAT"), ("f24_pkg", "F24_DIV_LAT")]


def _literal(pkg: str, name: str) -> int | None:
    """The constant's value when the package writes it as a plain decimal literal (an
    independent regular expression over the file), else None."""
    path = sv_params.packages()[pkg].path
    m = re.search(rf"localparam\s+int(?:\s+unsigned)?\s+{name}\s*=\s*(\d+)\s*;", path.read_text())
    return int(m.group(1)) if m else None


@pytest.mark.parametrize("pkg,name", USED, ids=[f"{p}::{n}" for p, n in USED])
def test_used_constants_are_found(pkg: str, name: str) -> None:
    got = sv_params.value(pkg, name)
    assert isinstance(got, int) and got > 0
    lit = _literal(pkg, name)
    if lit is not None:
        assert got == lit


def test_expressions_of_the_packages() -> None:
    """Constants defined by expressions over other packages' constants: as their comments say."""
    f24_div = sv_params.value("f24_pkg", "F24_DIV_LAT")
    p_add, p_mul = sv_params.values("pipe_pkg", "F24_ADD_LAT", "F24_MUL_LAT")
    gap = p_add + p_mul + 3 + (6 - (p_add + p_mul + 3) % 4) % 4  # traverse_pkg::setup_gap
    assert sv_params.value("traverse_pkg", "SETUP_LAT") == f24_div + p_mul + 6 + gap
    assert (p_add, p_mul) != (2, 1) or sv_params.value("traverse_pkg", "SETUP_LAT") == f24_div + 13
    assert sv_params.value("traverse_pkg", "SETUP_BUSY_W") == \
        (sv_params.value("traverse_pkg", "SETUP_LAT")).bit_length()
    add, mul, log2, idx = sv_params.values("pipe_pkg", "F24_ADD_LAT", "F24_MUL_LAT",
                                           "F24_LOG2_LAT", "F24_TO_INDEX_LAT")

    def mip_gap(a: int) -> int:
        """Pl's addition to the colour lod's on mip_level's one adder, padded to 1 or 2 mod 4."""
        base = a + log2 + 1
        return base + next(p for p in range(4) if (base + p) % 4 in (1, 2))

    assert sv_params.value("pipe_pkg", "MIP_LAT") == mul + mip_gap(add) + 1 + 2 * add + idx + 1
    assert sv_params.value("pipe_pkg", "VIEW_CALC_LAT") == 1 + mul + 2 * add + f24_div + 1 + mul + 1
    for a, m in ((2, 1), (3, 2)):  # view_calc and mip_level at their ADD_LAT / MUL_LAT
        assert sv_params.call("pipe_pkg", "view_calc_lat", a, m) == \
            1 + m + 2 * a + f24_div + 1 + m + 1
        assert sv_params.call("pipe_pkg", "mip_gap", a) == mip_gap(a)
        assert sv_params.call("pipe_pkg", "mip_lat", a, m) == m + mip_gap(a) + 1 + 2 * a + idx + 1
        # traverse_setup at its ADD_LAT / MUL_LAT: 21 at (2, 1), 26 at (3, 2)
        gap_am = a + m + 3 + (6 - (a + m + 3) % 4) % 4
        assert sv_params.call("traverse_pkg", "setup_gap", a, m) == gap_am
        assert sv_params.call("traverse_pkg", "setup_lat", a, m) == f24_div + m + 6 + gap_am
    assert sv_params.call("traverse_pkg", "setup_lat", 2, 1) == f24_div + 13


def test_the_drivers_use_the_package_values() -> None:
    from tb.harness import dm_pipeline, pipeline_words, traverse_words

    assert traverse_words.LOOKUP_LAT == sv_params.value("traverse_pkg", "LOOKUP_LAT")
    assert traverse_words.LOOP_DEPTH == sv_params.value("traverse_pkg", "LOOP_DEPTH")
    assert traverse_words.SETUP_DEPTH == sv_params.value("traverse_pkg", "SETUP_LAT")
    assert pipeline_words.TEX_LEVELS == sv_params.value("pipe_pkg", "TEX_LEVELS")
    assert dm_pipeline.MAX_MAP_SIDE == 1 << (traverse_words.MAX_LEVELS - 1)


SYNTHETIC = """\
// a_pkg: test input
package a_pkg;
  localparam int unsigned W = 8;     // comment with localparam int X = 99;
  /* localparam int Y = 5; */
  localparam int N = 'd3 + 4'hA      // 3 + 10
                   - 2'b01;          // over several lines: 12
  localparam int unsigned D = (W * N) / 5 % 7 << 1;
  localparam int C = $clog2(W + 1);
  localparam logic [7:0] NOT_INT = 8'hff;
  localparam int SELF = SELF + 1;
  localparam int BAD = W ? 1 : 2;
  function automatic int unsigned lat(int unsigned add_lat, int unsigned mul_lat);
    return 1 + 2 * add_lat + mul_lat + W;
  endfunction
  localparam int unsigned L = lat(2, N - 11);  // 1 + 4 + 1 + 8
endpackage

package b_pkg;
  import a_pkg::*;
  localparam int unsigned M = W + a_pkg::N + 24'h00_0001;
  localparam int UNKNOWN_REF = Q + 1;
  localparam int unsigned L2 = lat(3, 2) + a_pkg::lat(W, 0);  // 17 + 25
  localparam int NO_FUNC = nofunc(1);
endpackage
"""


@pytest.fixture()
def rtl(tmp_path: Path) -> Path:
    (tmp_path / "x").mkdir()
    (tmp_path / "x" / "ab_pkg.sv").write_text(SYNTHETIC)
    return tmp_path


def test_synthetic_expressions(rtl: Path) -> None:
    assert sv_params.value("a_pkg", "W", rtl) == 8
    assert sv_params.value("a_pkg", "N", rtl) == 12
    assert sv_params.value("a_pkg", "D", rtl) == ((8 * 12) // 5 % 7) << 1
    assert sv_params.value("a_pkg", "C", rtl) == 4
    assert sv_params.value("b_pkg", "M", rtl) == 8 + 12 + 1
    assert sv_params.values("a_pkg", "W", "N", rtl=rtl) == (8, 12)
    assert sv_params.value("a_pkg", "L", rtl) == 14
    assert sv_params.value("b_pkg", "L2", rtl) == 17 + 25
    assert sv_params.call("a_pkg", "lat", 3, 2, rtl=rtl) == 17
    with pytest.raises(sv_params.SvParamError, match=r"a_pkg::lat\(\): 2 arguments, called with 1"):
        sv_params.call("a_pkg", "lat", 3, rtl=rtl)


@pytest.mark.parametrize("pkg,name,words", [
    ("a_pkg", "X", ["a_pkg::X", "no 'localparam int X", "ab_pkg.sv"]),         # commented out
    ("a_pkg", "Y", ["a_pkg::Y", "no 'localparam int Y"]),
    ("a_pkg", "NOT_INT", ["a_pkg::NOT_INT", "no 'localparam int NOT_INT"]),
    ("c_pkg", "W", ["no package c_pkg", "a_pkg, b_pkg"]),
    ("a_pkg", "SELF", ["a_pkg::SELF", "itself"]),
    ("a_pkg", "BAD", ["a_pkg::BAD", "not an integer expression"]),
    ("b_pkg", "UNKNOWN_REF", ["b_pkg::UNKNOWN_REF", "Q is not an int constant"]),
    ("b_pkg", "NO_FUNC", ["b_pkg::NO_FUNC", "nofunc is not a function"]),
])
def test_missing_or_bad_names_fail_clearly(rtl: Path, pkg: str, name: str,
                                           words: list[str]) -> None:
    with pytest.raises(sv_params.SvParamError) as e:
        sv_params.value(pkg, name, rtl)
    for w in words:
        assert w in str(e.value), (w, str(e.value))


def test_missing_name_in_the_real_packages() -> None:
    with pytest.raises(sv_params.SvParamError, match=r"traverse_pkg::NO_SUCH_NAME.*traverse_pkg\.sv"):
        sv_params.value("traverse_pkg", "NO_SUCH_NAME")
