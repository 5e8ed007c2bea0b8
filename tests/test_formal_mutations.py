# SPDX-License-Identifier: Apache-2.0
"""The formal proofs can fail: known bugs put into a scratch copy of the RTL make `make formal`'s
driver (scripts/flow/formal.py) fail, with the assertion that caught each one named and a
counterexample trace (VCD) that the waves tooling (pywellen, GTKWave) opens.

The mutations: FIFO full one entry early (traverse_fifo's full_o), the credit check `<=` where
it is `<` (pipe_credit's room_o: one item more than LIMIT), and a FIFO with its head in a
register that refills it from the wrong RAM address (traverse_fifo's hd_q: the words come out
of order, nothing else changes); in circ_queue the pointers wrap one entry late (at DEPTH + 1:
ptr_model), and push lane k writes at tail + k whether the lanes below it push or not (the
entries land out of place: data_order or trk_in_mem, whichever the counterexample shows).  The
FIFO as the pipeline's free list of slot ids writes a word that goes straight into its head
register into the RAM too (the id is there twice: fl_exact, or the RAM count checks first).
In the caches: height_cache keeps an MSHR in MSHR_FILL after its fill instead of freeing it (a
dropped MSHR free: fill_state_once) and allocates an MSHR for a miss to a line an MSHR already
holds (the merge rule dropped: merge_no_alloc or mshr_unique); cache_axi_read keeps a line's
error bit after its last beat (the MSHR's next line is marked bad: r_err_marks, or the
wrapper's inv_slave a clock earlier), with AR_REG drops the AR register's valid before arready
(ar_stable), and does not advance the epoch at a reset (a beat of a read from before the reset
is taken for the current epoch's: stale_ignored, or the wrapper's inv_stale first).  Ray ids:
the traverse ring keeps a retired ray in its slot (its id leaves and stays: id_in_ring), and
traverse_rings takes a result from every ring at a handshake (the other rings' results are
lost: take_one or an id check); view_calc's tag pipeline does not take a fragment that
enters four clocks after another (its tag is dropped: vtag_inside); tex_cache reads the
response's tag from the tag queue's entry behind the head (inv_tq_read, or rsp_tag_order);
dm_pipeline pops the miss FIFO while the output register takes a shaded pixel (the miss is
lost: merge_count, inv_place or merge_leave_once), and sends a normal-map request to the
texture cache with the slot of the colour FIFO's head instead of its pixel's (the pair's
normal map goes to another pixel: inv_pairs, or tf_pairs), and does not count a pixel's slot
out of live_q (the slots in use no longer match it: slot_count, or slots_conserved).  A
further case removes one property from what the front end sees and shows the driver refuses the
run (the guard against properties dropped silently).

Where a mutant's counterexample is longer than make formal's BMC (one step beyond the induction,
which proves the properties at every depth), the copy runs that BMC deeper (MUTANT_BMC_DEPTH).

The scratch copies live under build/formal_mutants/ (inside the repository: YoWASP's tools see
the file system through relative paths).
"""
from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRATCH = ROOT / "build" / "formal_mutants"

