# SPDX-License-Identifier: Apache-2.0
"""The synthesis flow's parsing and reports (scripts/flow/synth.py, without running the tools), the
constraints, the FuseSoC core, the waveform helpers (scripts/waves.py, scripts/flow/gen_gtkw.py) and the
one-ray step trace (scripts/ray_steps.py).  Quick: no Yosys, nextpnr or Verilator runs."""
from __future__ import annotations

import argparse
import dataclasses
import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from model import heightmap, scenes, traverse
from model.rays import Rays
from scripts import waves
from scripts.flow import congestion, gen_gtkw, synth

ROOT = Path(__file__).resolve().parents[1]


def run(*args: str, timeout: int = 120) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, cwd=ROOT,
                          timeout=timeout)


# ---- scripts/flow/synth.py ------------------------------------------------------------------------------
def test_ecp5_and_xilinx_counts():
    stat = {"design": {"num_cells_by_type": {
        "LUT4": 100, "CCU2C": 10, "TRELLIS_DPR16X4": 2, "TRELLIS_FF": 50, "MULT18X18D": 3,
        "DP16KD": 4, "PFUMX": 7}}}
    e = synth.ecp5_counts(stat)
    assert (e["lut"], e["ff"], e["dsp"], e["bram"]) == (100 + 20 + 12, 50, 3, 4)
    x = synth.xilinx_counts({"design": {"num_cells_by_type": {
        "LUT1": 1, "LUT6": 5, "FDRE": 7, "FDSE": 1, "DSP48E1": 2, "RAMB18E1": 3,
        "RAMB36E1": 1, "RAM64M": 2, "SRLC32E": 1, "CARRY4": 4}}})
    assert (x["lut"], x["ff"], x["dsp"], x["bram"], x["lutram"]) == (6, 8, 2, 2.5, 9)


def test_placement_overfill():
    log = ("Info: Device utilisation:\nInfo: \t        TRELLIS_COMB:   86525/  83640   103%\n"
           "ERROR: Unable to find legal placement for all cells, design is probably at "
           "utilisation limit.\n")
    assert synth.placement_overfill(log) == ("nextpnr found no legal placement: 86,525 "
                                             "TRELLIS_COMB of 83,640 (103%) after packing")
    assert synth.placement_overfill(log.replace("TRELLIS_COMB", "X")) == \
        "nextpnr found no legal placement"
    assert synth.placement_overfill("ERROR: Max frequency for clock not met\n") is None


def _seg(kind, frm, to, delay, net=None, sources=()):
    s = {"type": kind, "delay": delay, "from": {"cell": frm, "port": "Q", "loc": [1, 1]},
         "to": {"cell": to, "port": "D", "loc": [2, 2]}}
    if net:
        s["net"], s["sources"] = net, list(sources)
    return s


def test_pnr_summary():
    rep = {"fmax": {"clk_i$glb_clk": {"achieved": 72.5, "constraint": 100.0}},
           "utilization": {"TRELLIS_COMB": {"used": 10, "available": 100},
                           "DP16KD": {"used": 0, "available": 208}},
           "critical_paths": [{"from": "posedge clk_i$glb_clk", "to": "posedge clk_i$glb_clk",
                               "path": [
               _seg("clk-to-q", "u_pipe.u_trav.u_unit.u_loop.t_q_TRELLIS_FF_Q",
                    "u_pipe.u_trav.u_unit.u_loop.t_q_TRELLIS_FF_Q", 0.5),
               _seg("routing", "u_pipe.u_trav.u_unit.u_loop.t_q_TRELLIS_FF_Q",
                    "u_pipe.u_trav.u_unit.u_loop.u_dx.x_LUT4_Z", 1.5, "n1",
                    ["rtl/fp/f24_add.sv:49.3-49.20", "/share/lattice/cells_map.v:1.1"]),
               _seg("logic", "u_pipe.u_trav.u_unit.u_loop.u_dx.x_LUT4_Z",
                    "u_pipe.u_trav.u_unit.u_loop.u_dx.x_LUT4_Z", 0.4),
               _seg("setup", "u_pipe.u_trav.u_unit.u_loop.u_dx.y_q[3]_FF",
                    "u_pipe.u_trav.u_unit.u_loop.u_dx.y_q[3]_FF", 0.1)]}]}
    log = ("Info: Critical path report for clock 'clk_i$glb_clk' (posedge -> posedge):\n"
           "Info: curr total\nInfo:  0.5 0.5 Source x\n\nInfo: Max frequency for clock\n")
    r = synth.pnr_summary(rep, log)
    assert r["fmax_mhz"] == 72.5 and r["target_mhz"] == 100.0
    c = r["critical_path"]
    assert c["delay_ns"] == pytest.approx(2.5) and c["routing_ns"] == pytest.approx(1.5)
    assert c["logic_levels"] == 1
    assert c["from_inst"] == "u_pipe.u_trav.u_unit.u_loop"
    assert c["to_inst"] == "u_pipe.u_trav.u_unit.u_loop.u_dx"
    assert c["sources"] == ["rtl/fp/f24_add.sv:49"]
    assert "Source x" in r["critical_path_text"]
    assert set(r["utilization"]) == {"TRELLIS_COMB"}
    with pytest.raises(synth.StepError):
        synth.pnr_summary({"fmax": {}}, "")


