#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Write the GTKWave save files of tb/waves/ (one signal list, three hierarchies), or check them
against an FST.

  gen_gtkw.py                 write tb/waves/*.gtkw
  gen_gtkw.py --check-only    exit 1 if a committed file differs from what this script writes
  gen_gtkw.py --fst F.fst --target NAME
                              exit 1 listing the save file's signals that F.fst lacks

Targets (the scope prefix is where each simulator puts the unit):
  traverse_harness.gtkw  the Verilator C++ harness (tb/harness/traverse_system.py, scripts/ray_steps.py
                         --waves): TOP.traverse_system...
  traverse_system.gtkw   the cocotb test (make waves TEST=traverse_system): traverse_system...
  dm_pipeline.gtkw       the cocotb test of the whole pipeline (make waves TEST=dm_pipeline, SLOTS=32):
                         dm_pipeline..., the traverse groups under dm_pipeline.u_trav.g_ring[0].u_sys (ring 0)

Signal names follow GTKWave's facility names for Verilator's FST: a vector is `name[msb:0]`, an
unpacked array element `arr.arr[i]`, a packed struct member `s.member` (--trace-structs).  The
--fst check reads the FST with pywellen and maps its names the same way.
"""
from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "tb" / "waves"
from model.cli import Parser
from tb.harness import sv_params

#: The traverse ring's stages and its busy count's width (traverse_pkg), for the loop's groups.
LOOP_DEPTH = sv_params.value("traverse_pkg", "LOOP_DEPTH")
LOOP_BUSY_W = sv_params.value("traverse_pkg", "LOOP_BUSY_W")

# GTKWave trace flags: hex / binary / decimal, right-justified; comment; group begin / end.
HEX, BIN, DEC = "22", "28", "24"
COMMENT, GRP_BEGIN, GRP_END = "200", "800200", "1000200"

# A signal: (path below the unit's scope, width or a width key, format).  Width keys differ per
# target: ID (ray id: RAY_ID_W), AXI_ID.
Sig = tuple[str, "int | str", str]

TRAVERSE: list[tuple[str, list[Sig]]] = [
    ("rays in", [
        ("clk_i", 1, BIN), ("rst_ni", 1, BIN), ("ray_valid_i", 1, BIN), ("ray_ready_o", 1, BIN),
        ("ray_id_i", "ID", DEC), ("ray_u0_i", 24, HEX), ("ray_v0_i", 24, HEX),
        ("ray_du_i", 24, HEX), ("ray_dv_i", 24, HEX)]),
    ("setup (first mode) -> setup FIFO", [
        ("u_unit.su_valid", 1, BIN), ("u_unit.su_id", "ID", DEC),
        ("u_unit.su_ray.k", 4, DEC), ("u_unit.su_ray.cx", 16, DEC), ("u_unit.su_ray.cy", 16, DEC),
        ("u_unit.su_ray.t", 24, HEX), ("u_unit.su_ray.inv_du", 24, HEX),
        ("u_unit.su_ray.inv_dv", 24, HEX), ("u_unit.su_ray.t_map", 24, HEX),
        ("u_unit.su_ray.invalid", 1, BIN), ("u_unit.su_ray.done", 1, BIN)]),
    ("loop: v_q[s] stage s holds a ray (its fields in f_q[s]); S0 looks its height up; du, dv "
     f"tables' slot sl_q[s] = (sl_q[0] - s) mod {LOOP_DEPTH}", [
        ("u_unit.u_loop.v_q", LOOP_DEPTH, BIN), ("u_unit.u_loop.sl_q.sl_q[0]", 5, DEC),
        ("u_unit.u_loop.live0_q", 1, BIN), ("u_unit.u_loop.addr0", 32, HEX)]),
    ("S1 height lookup -> S4 response (LOOKUP_LAT 3; rs_hit 0: goes round again); the state of "
     "the ray in S1", [
        ("u_unit.lk_valid_o", 1, BIN), ("u_unit.lk_addr_o", 32, HEX), ("u_unit.lk_wide_o", 1, BIN),
        ("u_unit.rs_valid_i", 1, BIN), ("u_unit.rs_hit_i", 1, BIN), ("u_unit.rs_err_i", 1, BIN),
        ("u_unit.rs_data_i", 16, HEX),
        ("u_unit.u_loop.node_q.node_q[1].k", 4, DEC),
        ("u_unit.u_loop.node_q.node_q[1].cx", 16, DEC),
        ("u_unit.u_loop.node_q.node_q[1].cy", 16, DEC), ("u_unit.u_loop.t_q.t_q[1]", 24, HEX),
        ("u_unit.u_loop.stat_q.stat_q[1].iters", 16, DEC)]),
    ("S4-S7: H, plane = 1 - H, crossing times, t_end", [
        ("u_unit.u_loop.h", 24, HEX), ("u_unit.u_loop.plane", 24, HEX),
        ("u_unit.u_loop.tx_raw", 24, HEX), ("u_unit.u_loop.ty_raw", 24, HEX),
        ("u_unit.u_loop.tend6_q", 24, HEX),
        ("u_unit.u_loop.inside7", 1, BIN)]),
    ("S14: descent (the new level, levels descended)", [
        ("u_unit.u_loop.nk14_q", 4, DEC), ("u_unit.u_loop.dd14", 4, DEC)]),
    (f"S18: the iteration's action and the next state (stage {LOOP_DEPTH - 2} of the "
     f"{LOOP_DEPTH}-stage ring)", [
        ("u_unit.u_loop.live18", 1, BIN), ("u_unit.u_loop.act18_q.is_hit", 1, BIN),
        ("u_unit.u_loop.act18_q.down", 1, BIN), ("u_unit.u_loop.act18_q.miss", 1, BIN),
        ("u_unit.u_loop.iter18", 1, BIN), ("u_unit.u_loop.hit18", 1, BIN),
        ("u_unit.u_loop.down18", 1, BIN), ("u_unit.u_loop.cross18", 1, BIN),
        ("u_unit.u_loop.miss18", 1, BIN), ("u_unit.u_loop.err18", 1, BIN),
        ("u_unit.u_loop.cap18", 1, BIN), ("u_unit.u_loop.it18_q", 16, DEC)]),
    (f"S19: retire / admit a new ray (the tail, stage {LOOP_DEPTH - 1})", [
        ("u_unit.u_loop.retire", 1, BIN), ("u_unit.u_loop.admit", 1, BIN),
        ("u_unit.u_loop.bypass", 1, BIN), ("u_unit.u_loop.busy_o", LOOP_BUSY_W, DEC)]),
    ("results out", [
        ("res_valid_o", 1, BIN), ("res_ready_i", 1, BIN), ("res_id_o", "ID", DEC),
        ("res_hit_o", 1, BIN), ("res_t_o", 24, HEX), ("res_u_o", 24, HEX), ("res_v_o", 24, HEX),
        ("res_iters_o", 16, DEC), ("res_invalid_o", 1, BIN), ("res_capped_o", 1, BIN),
        ("res_err_o", 1, BIN)]),
    ("height cache", [
        ("u_cache.lk_valid_i", 1, BIN), ("u_cache.lk_addr_i", 32, HEX),
        ("u_cache.s1_valid_q", 1, BIN), ("u_cache.s2_valid_q", 1, BIN),
        ("u_cache.s2_conflict_q", 1, BIN), ("u_cache.s2_hit", 1, BIN), ("u_cache.s2_miss", 1, BIN),
        ("u_cache.s3_alloc", 1, BIN),
        ("u_cache.rs_valid_o", 1, BIN), ("u_cache.rs_hit_o", 1, BIN), ("u_cache.rs_err_o", 1, BIN),
        ("u_cache.rs_data_o", 16, HEX), ("u_cache.stat_hits_o", 48, DEC),
        ("u_cache.stat_misses_o", 48, DEC)]),
    ("AXI AR (heights)", [
        ("m_axi_arvalid", 1, BIN), ("m_axi_arready", 1, BIN), ("m_axi_arid", "AXI_ID", HEX),
        ("m_axi_araddr", 32, HEX), ("m_axi_arlen", 8, DEC), ("m_axi_arsize", 3, DEC),
        ("m_axi_arburst", 2, BIN)]),
    ("AXI R (heights)", [
        ("m_axi_rvalid", 1, BIN), ("m_axi_rready", 1, BIN), ("m_axi_rid", "AXI_ID", HEX),
        ("m_axi_rdata", 64, HEX), ("m_axi_rresp", 2, BIN), ("m_axi_rlast", 1, BIN)]),
]

PIPELINE_FRONT: list[tuple[str, list[Sig]]] = [
    ("fragments in", [
        ("clk_i", 1, BIN), ("rst_ni", 1, BIN), ("frag_valid_i", 1, BIN), ("frag_ready_o", 1, BIN),
        ("frag_id_i", 20, DEC), ("frag_u0_i", 24, HEX), ("frag_v0_i", 24, HEX),
        ("frag_pl0_i", 24, HEX), ("frag_tri_i", 4, DEC)]),
    ("slots, view_calc -> FIFO #0 (credits)", [
        ("live_q", "SLOT1", DEC), ("free_head", "SLOT", DEC), ("vc_cnt", 5, DEC),
        ("vc_valid", 1, BIN), ("vc_slot", "SLOT", DEC), ("vc_du", 24, HEX), ("vc_dv", 24, HEX),
        ("vc_seg", 24, HEX), ("f0_count", 5, DEC), ("f0_rd", 1, BIN)]),
]

PIPELINE_BACK: list[tuple[str, list[Sig]]] = [
    ("traversal results: hit -> MIP / texture, miss -> miss FIFO", [
        ("res_valid", 1, BIN), ("res_ready", 1, BIN), ("res_id", "SLOT", DEC),
        ("res_hit", 1, BIN), ("res_t", 24, HEX), ("res_u", 24, HEX), ("res_v", 24, HEX),
        ("res_iters", 16, DEC), ("hit_adm", 1, BIN), ("miss_wr", 1, BIN),
        ("req_cnt", 5, DEC), ("hit_cnt", 7, DEC)]),
    ("MIP level -> texture address unit (colour, then normal map)", [
        ("mip_valid", 1, BIN), ("mip_tex", 1, BIN), ("mip_lvl", 5, DEC),
        ("ta_valid", 1, BIN), ("ta_tex", 1, BIN), ("ta_slot", "SLOT", DEC)]),
    ("texture cache requests / responses", [
        ("tc_req_valid", 1, BIN), ("tc_req_ready", 1, BIN), ("rq_sel_q", 1, BIN),
        ("rq_slot", "SLOT", DEC), ("tc_rsp_valid", 1, BIN), ("tc_rsp_err", 1, BIN),
        ("tc_rsp_texel.tc_rsp_texel[0]", 32, HEX), ("tc_rsp_texel.tc_rsp_texel[1]", 32, HEX),
        ("tc_rsp_texel.tc_rsp_texel[2]", 32, HEX), ("tc_rsp_texel.tc_rsp_texel[3]", 32, HEX)]),
    ("AXI AR (textures)", [
        ("m_axi_t_arvalid", 1, BIN), ("m_axi_t_arready", 1, BIN), ("m_axi_t_arid", 6, HEX),
        ("m_axi_t_araddr", 32, HEX), ("m_axi_t_arlen", 8, DEC)]),
    ("AXI R (textures)", [
        ("m_axi_t_rvalid", 1, BIN), ("m_axi_t_rready", 1, BIN), ("m_axi_t_rid", 6, HEX),
        ("m_axi_t_rdata", 64, HEX), ("m_axi_t_rresp", 2, BIN), ("m_axi_t_rlast", 1, BIN)]),
    ("filter -> shade -> pixels out", [
        ("tf_valid", 1, BIN), ("tf_r", 24, HEX), ("tf_g", 24, HEX), ("tf_b", 24, HEX),
        ("sh_in_valid", 1, BIN), ("sh_valid", 1, BIN),
        ("px_valid_o", 1, BIN), ("px_ready_i", 1, BIN), ("px_id_o", 20, DEC),
        ("px_rgb_o.px_rgb_o[0]", 8, HEX), ("px_rgb_o.px_rgb_o[1]", 8, HEX),
        ("px_rgb_o.px_rgb_o[2]", 8, HEX), ("px_hit_o", 1, BIN), ("px_invalid_o", 1, BIN),
        ("px_err_o", 1, BIN), ("px_iters_o", 16, DEC), ("idle_o", 1, BIN)]),
]

# target: (scope of the unit, traverse scope, width keys, pipeline groups?, what)
TARGETS = {
    "traverse_harness": ("TOP.traverse_system", None, {"ID": 16, "AXI_ID": 4},
                         "traverse_system in the Verilator C++ harness (tb/harness/traverse_system.py, "
                         "scripts/ray_steps.py --waves)"),
    "traverse_system": ("traverse_system", None, {"ID": 16, "AXI_ID": 4},
                        "traverse_system in its cocotb test (make waves TEST=traverse_system)"),
    "dm_pipeline": ("dm_pipeline", "u_trav.g_ring[0].u_sys", {"ID": 5, "AXI_ID": 4, "SLOT": 5, "SLOT1": 6},
                    "dm_pipeline in its cocotb test, SLOTS=32 (make waves TEST=dm_pipeline)"),
}


def groups_for(target: str) -> list[tuple[str, list[tuple[str, int, str]]]]:
    scope, trav, widths, _ = TARGETS[target]

    def resolve(sigs: list[Sig], prefix: str) -> list[tuple[str, int, str]]:
        return [(f"{prefix}.{p}", widths[w] if isinstance(w, str) else w, f) for p, w, f in sigs]

    if trav is None:
        return [(name, resolve(s, scope)) for name, s in TRAVERSE]
    out = [(name, resolve(s, scope)) for name, s in PIPELINE_FRONT]
    # the traverse unit inside the pipeline: its AXI port is the pipeline's height port
    for name, s in TRAVERSE:
        if name == "rays in":
            s = [x for x in s if x[0] not in ("clk_i", "rst_ni")]
        out.append((f"traverse: {name}", resolve(s, f"{scope}.{trav}")))
    out += [(name, resolve(s, scope)) for name, s in PIPELINE_BACK]
    return out


def facility(path: str, width: int) -> str:
    return path + (f"[{width - 1}:0]" if width > 1 else "")


def render(target: str) -> str:
    _, _, _, what = TARGETS[target]
    lines = ["[*] SPDX-License-Identifier: Apache-2.0",
             f"[*] GTKWave save file: {what}.",
             "[*] Generated by scripts/flow/gen_gtkw.py (edit the lists there, not this file).",
             "[*] Open: gtkwave <dump.fst> this-file.gtkw",
             "[timestart] 0", "[size] 1600 1000", "[pos] -1 -1", "[sst_width] 260",
             "[signals_width] 360", "[sst_expanded] 1", "[sst_vpaned_height] 300"]
    for name, sigs in groups_for(target):
        lines += [f"@{GRP_BEGIN}", f"-{name}"]
        cur = None
        for path, width, fmt in sigs:
            if fmt != cur:
                lines.append(f"@{fmt}")
                cur = fmt
            lines.append(facility(path, width))
        lines += [f"@{GRP_END}", f"-{name}"]
    return "\n".join(lines) + "\n"


def fst_facilities(fst: Path) -> set[str]:
    """GTKWave's facility names of an FST, from pywellen's (arrays: `a.[i]` -> `a.a[i]`)."""
    import pywellen

    w = pywellen.Waveform(str(fst))
    names = set()
    for v in w.all_vars():
        parts = v.full_name.split(".")
        parts = [(parts[i - 1] + p if p.startswith("[") and i else p) for i, p in enumerate(parts)]
        vt = str(v.var_type() if callable(v.var_type) else v.var_type)
        names.add(".".join(parts) + (f"[{v.bitwidth - 1}:0]"
                                     if v.bitwidth > 1 and "Param" not in vt else ""))
    return names


def check_fst(target: str, fst: Path) -> list[str]:
    have = fst_facilities(fst)
    return [facility(p, w) for _, sigs in groups_for(target) for p, w, _ in sigs
            if facility(p, w) not in have]


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog="gen_gtkw.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--check-only", action="store_true")
    ap.add_argument("--fst", type=Path)
    ap.add_argument("--target", choices=sorted(TARGETS))
    args = ap.parse_args(argv)
    if args.fst is not None:
        if args.target is None:
            print("gen_gtkw.py: error: --fst needs --target", file=sys.stderr)
            return 2
        if not args.fst.is_file():
            print(f"gen_gtkw.py: error: no file {args.fst}", file=sys.stderr)
            return 2
        try:
            missing = check_fst(args.target, args.fst)
        except (RuntimeError, OSError, ValueError) as e:
            msg = " ".join(str(e).split()) or type(e).__name__
            print(f"gen_gtkw.py: error: {args.fst} is not a readable FST/VCD waveform ({msg})",
                  file=sys.stderr)
            return 2
        n = sum(len(s) for _, s in groups_for(args.target))
        if missing:
            print(f"gen_gtkw.py: {args.target}: {len(missing)} of {n} signals not in {args.fst}:")
            for m in missing:
                print(f"  {m}")
            return 1
        print(f"gen_gtkw.py: {args.target}: all {n} signals found in {args.fst}")
        return 0
    stale = []
    for t in TARGETS:
        path = OUT / f"{t}.gtkw"
        text = render(t)
        if args.check_only:
            if not path.is_file() or path.read_text() != text:
                stale.append(str(path.relative_to(ROOT)))
        else:
            OUT.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
    if stale:
        print("gen_gtkw.py: out of date (run scripts/flow/gen_gtkw.py): " + ", ".join(stale))
        return 1
    if not args.check_only:
        print(f"gen_gtkw.py: wrote {', '.join(f'tb/waves/{t}.gtkw' for t in TARGETS)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