# name: (file, original text, mutated text, task, the assertion expected to fail: a regular
# expression)
MUTANTS = {
    "fifo_full_early": (
        "rtl/traverse/traverse_fifo.sv",
        "assign full_o    = (cnt_q == (AW+1)'(DEPTH));",
        "assign full_o    = (cnt_q == (AW+1)'(DEPTH - 1));",
        "traverse_fifo:bmc_d4", "count_flags"),
    "credit_le": (
        "rtl/pipe/pipe_credit.sv",
        "assign room_o  = ({1'b0, cnt_q} + {1'b0, held_i}) < (CW + 1)'(LIMIT);",
        "assign room_o  = ({1'b0, cnt_q} + {1'b0, held_i}) <= (CW + 1)'(LIMIT);",
        "pipe_credit:bmc_l16", "within_limit"),
    "fifo_head_wrong_word": (
        "rtl/traverse/traverse_fifo.sv",
        "if (hd_load) hd_q <= m_any ? mem_q[rp_q] : wr_data_i;",
        "if (hd_load) hd_q <= m_any ? mem_q[rp_q + AW'(1)] : wr_data_i;",
        "traverse_fifo:bmc_d4_reg", "data_order"),
    "queue_wrap_late": (
        "rtl/common/circ_queue.sv",
        "if (q >= DEPTH) q = q - DEPTH;",
        "if (q > DEPTH) q = q - DEPTH;",
        "circ_queue:bmc_peek", "(?:ptr_model|peek_addr)"),
    "queue_lane_place": (
        "rtl/common/circ_queue.sv",
        "if (wr_i[k] && 32'(n) == j) begin",
        "if (wr_i[k] && k == j) begin",
        "circ_queue:bmc_multi", "(?:data_order|trk_in_mem)"),
    "mshr_free_dropped": (
        "rtl/cache/height_cache.sv",
        "MSHR_FILL: mshr_state_q[i] <= MSHR_FREE;",
        "MSHR_FILL: ;",
        "height_cache:bmc_small", "fill_state_once"),
    "mshr_merge_dropped": (
        "rtl/cache/height_cache.sv",
        "&& !(|way_hit) && !(|mshr_match) && !s3_same;",
        "&& !(|way_hit) && !s3_same;",
        "height_cache:bmc_small", "(?:merge_no_alloc|mshr_unique)"),
    "axi_error_sticky": (
        "rtl/cache/cache_axi_read.sv",
        "        rerr_q[r_idx_o] <= 1'b0;\n",
        "",
        "cache_axi_read:bmc_head", "(?:r_err_marks|inv_slave)"),
    "free_list_dup": (
        "rtl/traverse/traverse_fifo.sv",
        "assign m_wr    = wr_i && !(hd_load && !m_any);",
        "assign m_wr    = wr_i;",
        "traverse_fifo:bmc_free", "(?:fl_exact|fl_total|ram_count|ram_room)"),
    "axi_epoch_frozen": (
        "rtl/cache/cache_axi_read.sv",
        "if (!rst_ni && !in_rst_q) epoch_q <= epoch_q + EPOCH_W'(1);",
        "if (!rst_ni && !in_rst_q) epoch_q <= epoch_q;",
        "cache_axi_read:bmc_rst", "(?:stale_ignored|inv_stale|r_beat_expected|r_outstanding)"),
    "ring_id_duplicated": (
        "rtl/traverse/traverse_loop.sv",
        "v_q     <= {v_q[D-2:0], (v_q[D-1] && !retire && !park) || admit || unpark};",
        "v_q     <= {v_q[D-2:0], (v_q[D-1] && !park) || admit || unpark};",
        "traverse_loop:bmc_ids", r"(?:g_ids\.(?:id_in_ring|id_leave_once)|ring_ids_distinct)"),
    "unit_credit_le": (
        "rtl/traverse/traverse_unit.sv",
        "assign ray_ready_o = (sf_used_q < (SF_AW+1)'(SETUP_FIFO_DEPTH)) && su_in_ready;",
        "assign ray_ready_o = (sf_used_q <= (SF_AW+1)'(SETUP_FIFO_DEPTH)) && su_in_ready;",
        "traverse_unit:bmc_ids",
        r"(?:setup_fifo_never_overflows|setup_credits|no_overflow|count_model)"),
    "rings_result_dropped": (
        "rtl/traverse/traverse_rings.sv",
        "r_res_ready[gnt] = res_ready_i;",
        "r_res_ready      = {R{res_ready_i}};",
        "traverse_rings:bmc_ids",
        r"(?:take_one|g_ids\.(?:rid_count|rid_leave_once|rid_ring)|inv_held)"),
    "axi_ar_dropped": (
        "rtl/cache/cache_axi_read.sv",
        "if (!ar_v_q || m_axi_arready) ar_v_q <= ap_v_q;",
        "ar_v_q <= ap_v_q;",
        "cache_axi_read:bmc_reg", "ar_stable"),
    "view_tag_dropped": (
        "rtl/pipe/view_calc.sv",
        ".clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o, .stage_valid_o(stage_v));",
        ".clk_i, .rst_ni, .en_i, .valid_i(valid_i && !stage_v[4]), .tag_i, .valid_o, .tag_o,"
        " .stage_valid_o(stage_v));",
        "view_calc:bmc_tags", "(?:vtag_inside|vtag_leave_once)"),
    "tex_tag_off_by_one": (
        "rtl/cache/tex_cache_data.sv",
        "tq_rd_q <= tq_mem[tq_rp_d];",
        "tq_rd_q <= tq_mem[tq_rp_d + TQ_W'(1)];",
        "tex_cache:bmc_tags", "(?:inv_tq_read|rsp_tag_order)"),
    "merge_miss_dropped": (
        "rtl/pipe/dm_pipeline.sv",
        "assign miss_rd = o_load && out_empty && !miss_empty;",
        "assign miss_rd = o_load && !miss_empty;",
        "dm_pipeline:bmc_merge", "(?:merge_count|inv_place|merge_leave_once)"),
    "pair_slot_from_colour_fifo": (
        "rtl/pipe/dm_pipeline.sv",
        "assign rq_slot  = rq_sel_q ? pair_slot_q : rq_c_head[SLOT_W+REQ_W-1 -: SLOT_W];",
        "assign rq_slot  = rq_c_head[SLOT_W+REQ_W-1 -: SLOT_W];",
        "dm_pipeline_pairs:bmc_pairs", "(?:inv_pairs|tf_pairs)"),
    "skid_data_overwritten": (
        "rtl/common/skid_buffer.sv",
        "    if (!full_q) data_q <= data_i;",
        "    data_q <= data_i;",
        "skid_buffer:bmc_pass", "(?:order|inv_data|out_held)"),
    "skid_item_dropped": (
        "rtl/common/skid_buffer.sv",
        "        out_v_q <= full_q || valid_i;    // the skid's item first, else the producer's",
        "        out_v_q <= valid_i;",
        "skid_buffer:bmc_reg", "(?:count_model|inv_count|order)"),
    "live_not_freed": (
        "rtl/pipe/dm_pipeline.sv",
        "else         live_q <= live_q + (SLOT_W+1)'(acc) - (SLOT_W+1)'(px_done);",
        "else         live_q <= live_q + (SLOT_W+1)'(acc);",
        "dm_pipeline_slots:bmc_slots", "(?:slot_count|slots_conserved)"),
}