def test_router_args():
    # auto: router1 out of context and for the top; router2 (timing-driven rip-up) on request
    assert synth.router_args("auto", True) == ["--router", "router1"]
    assert synth.router_args("auto", False) == ["--router", "router1"]
    assert synth.router_args("router1", False) == ["--router", "router1"]
    assert synth.router_args("router2", True) == ["--router", "router2", "--tmg-ripup"]
    assert synth.router_args("router2", False) == ["--router", "router2", "--tmg-ripup"]
    assert synth.router_text("auto") == "router1"
    # --no-tmg-ripup: router2 alone, router1 unchanged
    assert synth.router_args("router2", False, False) == ["--router", "router2"]
    assert synth.router_args("auto", False, False) == ["--router", "router1"]
    assert synth.router_args("router1", True, False) == ["--router", "router1"]
    assert "with timing" in synth.router_text("router2")
    assert synth.router_text("router2", False) == "router2 without timing-driven rip-up"


def test_top_ecp5_opts(tmp_path: Path):
    # --top-ecp5-opts (default -nowidelut) reaches the tops' synth_ecp5 only (the P&R tops and
    # the system top with its --param variants), after --ecp5-opts
    args = argparse.Namespace(out=tmp_path, ecp5_opts="-abc2", top_ecp5_opts="-nowidelut",
                              abc9_delay=0)
    f = synth.Flow(args, 1)
    blk = {b.name: b for b in synth.BLOCKS}
    sys0 = dataclasses.replace(blk[synth.SYSTEM_TOP], name=synth.SYSTEM_TOP + "_PYR_BUILD0")
    for top in (blk[synth.TOP], blk[synth.TOP2], blk[synth.SYSTEM_TOP], sys0):
        assert f.ecp5_opts(top) == " -abc2 -nowidelut", top.name
    assert f.ecp5_opts(blk["f24_add"]) == " -abc2" and f.ecp5_key(blk["f24_add"]) == "-abc2"
    assert f.ecp5_opts() == " -abc2"
    args.ecp5_opts, args.top_ecp5_opts = "", ""
    assert f.ecp5_opts(blk[synth.TOP]) == "" and f.ecp5_key(blk[synth.TOP]) == ""


def test_heatmap_args():
    assert synth.heatmap_args(True, "router2", False, "out/heatmap/top") == [
        "--router2-heatmap", "out/heatmap/top"]
    assert synth.heatmap_args(True, "auto", False, "p") == []        # auto is router1
    assert synth.heatmap_args(False, "router2", False, "p") == []    # not asked for
    assert synth.heatmap_args(True, "router2", True, "p") == []      # a block out of context
    assert synth.heatmap_args(True, "router1", False, "p") == []     # router1: no heatmaps


def test_placer_args():
    # only the placer and the heap placer's tuning options, each with its value; anything else
    # is an error
    assert synth.placer_args("") == []
    assert synth.placer_args("--placer-heap-timingweight 20 --placer-heap-critexp 4") == [
        "--placer-heap-timingweight", "20", "--placer-heap-critexp", "4"]
    assert synth.placer_args("--placer-heap-no-ctrl-set") == ["--placer-heap-no-ctrl-set"]
    assert synth.placer_args("--placer static") == ["--placer", "static"]
    with pytest.raises(ValueError, match="is not one of heap, static"):
        synth.placer_args("--placer sa")
    with pytest.raises(ValueError, match="not one of"):
        synth.placer_args("--router router2")
    with pytest.raises(ValueError, match="needs a value"):
        synth.placer_args("--placer-heap-alpha")