def scratch_tree(name: str) -> Path:
    """A copy of rtl/ and formal/ to mutate."""
    root = SCRATCH / name
    shutil.rmtree(root, ignore_errors=True)
    root.mkdir(parents=True)
    for d in ("rtl", "formal"):
        shutil.copytree(ROOT / d, root / d)
    return root


def mutate(root: Path, rel: str, old: str, new: str) -> None:
    path = root / rel
    text = path.read_text()
    assert text.count(old) == 1, f"{rel}: the text to mutate is not there once: {old}"
    path.write_text(text.replace(old, new))


# BMC depths the mutants' copies run at where make formal's BMC is shallower (one step deeper
# than the induction, which proves the properties at every depth): the step at which each
# mutant's counterexample ends lies beyond it.  file:task -> depth.
MUTANT_BMC_DEPTH = {
    "traverse_loop:bmc_ids": 27,   # id_in_ring at step LOOP_DEPTH + 3 = 26 (23 slots)
    "tex_cache:bmc_tags": 10,      # inv_tq_read at step 5
    "pidm_regs:bmc": 5,            # the wrong read-back bit: rd_value at step 4
    "dm_pipeline_slots:bmc_slots": 14,  # the first pixel leaves at step 12: slot_count at 13
}


def deepen_bmc(root: Path, task: str) -> None:
    """Set the copy's BMC depth for `task` to MUTANT_BMC_DEPTH's (no change for other tasks)."""
    depth = MUTANT_BMC_DEPTH.get(task)
    if depth is None:
        return
    sby = root / "formal" / (task.split(":")[0] + ".sby")
    text = sby.read_text()
    new, n = re.subn(r"^bmc: depth \d+$", f"bmc: depth {depth}", text, flags=re.M)
    assert n == 1, f"{sby}: no single 'bmc: depth N' line"
    sby.write_text(new)