def test_float_units_inventory(tmp_path):
    """float_units counts the units below every instance of each block from Yosys's statistics
    of the kept hierarchy: sub-blocks included, multiplicities multiplied, units inside units
    counted; the paper's rows and report.md's tables follow."""
    mods = {
        "\\top": {"num_cells_by_type": {"$dff": 4, "dm_pipeline$top.u_pipe": 1}},
        "\\dm_pipeline$top.u_pipe": {"num_cells_by_type": {
            "$add": 3, "view_calc$top.u_pipe.u_view": 1, "traverse_unit$top.u_pipe.u_trav": 1,
            "f24_to_index$top.u_pipe.u_glue": 1}},
        "\\view_calc$top.u_pipe.u_view": {"num_cells_by_type": {
            "f24_mul$top.u_pipe.u_view.u_du": 3, "f24_div$top.u_pipe.u_view.u_k": 1}},
        "\\f24_mul$top.u_pipe.u_view.u_du": {"num_cells_by_type": {"$mul": 1}},
        "\\f24_div$top.u_pipe.u_view.u_k": {"num_cells_by_type": {
            "f24_mul$top.u_pipe.u_view.u_k.u_m": 1}},          # a unit inside a unit
        "\\f24_mul$top.u_pipe.u_view.u_k.u_m": {"num_cells_by_type": {}},
        "\\traverse_unit$top.u_pipe.u_trav": {"num_cells_by_type": {
            "traverse_loop$top.u_pipe.u_trav.u_loop": 2,
            "traverse_setup$top.u_pipe.u_trav.u_setup": 1}},
        "\\traverse_loop$top.u_pipe.u_trav.u_loop": {"num_cells_by_type": {
            "f24_add$top.u_pipe.u_trav.u_loop.u_dx": 2,
            "f24_one_minus$top.u_pipe.u_trav.u_loop.u_p": 1}},
        "\\f24_add$top.u_pipe.u_trav.u_loop.u_dx": {"num_cells_by_type": {}},
        "\\f24_one_minus$top.u_pipe.u_trav.u_loop.u_p": {"num_cells_by_type": {}},
        "\\traverse_setup$top.u_pipe.u_trav.u_setup": {"num_cells_by_type": {
            "f24_cmp$top.u_pipe.u_trav.u_setup.u_c": 1}},
        "\\f24_cmp$top.u_pipe.u_trav.u_setup.u_c": {"num_cells_by_type": {}},
        "\\f24_to_index$top.u_pipe.u_glue": {"num_cells_by_type": {}},
    }
    fu = synth.float_units({"modules": mods}, "top")
    assert fu["units"] == synth.FLOAT_UNITS and set(fu["blocks"]) == {
        "dm_pipeline", "view_calc", "traverse_unit", "traverse_loop", "traverse_setup"}
    nz = lambda row: {k: v for k, v in row.items() if v}  # noqa: E731
    assert nz(fu["blocks"]["view_calc"]) == {"instances": 1, "f24_mul": 4, "f24_div": 1}
    assert nz(fu["blocks"]["traverse_loop"]) == {"instances": 2, "f24_add": 4,
                                                 "f24_one_minus": 2}
    assert nz(fu["blocks"]["traverse_setup"]) == {"instances": 1, "f24_cmp": 1}
    assert nz(fu["blocks"]["traverse_unit"]) == {"instances": 1, "f24_add": 4,
                                                 "f24_one_minus": 2, "f24_cmp": 1}
    assert nz(fu["blocks"]["dm_pipeline"]) == {"instances": 1, "f24_add": 4, "f24_one_minus": 2,
                                               "f24_cmp": 1, "f24_mul": 4, "f24_div": 1,
                                               "f24_to_index": 1}
    assert nz(fu["paper_rows"]["View calc."]) == {"f24_mul": 4, "f24_div": 1}
    assert nz(fu["paper_rows"]["Traverse"]) == {"f24_add": 4, "f24_one_minus": 2, "f24_cmp": 1}
    assert not any(fu["paper_rows"]["Addr. calc."].values())       # no mip_level / tex_addr
    assert synth.ours_vs_paper(fu["blocks"]["dm_pipeline"]) == {
        "add": 6, "mul": 4, "div": 1, "cmp": 1, "sqrt": 0, "rsqrt": 0, "log2": 0, "conv": 1}
    # the same as the top of the counting: the block is its own instance
    assert synth.float_units({"modules": mods}, "dm_pipeline$top.u_pipe")["blocks"][
        "dm_pipeline"] == fu["blocks"]["dm_pipeline"]
    with pytest.raises(synth.StepError):
        synth.float_units({"modules": mods}, "nope")
    # report.md: our blocks' table, then the paper's Table 1 beside ours (its total summed)
    md = "\n".join(synth.float_units_md(fu))
    assert "| `traverse_loop` | 2 | 4 | 2 | 0 | 0 | 0 | 0 | 0 | 0 | 0 | 0 | 0 |" in md
    assert "| Traverse | 6 / 0 / 7 / 5 / 2 / 0 | 6 / 0 / 0 / 1 / 0 / 0 / 0 / 0 |" in md
    assert "| Total | 8 / 2 / 7 / 12 / 4 / 1 | 6 / 4 / 1 / 1 / 0 / 0 / 0 / 1 |" in md
    report = {"date": "2026-01-01T00:00:00", "top": synth.TOP,
              "settings": {"yosys": "Y", "nextpnr": "N", "device_name": "LFE5U-85F", "speed": 8,
                           "package": "CABGA756", "target_mhz": 100.0,
                           "lpf": "constraints/dm_pipeline.lpf", "seed": 1,
                           "rtl": {"commit": "abc1234-dirty"}},
              "blocks": {}, "xilinx": {}, "pnr": {}, "seconds": {}, "float_units": fu}
    synth.write_md(report, tmp_path / "r.md")
    text = (tmp_path / "r.md").read_text()
    assert md in text and "RTL of abc1234-dirty" in text


def test_top_record_and_merge():
    """A routed top's entry of report.json's `tops`, and the merge that keeps one per name."""
    settings = {"seed": 3, "router": "auto", "device_name": "LFE5U-85F",
                "rtl": {"commit": synth.rtl_commit("abc1234", [" M rtl/pipe/x.sv"])}}
    counts = {"lut": 10, "ff": 20, "dsp": 3, "bram": 4, "cells": {}}
    t = synth.top_record(synth.TOP, counts, 57.25, settings, 1)
    assert t == {"name": synth.TOP, "rings": 1, "lut": 10, "ff": 20, "dsp": 3, "bram": 4,
                 "fmax_mhz": 57.25, "seed": 3, "router": "router1", "device": "LFE5U-85F",
                 "rtl_commit": "abc1234-dirty"}
    assert tuple(t) == synth.TOP_FIELDS
    assert synth.rtl_commit("abc1234", []) == "abc1234"
    old = [{"name": "a", "fmax_mhz": 1.0}, {"name": synth.TOP, "fmax_mhz": 2.0}, "junk"]
    assert synth.merge_tops(old, [t]) == [{"name": "a", "fmax_mhz": 1.0}, t]
    assert synth.merge_tops([], [t]) == [t]
    assert synth.merge_tops([{"name": "a"}], [t]) == [{"name": "a"}, t]


def test_synth_record(tmp_path):
    """--record copies report.json's routed tops into the committed results, replacing the entry
    of the same name and keeping the others; make render's clock then reads the new entry."""
    from tb.harness import dm_pipeline as dm

    out, results = tmp_path / "out", tmp_path / "results" / "synth-ecp5.json"
    out.mkdir()
    settings = {"seed": 2, "router": "auto", "device_name": "LFE5U-85F",
                "rtl": {"commit": "1234abc"}}
    entry = synth.top_record(synth.TOP, {"lut": 1, "ff": 2, "dsp": 3, "bram": 4}, 61.5,
                             settings, 1)
    (out / "report.json").write_text(json.dumps({"top": synth.TOP, "tops": [entry]}))
    results.parent.mkdir()
    other = {"name": "other_top", "rings": 2, "fmax_mhz": 40.0}
    results.write_text(json.dumps({"tops": [
        {"name": synth.TOP, "rings": 1, "fmax_mhz": 58.2, "seed": 1}, other]}))
    p = run("scripts/flow/synth.py", "--record", "--out", str(out), "--results", str(results))
    assert p.returncode == 0 and synth.TOP in p.stdout, p.stdout + p.stderr
    assert json.loads(results.read_text()) == {"tops": [entry, other]}
    mhz, src = dm.routed_clock(results)
    assert mhz == 61.5 and "seed 2" in src and "RTL of 1234abc" in src
    # nothing to record, a broken entry, no report: one line, exit 2, the results untouched
    before = results.read_text()
    for rep in ({"top": synth.TOP}, {"tops": [{"name": synth.TOP}]}, None):
        if rep is None:
            (out / "report.json").unlink()
        else:
            (out / "report.json").write_text(json.dumps(rep))
        p = run("scripts/flow/synth.py", "--record", "--out", str(out), "--results", str(results))
        assert p.returncode == 2 and len(p.stdout.splitlines()) == 1, p.stdout
        assert results.read_text() == before


def test_system_top_record(tmp_path):
    """The system top, routed out of context, is recorded as a top marked `out_of_context`, from a
    report's `tops` or, for a report without it, from its block and place-and-route entries."""
    settings = {"seed": 1, "router": "auto", "device_name": "LFE5U-85F", "rtl": {"commit": "c0ffee1"}}
    counts = {"lut": 70000, "ff": 36000, "dsp": 46, "bram": 150}
    t = synth.top_record(synth.SYSTEM_TOP, counts, 55.5, settings, 1, ooc=True)
    assert t["out_of_context"] is True and t["router"] == synth.resolved_router("auto", True)
    report = {"blocks": {synth.SYSTEM_TOP: counts},
              "pnr": {synth.SYSTEM_TOP: {"fmax_mhz": 55.5, "out_of_context": True}},
              "settings": settings}
    assert synth.system_top_records(report) == [t]
    assert synth.system_top_records({"blocks": {}, "pnr": {}, "settings": settings}) == []
    out, results = tmp_path / "out", tmp_path / "synth-ecp5.json"
    out.mkdir()
    (out / "report.json").write_text(json.dumps(report))
    results.write_text(json.dumps({"tops": [{"name": synth.TOP, "rings": 1, "fmax_mhz": 57.3}]}))
    assert synth.record(out / "report.json", results) == [synth.SYSTEM_TOP]
    assert json.loads(results.read_text())["tops"] == [
        {"name": synth.TOP, "rings": 1, "fmax_mhz": 57.3}, t]


def test_system_top_variant_record(tmp_path):
    """A `--param` variant of the system top (e.g. without the pyramid builder) is recorded under
    its own key with the parameters it overrides, beside the default build's entry."""
    settings = {"seed": 1, "router": "auto", "device_name": "LFE5U-85F", "rtl": {"commit": "c0ffee1"}}
    name = f"{synth.SYSTEM_TOP}_PYR_BUILD0"
    counts = {"lut": 56000, "ff": 40000, "dsp": 44, "bram": 140, "params": {"PYR_BUILD": 0}}
    report = {"blocks": {name: counts, "tex_cache": {"lut": 1, "ff": 1, "dsp": 0, "bram": 1}},
              "pnr": {name: {"fmax_mhz": 60.5}, "tex_cache": {"fmax_mhz": 100.0}},
              "settings": settings}
    [t] = synth.system_top_records(report)
    assert t["name"] == name and t["params"] == {"PYR_BUILD": 0} and t["out_of_context"] is True
    assert t["lut"] == 56000 and t["fmax_mhz"] == 60.5
    out, results = tmp_path / "out", tmp_path / "synth-ecp5.json"
    out.mkdir()
    (out / "report.json").write_text(json.dumps(report))
    sys_t = {"name": synth.SYSTEM_TOP, "rings": 1, "fmax_mhz": 50.0}
    results.write_text(json.dumps({"tops": [sys_t]}))
    assert synth.record(out / "report.json", results) == [name]
    assert json.loads(results.read_text())["tops"] == [sys_t, t]


def test_committed_results_have_top_fields():
    """docs/results/synth-ecp5.json holds one entry per routed top in the shape --record writes."""
    doc = json.loads(synth.RESULTS.read_text())
    names = [t["name"] for t in doc["tops"]]
    assert len(names) == len(set(names)) and synth.TOP in names
    for t in doc["tops"]:
        assert set(synth.TOP_FIELDS) <= set(t) and t["fmax_mhz"] > 0


def test_ooc_wrapper_text():
    ports = synth.parse_portlist("module x\ninput [0:0] clk_i\ninput [23:0] a_i\n"
                                 "input [0:0] en_i\noutput [23:0] y_o\n")
    assert ports == [("input", 1, "clk_i"), ("input", 24, "a_i"), ("input", 1, "en_i"),
                     ("output", 24, "y_o")]
    b = synth.Block("blk", "f24_mul", {"TAG_W": 7})
    text = synth.ooc_wrapper_text(b, ports)
    assert "module ooc_blk" in text and "f24_mul #(.TAG_W(7)) u_block" in text
    assert ".a_i(in_q[23:0])" in text and ".en_i(in_q[24:24])" in text
    assert ".y_o(out_d[23:0])" in text and "input  logic [24:0] in_i" in text
    with pytest.raises(synth.StepError):
        synth.ooc_wrapper_text(b, [("input", 8, "a_i")])