def run_formal(root: Path, task: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "flow" / "formal.py"),
                           "--root", str(root), "--only", task, "--jobs", "1"],
                          capture_output=True, text=True, cwd=ROOT, timeout=600)


@pytest.mark.xdist_group("formal_mutants")
@pytest.mark.parametrize("name", sorted(MUTANTS))
def test_mutant_fails_with_trace(name: str):
    rel, old, new, task, prop = MUTANTS[name]
    root = scratch_tree(name)
    mutate(root, rel, old, new)
    deepen_bmc(root, task)
    p = run_formal(root, task)
    out = p.stdout + p.stderr
    assert p.returncode == 1, out
    assert out.strip().splitlines()[-1].endswith(" 1 failed"), out
    assert re.search(rf"{re.escape(task)} \(\w+\) FAIL", out), out
    # a property of a bound checker (u_assert), of the formal wrapper (the top) or of a formal
    # checker bound into the top (u_formal)
    assert re.search(rf"failed assertion (?:\S*u_assert\.|\w+_formal\.|\S*u_formal\.){prop}\b",
                     out), out
    traces = [root / m for m in re.findall(r"^  trace: (\S+\.vcd)$", out, re.M)]
    assert traces, out
    import pywellen
    for vcd in traces:
        assert vcd.is_file(), vcd
        w = pywellen.Waveform(str(vcd))
        names = [v.full_name for v in w.all_vars()]
        assert any(n.endswith("rst_ni") for n in names), names[:20]


@pytest.mark.xdist_group("formal_mutants")
def test_unmutated_copy_passes():
    """An unchanged copy is the tree itself, so the failures above are the mutations': the copy's
    files are byte for byte those of rtl/ and formal/, whose tasks (every mutant's among them)
    `make formal` proves before the tests run in `make test`; and the driver passes a task on the
    copy through --root (one short task: running every mutant's task again here cost two minutes
    of `make test` and showed nothing `make formal` does not)."""
    root = scratch_tree("unmutated")
    for d in ("rtl", "formal"):
        src = sorted(p.relative_to(ROOT) for p in (ROOT / d).rglob("*") if p.is_file())
        dst = sorted(p.relative_to(root) for p in (root / d).rglob("*") if p.is_file())
        assert src == dst, f"{d}/: the copy's files differ from the tree's"
        for rel in src:
            assert (ROOT / rel).read_bytes() == (root / rel).read_bytes(), rel
    tasks = {task for _, _, _, task, _ in MUTANTS.values()}
    assert "pipe_credit:bmc_l16" in tasks
    p = run_formal(root, "pipe_credit:bmc_l16")
    assert p.returncode == 0, p.stdout + p.stderr
    assert p.stdout.strip().splitlines()[-1].endswith(", 0 failed"), p.stdout


@pytest.mark.xdist_group("formal_mutants")
def test_dropped_property_is_refused():
    """A property the front end never sees (here left out by the preprocessor) fails the run."""
    root = scratch_tree("dropped")
    mutate(root, "rtl/traverse/traverse_fifo_assert.sv",
           "      data_order:   assert",
           "`ifdef FORMAL_NEVER_DEFINED\n      data_order:   assert")
    mutate(root, "rtl/traverse/traverse_fifo_assert.sv",
           "the word due is %0h\", rd_data_i, trk_data_q);",
           "the word due is %0h\", rd_data_i, trk_data_q);\n`endif")
    p = run_formal(root, "traverse_fifo:prove_d4")
    out = p.stdout + p.stderr
    assert p.returncode == 1, out
    assert "traverse_fifo:prove_d4 (prove) LOST" in out, out
    assert "assert data_order lost by the front end" in out, out


def _driver():
    import importlib.util
    spec = importlib.util.spec_from_file_location("formal_driver",
                                                  ROOT / "scripts" / "flow" / "formal.py")
    mod = importlib.util.module_from_spec(spec)
    assert spec.loader is not None
    sys.modules["formal_driver"] = mod   # dataclasses look their module up there
    spec.loader.exec_module(mod)
    return mod