def test_report_markdown(tmp_path):
    report = {
        "date": "2026-01-01T00:00:00", "top": synth.TOP,
        "settings": {"yosys": "Yosys 0.70", "nextpnr": "nextpnr-0.11", "device_name": "LFE5U-85F",
                     "speed": 8, "package": "CABGA756", "target_mhz": 100.0,
                     "lpf": "constraints/dm_pipeline.lpf", "seed": 1},
        "blocks": {"f24_add": {"lut": 10, "ff": 5, "dsp": 0, "bram": 0, "what": "add",
                               "fmax_mhz": 90.0}},
        "xilinx": {"f24_add": {"lut": 7, "lutram": 0, "ff": 5, "dsp": 0, "bram": 0}},
        "pnr": {}, "seconds": {"synth_ecp5 f24_add": 1.5},
    }
    synth.write_md(report, tmp_path / "r.md")
    md = (tmp_path / "r.md").read_text()
    assert "| `f24_add` | add | 10 | 5 | 0 | 0 | 90 | 7 |" in md
    assert "synth_ecp5 f24_add | 1.5" in md
    assert "counts from `synth_ecp5`," in md
    report["settings"]["ecp5_opts"] = "-nowidelut"   # --ecp5-opts is named in the report
    synth.write_md(report, tmp_path / "r.md")
    assert "counts from `synth_ecp5 -nowidelut`," in (tmp_path / "r.md").read_text()
    report["settings"]["abc9_delay_ps"] = 6000       # so is --abc9-delay
    synth.write_md(report, tmp_path / "r.md")
    assert ("counts from `synth_ecp5 -nowidelut` with abc9 delay target 6000 ps,"
            in (tmp_path / "r.md").read_text())
    report["settings"]["ecp5_opts"] = ""              # --top-ecp5-opts: the top's own options
    report["settings"]["abc9_delay_ps"] = 0
    report["settings"]["top_ecp5_opts"] = "-nowidelut"
    synth.write_md(report, tmp_path / "r.md")
    assert "counts from `synth_ecp5` (the top with -nowidelut)," in (tmp_path / "r.md").read_text()


def test_synth_bad_arguments():
    p = run("scripts/flow/synth.py", "--blocks", "nope")
    assert p.returncode == 2 and "unknown block" in p.stdout and len(p.stdout.splitlines()) == 1
    p = run("scripts/flow/synth.py", "--out", "/tmp/elsewhere")
    assert p.returncode == 2 and "inside the repository" in p.stdout
    p = run("scripts/flow/synth.py", "--blocks", "f24_add", "--ecp5-opts=-nowidelut; tee x")
    assert p.returncode == 2 and "--ecp5-opts" in p.stdout and len(p.stdout.splitlines()) == 1
    p = run("scripts/flow/synth.py", "--blocks", "f24_add", "--top-ecp5-opts=-nowidelut; tee x")
    assert p.returncode == 2 and "--top-ecp5-opts" in p.stdout and len(p.stdout.splitlines()) == 1
    p = run("scripts/flow/synth.py", "--blocks", "f24_add", "--abc9-delay", "-5")
    assert p.returncode == 2 and "--abc9-delay" in p.stdout and len(p.stdout.splitlines()) == 1
    p = run("scripts/flow/synth.py", "--breakdown", "--blocks", "view_calc")
    assert p.returncode == 2 and "not an FPGA top" in p.stdout and len(p.stdout.splitlines()) == 1


def test_breakdown_counts():
    """breakdown_counts sums each kept block's instances (a block's own cells, LUT4 as nextpnr
    counts them), puts every other module into the rest, and takes the total from the design;
    report.md's table lists the blocks by LUT4 with their share of the total."""
    cells = lambda **k: {"num_cells_by_type": k}  # noqa: E731
    stat = {
        "modules": {
            "\\top": cells(LUT4=10, TRELLIS_FF=7, CCU2C=1),
            "\\height_cache$top.u_pipe.g_ring[0].u_cache": cells(LUT4=20, DP16KD=3),
            "\\height_cache$top.u_pipe.g_ring[1].u_cache": cells(LUT4=22, DP16KD=3),
            "\\tex_cache$top.u_pipe.u_tc": cells(LUT4=5, TRELLIS_DPR16X4=2, TRELLIS_FF=4),
            "\\traverse_fifo$top.u_pipe.u_f": cells(LUT4=3),  # not a kept block: the rest
        },
        "design": {"num_cells_by_type": {"LUT4": 60, "CCU2C": 1, "TRELLIS_DPR16X4": 2,
                                         "TRELLIS_FF": 11, "DP16KD": 6}},
    }
    bd = synth.breakdown_counts(stat, ("height_cache", "tex_cache", "shade_unit"))
    assert bd["blocks"]["height_cache"] == {"lut": 42, "ff": 0, "dsp": 0, "bram": 6,
                                            "instances": 2}
    assert bd["blocks"]["tex_cache"] == {"lut": 5 + 12, "ff": 4, "dsp": 0, "bram": 0,
                                         "instances": 1}
    assert bd["blocks"]["shade_unit"]["instances"] == 0
    assert bd["rest"] == {"lut": 10 + 2 + 3, "ff": 7, "dsp": 0, "bram": 0}
    assert bd["total"] == {"lut": 60 + 2 + 12, "ff": 11, "dsp": 0, "bram": 6}
    assert (sum(r["lut"] for r in bd["blocks"].values()) + bd["rest"]["lut"]
            == bd["total"]["lut"])
    md = synth.breakdown_md(bd | {"top": "top"})
    rows = [r for r in md if r.startswith("| `")]
    assert rows[0].startswith("| `height_cache` | 2 | 42 | 56.8 |"), rows
    assert md[-2].startswith("| total | | 74 | 100.0 | 11 |")