def test_sby_parsing_and_bmc_depth_rule(tmp_path):
    """The driver reads tasks, modes and depths, and refuses a file whose BMC is not deeper than
    its induction; unlabelled properties are reported."""
    drv = _driver()
    sby = tmp_path / "x.sby"
    text = ("[tasks]\nprove_a a prove\nbmc_a a bmc\ncover_a a cover\n\n[options]\n"
            "prove: mode prove\nprove: depth 3\nbmc: mode bmc\nbmc: depth {bmc}\n"
            "cover: mode cover\n\n[files]\nrtl/x.sv\n")
    sby.write_text(text.format(bmc=12))
    tasks = drv.parse_sby(sby)
    assert [(t.name, t.mode, t.depth) for t in tasks] == [
        ("prove_a", "prove", 3), ("bmc_a", "bmc", 12), ("cover_a", "cover", 20)]
    assert tasks[0].files == ["rtl/x.sv"]
    sby.write_text(text.format(bmc=3))
    with pytest.raises(ValueError, match="deeper"):
        drv.parse_sby(sby)
    labels, problems = drv.labelled_properties(
        "// assert (x);\n  a1: assert (x);\n  c1: cover (y);\n  assert (z);\n", "f.sv")
    assert labels == {"assert": {"a1"}, "cover": {"c1"}}
    assert len(problems) == 1 and problems[0].startswith("f.sv:4:")


# The register block (formal/pidm_regs.sby): known bugs in a copy of the generated block
# rtl/top/pidm_regs.sv.  name: (original text, mutated text, the assertion expected to fail).
REGS_MUTANTS = {
    # ERROR.t_axi (W1C) cleared by any write to ERROR, whatever its bit 1 holds
    "regs_w1c_clears_all": (
        "next_c = field_storage.ERROR.t_axi.value & ~(decoded_wr_data[1:1] & decoded_wr_biten[1:1]);",
        "next_c = 1'b0;",
        r"\\?g_t\[14\]\.field_match"),
    # the byte strobes honoured again (the generated line scripts/flow/regs.py changes): a write
    # with a strobe off keeps that byte
    "regs_strobes_honoured": (
        "cpuif_wr_biten[i*8 +: 8] = '1;  // WSTRB ignored: whole-word writes (scripts/flow/regs.py)",
        "cpuif_wr_biten[i*8 +: 8] = {8{axil_wstrb[i]}};",
        r"(?:wr_commit_fields|\\?g_t\[\d+\]\.field_match)"),
    # HEIGHT.MODE.bits16 read back in reserved bit 9 instead of bit 8
    "regs_read_wrong_bit": (
        "readback_data_var[ad_hi(12'h200)][8] = field_storage.HEIGHT.MODE.bits16.value;",
        "readback_data_var[ad_hi(12'h200)][9] = field_storage.HEIGHT.MODE.bits16.value;",
        r"(?:rd_value|rdata_match|front_entries)"),
}


@pytest.mark.xdist_group("formal_mutants")
@pytest.mark.parametrize("name", sorted(REGS_MUTANTS))
def test_regs_mutant_fails_with_trace(name: str):
    """A register block that breaks the RDL's rules fails pidm_regs:bmc with a trace (the
    unchanged block passes the same task in make formal)."""
    old, new, prop = REGS_MUTANTS[name]
    root = scratch_tree(name)
    mutate(root, "rtl/top/pidm_regs.sv", old, new)
    task = "pidm_regs:bmc"
    deepen_bmc(root, task)
    p = run_formal(root, task)
    out = p.stdout + p.stderr
    assert p.returncode == 1, out
    assert out.strip().splitlines()[-1].endswith(" 1 failed"), out
    assert re.search(rf"{re.escape(task)} \(\w+\) FAIL", out), out
    assert re.search(rf"failed assertion pidm_regs_formal\.{prop}\b", out), out
    traces = [root / m for m in re.findall(r"^  trace: (\S+\.vcd)$", out, re.M)]
    assert traces, out
    import pywellen
    for vcd in traces:
        w = pywellen.Waveform(str(vcd))
        names = [v.full_name for v in w.all_vars()]
        assert any(n.endswith("rst_ni") for n in names), names[:20]