def test_synth_param_overrides(tmp_path):
    """--param BLOCK:NAME=VALUE: the block under its own key with the parameter set."""
    assert synth.parse_param("f24_add:LAT=3") == ("f24_add", "LAT", 3)
    for bad in ("f24_add:LAT", "f24_add=3", "f24_add:LAT=x", ":LAT=3"):
        with pytest.raises(ValueError):
            synth.parse_param(bad)
    div = next(b for b in synth.BLOCKS if b.name == "f24_div")
    v = synth.with_params(div, {"LAT": 5})
    assert (v.name, v.module, v.params) == ("f24_div_LAT5", "f24_div", {"LAT": 5})
    assert synth.with_params(div, {}) is div
    flow = synth.Flow.__new__(synth.Flow)  # read_cmd needs only the file list
    flow.files = ["rtl/fp/f24_div.sv"]
    assert flow.read_cmd(v).endswith("--top f24_div -G LAT=5")
    # Both keys in the report's tables, the design's block first.
    report = {
        "date": "2026-01-01T00:00:00", "top": synth.TOP,
        "settings": {"yosys": "Y", "nextpnr": "N", "device_name": "LFE5U-85F", "speed": 8,
                     "package": "CABGA756", "target_mhz": 100.0,
                     "lpf": "constraints/dm_pipeline.lpf", "seed": 1},
        "blocks": {n: {"lut": 1, "ff": 1, "dsp": 0, "bram": 0, "what": n}
                   for n in ("f24_add_LAT3", "f24_add")},
        "xilinx": {}, "pnr": {}, "seconds": {},
    }
    synth.write_md(report, tmp_path / "r.md")
    md = (tmp_path / "r.md").read_text()
    assert md.index("| `f24_add` |") < md.index("| `f24_add_LAT3` |")
    for args, msg in ((["--param", "f24_add:LAT"], "BLOCK:NAME=VALUE"),
                      (["--param", "nope:LAT=3"], "unknown block")):
        p = run("scripts/flow/synth.py", *args)
        assert p.returncode == 2 and msg in p.stdout and len(p.stdout.splitlines()) == 1


def test_blocks_are_rtl_modules():
    from tb.common.runner import rtl_index
    index = rtl_index()
    for b in synth.BLOCKS:
        assert b.module in index, b.module


def test_div_block_is_the_design_divider():
    """The f24_div block is synthesised with the latency the design instantiates."""
    pkg = (ROOT / "rtl" / "fp" / "f24_pkg.sv").read_text()
    m = re.search(r"localparam\s+int\s+unsigned\s+F24_DIV_LAT\s*=\s*(\d+)\s*;", pkg)
    assert m
    (div,) = [b for b in synth.BLOCKS if b.name == "f24_div"]
    assert div.params == {"LAT": int(m.group(1))}
    assert f"({m.group(1)} clocks)" in div.what


def test_add_mul_blocks_are_the_design_units():
    """The f24_add and f24_mul blocks are synthesised at the depths the blocks instantiate
    (pipe_pkg::F24_ADD_LAT, F24_MUL_LAT)."""
    from tb.harness import sv_params
    for name, const in (("f24_add", "F24_ADD_LAT"), ("f24_mul", "F24_MUL_LAT")):
        lat = sv_params.value("pipe_pkg", const)
        (b,) = [b for b in synth.BLOCKS if b.name == name]
        assert b.params == {"LAT": lat} and f"({lat} clocks)" in b.what, (name, b)


# ---- constraints ---------------------------------------------------------------------------------
def test_constraints():
    assert synth.read_target(ROOT / "constraints" / "dm_pipeline.lpf") == 100.0
    xdc = (ROOT / "constraints" / "dm_pipeline.xdc").read_text()
    sdc = (ROOT / "constraints" / "dm_pipeline.sdc").read_text()
    for text in (xdc, sdc):
        assert re.search(r"create_clock .*-period 10\.000 .*clk_i", text)


# ---- the FuseSoC core ----------------------------------------------------------------------------
def core_filesets(text: str) -> dict[str, list[str]]:
    """The files of each fileset of a CAPI2 core (the subset of YAML the core uses)."""
    sets: dict[str, list[str]] = {}
    section, cur = None, None
    for ln in text.splitlines():
        if not ln.strip() or ln.lstrip().startswith("#"):
            continue
        if not ln.startswith(" "):
            section, cur = ln.split(":")[0], None
        elif section == "filesets" and re.match(r"^  \w+:\s*$", ln):
            cur = ln.strip()[:-1]
            sets[cur] = []
        elif section == "filesets" and cur and re.match(r"^\s+- ", ln):
            sets[cur].append(re.sub(r":\s*\{.*\}$", "", ln.strip()[2:]).strip())
    return sets


def test_fusesoc_core_lists_every_rtl_file():
    text = (ROOT / "pyramidal_idm.core").read_text()
    assert text.startswith("CAPI=2:")
    sets = core_filesets(text)
    files = [f for fs in sets.values() for f in fs]
    for f in files:
        assert (ROOT / f).is_file(), f"pyramidal_idm.core lists a missing file: {f}"
    rtl = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "rtl").rglob("*.sv"))
    missing = [f for f in rtl if f not in files]
    assert not missing, f"RTL files not in pyramidal_idm.core (add them to a fileset): {missing}"
    # packages first: every *_pkg.sv comes before the first module file
    order = [f for f in files if f.endswith(".sv")]
    first_mod = min(i for i, f in enumerate(order) if not f.endswith("_pkg.sv"))
    assert all(i < first_mod for i, f in enumerate(order) if f.endswith("_pkg.sv"))
    # every fileset a target names exists
    for m in re.finditer(r"filesets:\s*\[([^\]]*)\]", text, re.S):
        for name in re.split(r"[,\s]+", m.group(1).strip()):
            assert name in sets, name
    for target in ("lint", "sim", "synth"):
        assert re.search(rf"^  {target}:", text, re.M)


def test_fusesoc_validates_core_when_installed(tmp_path):
    fusesoc = None
    for cand in ("fusesoc",):
        import shutil
        fusesoc = shutil.which(cand)
    if fusesoc is None:
        pytest.skip("fusesoc not installed (the core was checked with FuseSoC 2.4.7)")
    p = subprocess.run([fusesoc, "--cores-root", str(ROOT), "core", "show", "pyramidal_idm"],
                       capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert p.returncode == 0, p.stderr


# ---- waveforms -----------------------------------------------------------------------------------
def test_waves_resolve():
    assert waves.resolve("traverse_system")[0] == "tb/traverse_system"
    assert waves.resolve("tb/traverse_system")[0] == "tb/traverse_system"
    node = "tb/traverse_system/test_traverse_system.py::test_traverse_system"
    assert waves.resolve(node)[0] == node
    with pytest.raises(ValueError, match="testbenches"):
        waves.resolve("no_such_unit")


def test_waves_gtkw_for():
    for build, gtkw in (("traverse_system-SETS64-WAYS2-waves", "traverse_system.gtkw"),
                        ("dm_pipeline-SLOTS32-waves", "dm_pipeline.gtkw"),
                        ("traverse_system-waves", "traverse_system.gtkw")):
        assert waves.gtkw_for(Path("/x") / build / "dump.fst").name == gtkw
    assert waves.gtkw_for(Path("/x/f24_add-waves/dump.fst")) is None


def test_waves_bad_test():
    p = run("scripts/waves.py", "")
    assert p.returncode == 2 and "TEST=" in p.stderr
    p = run("scripts/waves.py", "no_such_unit")
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1


def test_gtkw_files_current():
    assert gen_gtkw.main(["--check-only"]) == 0


def test_gtkw_signals_exist_in_rtl():
    """Every signal name a save file shows is in the RTL, and a signal under an instance in the
    file of that instance's module (a rename shows up here even when another module happens to
    use the old name; the hierarchy itself is checked against real FSTs with gen_gtkw.py --fst)."""
    files = {p.stem: p.read_text() for p in (ROOT / "rtl").rglob("*.sv")}
    src = " ".join(files.values())
    words = set(re.findall(r"\b\w+\b", src))
    # instance name -> the words of its modules' files (module_name #(...) u_x ( ...); an
    # instance name used in several modules gets all of their words)
    inst: dict[str, set[str]] = {}
    for m in re.finditer(r"^\s*(\w+)\s*(?:#\s*\((?:[^;]*?)\))?\s*(u_\w+)\s*\(", src, re.M):
        if m.group(1) in files:
            inst.setdefault(m.group(2), set()).update(re.findall(r"\b\w+\b", files[m.group(1)]))
    for t in gen_gtkw.TARGETS:
        for _, sigs in gen_gtkw.groups_for(t):
            for path, _, _ in sigs:
                scope = words
                for part in path.split(".")[1:]:
                    name = re.sub(r"\[\d+\]$", "", part)
                    assert name in scope, f"{t}: {path}: {name} is not in its module's RTL"
                    # an instance's signals are looked up in its module; below a signal (struct
                    # members, array elements) anywhere
                    scope = inst.get(name, words)


# ---- scripts/ray_steps.py ------------------------------------------------------------------------
def test_ray_steps_matches_trace(tmp_path):
    out = tmp_path / "steps.json"
    p = run("scripts/ray_steps.py", "--scene", "rocks", "--map-size", "32", "--ray", "5.3",
            "20.7", "3.1", "-2.2", "--method", "park", "--json", str(out))
    assert p.returncode == 0, p.stderr
    d = json.loads(out.read_text())
    pyr = heightmap.build(scenes.load_scene("rocks", 32).heights)
    rays = Rays.from_array(np.array([[5.3, 20.7, 3.1, -2.2]]))
    rec: list = []
    res = traverse.trace(pyr, rays, "park", "f24", record=rec)
    assert len(d["steps"]) == len(rec) == int(res.iterations[0]) > 0
    img = pyr.memory_image()
    for s, r in zip(d["steps"], rec):
        assert (s["level"], s["cx"], s["cy"], s["action"]) == (r["level"], r["cx"], r["cy"],
                                                               r["action"])
        assert img[s["address"] - d["base"]] == s["code"]   # the byte the RTL reads
    assert d["model"]["hit"] == bool(res.hit[0]) and d["model"]["t"] == float(res.t[0])
    # the printed table: one line per iteration, f24 patterns shown
    lines = [ln for ln in p.stdout.splitlines() if re.match(r"^\s+\d+\s+\d+\s", ln)]
    assert len(lines) == len(rec)
    assert re.search(r"as f24 .*: [0-9a-f]{6} [0-9a-f]{6} [0-9a-f]{6} [0-9a-f]{6}", p.stdout)


def test_ray_steps_pixel_and_rays_file(tmp_path):
    p = run("scripts/ray_steps.py", "--scene", "bump", "--map-size", "32", "--pixel", "32", "32",
            "--image", "64", "--angle", "front", "--engine", "f64")
    assert p.returncode == 0, p.stderr
    assert "pixel (32, 32)" in p.stdout and "model:" in p.stdout
    np.save(tmp_path / "r.npy", np.array([[1.5, 2.5, 0.3, 0.1], [np.nan, 0, 1, 1]]))
    p = run("scripts/ray_steps.py", "--scene", "bump", "--map-size", "32", "--rays",
            str(tmp_path / "r.npy"), "--index", "1")
    assert p.returncode == 0 and "invalid" in p.stdout


@pytest.mark.parametrize("args,msg", [
    (["--ray", "1", "1", "1", "1", "--method", "nope"], "unknown method"),
    (["--rays", "x.npy"], "--index"),
    (["--pixel", "0", "0", "--image", "64"], "not covered"),
    ([], "exactly one of"),
    (["--ray", "1", "1", "1", "1", "--engine", "f64", "--rtl"], "f24"),
    (["--ray", "1", "1", "1", "1", "--waves", "w.vcd"], ".fst"),
])
def test_ray_steps_errors(args, msg):
    p = run("scripts/ray_steps.py", "--scene", "bump", "--map-size", "16", *args)
    assert p.returncode == 2, p.stdout + p.stderr
    assert msg in p.stderr and len(p.stderr.strip().splitlines()) == 1


def test_ray_steps_compare_lookups():
    from scripts import ray_steps
    steps_ = [{"iteration": 1, "address": 0x100, "code": 5},
              {"iteration": 2, "address": 0x140, "code": 7}]
    looks = [{"clock": 10, "time": 20, "address": 0x100, "hit": False, "err": False, "code": 0},
             {"clock": 28, "time": 56, "address": 0x100, "hit": True, "err": False, "code": 5},
             {"clock": 46, "time": 92, "address": 0x140, "hit": True, "err": False, "code": 7}]
    assert ray_steps.compare_lookups(steps_, looks) is None
    looks[2]["code"] = 8
    assert "iteration 2" in ray_steps.compare_lookups(steps_, looks)
    assert "only 1" in ray_steps.compare_lookups(steps_, looks[:2])
    assert "reads on" in ray_steps.compare_lookups(steps_[:1], looks[:2] + [looks[1]])


def test_ray_steps_expected_reads():
    """A descent whose locate moved its estimate: the ring reads the estimate once more (the
    redo) before the next iteration, at that iteration's t and count."""
    from scripts import ray_steps
    est = {"level": 1, "cx": 2, "cy": 3, "address": 0x180, "code": 9}
    steps_ = [{"iteration": 1, "level": 2, "cx": 1, "cy": 1, "t": 0.0, "address": 0x100,
               "code": 5, "estimate": est},
              {"iteration": 2, "level": 1, "cx": 3, "cy": 3, "t": 0.25, "address": 0x184,
               "code": 7}]
    reads = ray_steps.expected_reads(steps_)
    assert [r["address"] for r in reads] == [0x100, 0x180, 0x184]
    assert reads[1]["redo"] and reads[1]["iteration"] == 2 and reads[1]["t"] == 0.25
    looks = [{"clock": c, "time": 2 * c, "address": a, "hit": True, "err": False, "code": k}
             for c, a, k in ((10, 0x100, 5), (30, 0x180, 9), (50, 0x184, 7))]
    assert ray_steps.compare_lookups(reads, looks) is None
    assert "the redo before iteration 2" in ray_steps.compare_lookups(reads, looks[:1] + looks[2:])
    # the redo's lookup is the one after the descent's, whatever the cache answers; the
    # iteration's is the next answered one
    looks[1].update(hit=False, code=0)
    looks.insert(2, {"clock": 40, "time": 80, "address": 0x184, "hit": False, "err": False,
                     "code": 0})
    pairs, short = ray_steps.match_reads(reads, looks)
    assert short is None and [lk["clock"] for _, lk in pairs] == [10, 30, 50]
    assert ray_steps.compare_lookups(reads, looks) is None
    states = [{"level": 2, "cx": 1, "cy": 1, "t": 0, "iters": 0},
              {"level": 1, "cx": 2, "cy": 3, "t": 0x3d0000, "iters": 1},
              {"level": 1, "cx": 3, "cy": 3, "t": 0x3d0000, "iters": 1}]
    assert ray_steps.compare_states(reads, states) is None
    states[1]["cx"] = 3  # the RTL skipped the redo's cell
    assert "the redo before iteration 2" in ray_steps.compare_states(reads, states)


def test_congestion_summary(tmp_path, capsys):
    # router2's heatmap files of two iterations; the script reads the last by default
    hd = tmp_path / "heatmap"
    hd.mkdir()
    (hd / "top_congestion_by_net_3.csv").write_text("u_pipe.u_a.x,1\n")
    (hd / "top_congestion_by_net_7.csv").write_text(
        "u_pipe.u_trav.u_cache.g_way[0].u_lines.mem_q.0.0_DOA0[3],60\n"
        "u_pipe.u_trav.u_cache.rs_data_q_DI[0],15\n"
        "u_pipe.u_trav.u_unit.u_loop.n1,20\n"
        "$PACKER_GND_NET,5\n")
    grid = [[0] * 8 for _ in range(8)]
    grid[1][6] = 90   # one hot tile ...
    grid[5][2] = 10   # ... and a cooler one elsewhere
    (hd / "top_congestion_by_coordinate_7.csv").write_text(
        "\n".join(",".join(map(str, r)) + "," for r in grid) + "\n")
    assert congestion.main([str(hd), "--depth", "3"]) == 0
    r = json.loads((hd / "congestion_7.json").read_text())
    assert r["iteration"] == 7 and r["overused_wires_by_net_sum"] == 100
    shares = {b["block"]: b["share"] for b in r["blocks"]}
    assert shares == {"u_pipe.u_trav.u_cache": 0.75, "u_pipe.u_trav.u_unit": 0.2,
                      "(top level) PACKER_GND_NET": 0.05}
    assert r["hottest_sixteenth_share"] == 0.9
    assert "75.0%" in capsys.readouterr().out
    # depth 2 folds the cache and the unit into u_pipe.u_trav; an older iteration on request
    assert congestion.main([str(hd), "--depth", "2", "--iteration", "3",
                            "--json", str(tmp_path / "c.json")]) == 0
    assert json.loads((tmp_path / "c.json").read_text())["blocks"][0]["block"] == "u_pipe.u_a"
    # errors: one line, exit status 2
    assert congestion.main([str(tmp_path / "none")]) == 2
    assert congestion.main([str(tmp_path)]) == 2          # no CSV files there
    assert congestion.main([str(hd), "--iteration", "5"]) == 2
    assert "congestion.py: error:" in capsys.readouterr().err
