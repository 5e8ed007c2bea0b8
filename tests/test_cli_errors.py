# SPDX-License-Identifier: Apache-2.0
"""Every command-line tool rejects bad files and arguments with one line and exit status 2.

``TRACE_CASES`` are scripts/trace.py's (the contract's interface); ``TOOL_CASES`` list the cases of
every other tool: scripts/**/*.py with a command line, ``python -m tb.harness.traverse_system`` and ``python -m
tb.harness.dm_pipeline``.  A case passes when the tool exits with status 2, prints no traceback and
exactly one non-empty line in all (stdout and stderr together) that names the problem.  Every case
fails before any long work starts (argument checks, missing or unreadable files).  A case a tool
does not yet meet is marked ``xfail(strict=True)`` with what it does instead (reported to the
tool's owner): it must start passing when the tool is fixed, and the marker then goes.
"""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, cwd=ROOT,
                          timeout=120)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("cli")
    np.save(d / "h.npy", np.random.default_rng(0).random((16, 24)))
    rays = np.random.default_rng(1).uniform(0, 15, (50, 4))
    np.save(d / "r.npy", rays)
    np.save(d / "r32.npy", rays.astype(np.float32))
    np.save(d / "r3.npy", rays[:, :3])
    (d / "junk.npy").write_bytes(b"junk")
    (d / "junk.png").write_bytes(b"junk")
    (d / "junk.fst").write_bytes(b"junk")
    (d / "afile").write_text("a file, not a directory\n")
    (d / "junkcov").mkdir()
    (d / "junkcov" / "x.dat").write_text("not a coverage file\n")
    (d / "emptydir").mkdir()
    (d / "heat").mkdir()  # router2 heatmaps: iteration 1 good, iteration 2 a broken grid
    (d / "heat" / "top_congestion_by_net_1.csv").write_text("u_pipe.u_a.n,3\n")
    (d / "heat" / "top_congestion_by_coordinate_1.csv").write_text("0,3,\n0,0,\n")
    (d / "heat" / "top_congestion_by_net_2.csv").write_text("u_pipe.u_a.n,3\n")
    (d / "heat" / "top_congestion_by_coordinate_2.csv").write_text("0,x,\n")
    return d


TRACE_CASES = {
    "missing heightmap": ["--heightmap", "{d}/nope.png"],
    "unreadable heightmap": ["--heightmap", "{d}/junk.png"],
    "missing rays": ["--rays", "{d}/nope.npy"],
    "unreadable rays": ["--rays", "{d}/junk.npy"],
    "float32 rays": ["--rays", "{d}/r32.npy"],
    "rays of shape (N, 3)": ["--rays", "{d}/r3.npy"],
    "unknown method": ["--method", "nope"],
    "unknown engine": ["--engine", "gpu"],
    "approximate method on f24": ["--method", "relief", "--engine", "f24"],
    "approximate method on rtl": ["--method", "relief", "--engine", "rtl"],
    "missing output directory": ["--out", "{d}/no/such/dir/o.npz"],
    "bad bits": ["--bits", "12"],
}


@pytest.mark.parametrize("case", TRACE_CASES)
def test_trace_errors(files, case: str) -> None:
    base = {"--heightmap": f"{files}/h.npy", "--rays": f"{files}/r.npy", "--method": "park",
            "--engine": "f64", "--out": f"{files}/o.npz"}
    over = [a.format(d=files) for a in TRACE_CASES[case]]
    base.update(dict(zip(over[::2], over[1::2])))
    p = run("scripts/trace.py", *[x for kv in base.items() for x in kv])
    assert p.returncode == 2, (case, p.stdout, p.stderr)
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "error" in lines[0], (case, p.stderr)
    assert "Traceback" not in p.stderr


def test_trace_missing_argument_is_one_line(files) -> None:
    p = run("scripts/trace.py", "--heightmap", f"{files}/h.npy")
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1


def test_trace_writes_the_contract(files) -> None:
    out = files / "ok.npz"
    for method, engine in [("park", "f24"), ("oh", "f64"), ("relief", "f64"), ("park", "rtl")]:
        p = run("scripts/trace.py", "--heightmap", f"{files}/h.npy", "--rays", f"{files}/r.npy",
                "--method", method, "--engine", engine, "--out", str(out), "--quiet")
        assert p.returncode == 0, p.stderr
        z = np.load(out)
        for k in ("t", "u", "v", "hit", "iterations", "invalid", "stats"):
            assert k in z.files
        assert z["t"].dtype == np.float64 and z["hit"].dtype == bool
        assert z["iterations"].dtype == np.int64 and z["t"].shape == (50,)
        assert np.isnan(z["t"][~z["hit"]]).all()
        if engine == "rtl":
            st = json.loads(str(z["stats"]))
            for k in ("cycles", "rays", "iterations", "height_cache_hits", "height_cache_misses",
                      "mem_bytes"):
                assert k in st, k


# ---- every other tool ----------------------------------------------------------------------------

def _fails(why: str) -> dict[str, str]:
    return {"xfail": why}



#: tool (a script path or "-m module"), its arguments ({d}: a scratch directory holding h.npy,
#: r.npy, r3.npy, junk.npy, junk.png, junk.fst, afile, junkcov/x.dat, emptydir/), and optionally
#: {"xfail": what the tool does instead}.
TOOL_CASES: dict[str, tuple[str, list[str], dict[str, str]]] = {
    # render.py
    "render unknown option": ("scripts/render.py", ["--nope"], {}),
    "render unknown method": ("scripts/render.py", ["--method", "nope"], {}),
    "render size 0": ("scripts/render.py", ["--size", "0"], {}),
    "render bad angle": ("scripts/render.py", ["--angle", "sideways"], {}),
    "render missing heightmap": ("scripts/render.py", ["--heightmap", "{d}/nope.png"], {}),
    "render unreadable heightmap": ("scripts/render.py", ["--heightmap", "{d}/junk.png"], {}),
    "render unknown engine": ("scripts/render.py", ["--engine", "gpu"], {}),
    "render latency 0": ("scripts/render.py", ["--engine", "rtl", "--latency", "0"], {}),
    # study.py
    "study unknown scene": ("scripts/bench/study.py", ["--quick", "--scenes", "nope", "--out", "{d}/st"],
                            {}),
    "study bad angle": ("scripts/bench/study.py", ["--quick", "--angles", "nope", "--out", "{d}/st"], {}),
    "study out is a file": ("scripts/bench/study.py", ["--quick", "--out", "{d}/afile"], {}),
    "study size 0": ("scripts/bench/study.py", ["--quick", "--size", "0", "--out", "{d}/st"], {}),
    # bench_model.py
    "bench_model unknown scene": ("scripts/bench/bench_model.py", ["--scene", "nope"], {}),
    "bench_model unknown method": ("scripts/bench/bench_model.py", ["--methods", "nope"], {}),
    "bench_model bad angle": ("scripts/bench/bench_model.py", ["--angles", "sideways", "--out",
                                                         "{d}/bm.json"],
                              {}),
    "bench_model size 0": ("scripts/bench/bench_model.py", ["--size", "0", "--out", "{d}/bm.json"],
                           {}),
    "bench_model repeat 0": ("scripts/bench/bench_model.py", ["--repeat", "0", "--out", "{d}/bm.json"],
                             {}),
    # bench_rtl.py
    "bench_rtl unknown scene": ("scripts/bench/bench_rtl.py", ["--scenes", "nope"], {}),
    "bench_rtl approximate method": ("scripts/bench/bench_rtl.py", ["--methods", "relief"], {}),
    "bench_rtl bad angle": ("scripts/bench/bench_rtl.py", ["--angles", "sideways"], {}),
    "bench_rtl latency 0": ("scripts/bench/bench_rtl.py", ["--latency", "0"], {}),
    "bench_rtl mshrs not a power of two": ("scripts/bench/bench_rtl.py", ["--mshrs", "6"], {}),
    "bench_rtl park knob without park": ("scripts/bench/bench_rtl.py", ["--park-wait", "8"], {}),
    "bench_rtl park depth too deep": ("scripts/bench/bench_rtl.py", ["--park", "--park-depth",
                                                                    "41"], {}),
    "bench_rtl sets not a power of two": ("scripts/bench/bench_rtl.py", ["--sets", "300"], {}),
    # bench_pipeline.py
    "bench_pipeline unknown scene": ("scripts/bench/bench_pipeline.py", ["--scenes", "nope"], {}),
    "bench_pipeline bad view": ("scripts/bench/bench_pipeline.py", ["--views", "sideways"], {}),
    "bench_pipeline bad mip": ("scripts/bench/bench_pipeline.py", ["--mip", "maybe"], {}),
    "bench_pipeline map 0": ("scripts/bench/bench_pipeline.py", ["--map", "0"], {}),
    "bench_pipeline image not a number": ("scripts/bench/bench_pipeline.py", ["--image", "x"], {}),
    "bench_pipeline latency 0": ("scripts/bench/bench_pipeline.py", ["--latency", "0"], {}),
    "bench_pipeline approximate method": ("scripts/bench/bench_pipeline.py", ["--method", "relief"], {}),
    # terrain.py
    "terrain no source": ("scripts/terrain.py", [], {}),
    "terrain missing dem": ("scripts/terrain.py", ["--dem", "{d}/nope.tif"], {}),
    "terrain unreadable dem": ("scripts/terrain.py", ["--dem", "{d}/junk.png"], {}),
    "terrain dem and synthetic": ("scripts/terrain.py", ["--dem", "{d}/h.npy", "--synthetic",
                                                         "64"], {}),
    "terrain synthetic 0": ("scripts/terrain.py", ["--synthetic", "0"], {}),
    "terrain bad bits": ("scripts/terrain.py", ["--synthetic", "64", "--bits", "12"], {}),
    "terrain unknown method": ("scripts/terrain.py", ["--synthetic", "64", "--method", "nope"], {}),
    "terrain negative height scale": ("scripts/terrain.py", ["--synthetic", "64",
                                                             "--height-scale", "-1"], {}),
    "terrain unreadable texture": ("scripts/terrain.py", ["--synthetic", "64", "--texture",
                                                          "{d}/junk.png", "--out", "{d}/ter"], {}),
    "terrain out is a file": ("scripts/terrain.py", ["--synthetic", "64", "--out", "{d}/afile"],
                              {}),
    # relief_texture.py
    "relief_texture unknown sample": ("scripts/relief_texture.py", ["--samples", "nope", "--out",
                                                                    "{d}/rt"], {}),
    "relief_texture size 0": ("scripts/relief_texture.py", ["--size", "0", "--out", "{d}/rt"], {}),
    "relief_texture elevation 100": ("scripts/relief_texture.py", ["--elevation", "100", "--out",
                                                                   "{d}/rt"], {}),
    "relief_texture bad backend": ("scripts/relief_texture.py", ["--backends", "gpu", "--out",
                                                                 "{d}/rt"], {}),
    "relief_texture out is a file": ("scripts/relief_texture.py", ["--out", "{d}/afile"], {}),
    # ray_steps.py
    "ray_steps unknown scene": ("scripts/ray_steps.py", ["--scene", "nope", "--ray", "1", "1", "1",
                                                         "1"], {}),
    "ray_steps missing heightmap": ("scripts/ray_steps.py", ["--heightmap", "{d}/nope.png",
                                                             "--ray", "1", "1", "1", "1"], {}),
    "ray_steps unreadable heightmap": ("scripts/ray_steps.py", ["--heightmap", "{d}/junk.png",
                                                                "--ray", "1", "1", "1", "1"], {}),
    "ray_steps two ray sources": ("scripts/ray_steps.py", ["--ray", "1", "1", "1", "1", "--pixel",
                                                           "3", "3"], {}),
    "ray_steps missing rays": ("scripts/ray_steps.py", ["--rays", "{d}/nope.npy", "--index", "0"],
                               {}),
    "ray_steps rays of shape (N, 3)": ("scripts/ray_steps.py", ["--rays", "{d}/r3.npy", "--index",
                                                                "0"], {}),
    "ray_steps index out of range": ("scripts/ray_steps.py", ["--rays", "{d}/r.npy", "--index",
                                                              "99"], {}),
    "ray_steps unknown method": ("scripts/ray_steps.py", ["--ray", "1", "1", "1", "1", "--method",
                                                          "nope"], {}),
    "ray_steps waves not fst": ("scripts/ray_steps.py", ["--ray", "1", "1", "1", "1", "--rtl",
                                                         "--waves", "{d}/x.vcd"], {}),
    "ray_steps json in a file": ("scripts/ray_steps.py", ["--ray", "1", "1", "1", "1", "--json",
                                                          "{d}/afile/x.json"], {}),
    # waves.py
    "waves no test": ("scripts/waves.py", [], {}),
    "waves empty test": ("scripts/waves.py", [""], {}),
    "waves unknown test": ("scripts/waves.py", ["nope_tb"], {}),
    "waves directory with a test part": ("scripts/waves.py", ["tb/traverse_fifo::x"], {}),
    "waves unknown option": ("scripts/waves.py", ["traverse_fifo", "--nope"], {}),
    "waves case matching no test": ("scripts/waves.py", ["traverse_fifo", "--case", "nosuch"], {}),
    # congestion.py
    "congestion no directory": ("scripts/flow/congestion.py", ["{d}/nope"], {}),
    "congestion no heatmaps": ("scripts/flow/congestion.py", ["{d}/emptydir"], {}),
    "congestion depth 0": ("scripts/flow/congestion.py", ["{d}/emptydir", "--depth", "0"], {}),
    "congestion depth not a number": ("scripts/flow/congestion.py", ["{d}/emptydir", "--depth", "x"],
                                      {}),
    "congestion no such iteration": ("scripts/flow/congestion.py", ["{d}/heat", "--iteration", "9"],
                                     {}),
    "congestion bad grid": ("scripts/flow/congestion.py", ["{d}/heat", "--iteration", "2"], {}),
    "congestion json in a file": ("scripts/flow/congestion.py", ["{d}/heat", "--json",
                                                            "{d}/afile/x.json"], {}),
    # synth.py
    "synth unknown block": ("scripts/flow/synth.py", ["--blocks", "nope"], {}),
    "synth jobs 0": ("scripts/flow/synth.py", ["--jobs", "0"], {}),
    "synth missing constraints": ("scripts/flow/synth.py", ["--lpf", "{d}/nope.lpf"], {}),
    "synth constraints without a clock": ("scripts/flow/synth.py", ["--lpf", "{d}/afile"], {}),
    "synth missing report": ("scripts/flow/synth.py", ["--report-only", "--out", "{d}/nosyn"], {}),
    "synth unknown device": ("scripts/flow/synth.py", ["--device", "nope"], {}),
    # soak.py
    "soak rays 0": ("scripts/bench/soak.py", ["--rays", "0"], {}),
    "soak rays not a number": ("scripts/bench/soak.py", ["--rays", "x"], {}),
    "soak batch 0": ("scripts/bench/soak.py", ["--batch-rays", "0"], {}),
    "soak faults share 2": ("scripts/bench/soak.py", ["--faults", "2"], {}),
    "soak max side 0": ("scripts/bench/soak.py", ["--max-side", "0"], {}),
    "soak negative seed": ("scripts/bench/soak.py", ["--seed", "-1"], {}),
    "soak batch out of range": ("scripts/bench/soak.py", ["--rays", "10", "--batch-rays", "5",
                                                    "--only-batch", "7"], {}),
    "soak unknown variant": ("scripts/bench/soak.py", ["--variant", "nope"], {}),
    "soak out is a file": ("scripts/bench/soak.py", ["--out", "{d}/afile"], {}),
    # coverage.py
    "coverage unknown test path": ("scripts/bench/coverage.py", ["--tests", "nope/"], {}),
    "coverage jobs 0": ("scripts/bench/coverage.py", ["--jobs", "0"], {}),
    "coverage report without data": ("scripts/bench/coverage.py", ["--report-only", "--dat-dir",
                                                             "{d}/nodir"], {}),
    "coverage report of an empty directory": ("scripts/bench/coverage.py", ["--report-only",
                                                                      "--dat-dir", "{d}/emptydir",
                                                                      "--out", "{d}/cov"], {}),
    "coverage unreadable data": ("scripts/bench/coverage.py", ["--report-only", "--dat-dir",
                                                         "{d}/junkcov", "--out", "{d}/cov"], {}),
    "coverage out is a file": ("scripts/bench/coverage.py", ["--report-only", "--out", "{d}/afile"], {}),
    # the small maintenance tools
    "gen_f24_tables unknown option": ("scripts/flow/gen_f24_tables.py", ["--nope"], {}),
    "gen_gtkw fst without target": ("scripts/flow/gen_gtkw.py", ["--fst", "{d}/junk.fst"], {}),
    "gen_gtkw missing fst": ("scripts/flow/gen_gtkw.py", ["--fst", "{d}/nope.fst", "--target",
                                                     "traverse_harness"], {}),
    "gen_gtkw unreadable fst": ("scripts/flow/gen_gtkw.py", ["--fst", "{d}/junk.fst", "--target",
                                                        "traverse_harness"], {}),
    "gen_gtkw unknown target": ("scripts/flow/gen_gtkw.py", ["--target", "nope"], {}),
    "lint unknown module": ("scripts/flow/lint.py", ["nope_module"], {}),
    "lint unknown option": ("scripts/flow/lint.py", ["--nope"], {}),
    "synth_check log in a file": ("scripts/flow/synth_check.py", ["--log", "{d}/afile/x.log"],
                                  {}),
    "vector_summary unknown option": ("scripts/bench/vector_summary.py", ["--nope"], {}),
    "spdx unknown option": ("scripts/flow/spdx.py", ["--nope"], {}),
    "regs unknown option": ("scripts/flow/regs.py", ["--nope"], {}),
    # pack_frame.py
    "pack_frame no out": ("scripts/pack_frame.py", ["--scene", "rocks"], {}),
    "pack_frame unknown scene": ("scripts/pack_frame.py", ["--scene", "nope", "--out", "{d}/pf"], {}),
    "pack_frame unreadable heightmap": ("scripts/pack_frame.py", ["--heightmap", "{d}/junk.png",
                                                                  "--out", "{d}/pf"], {}),
    "pack_frame approximate method": ("scripts/pack_frame.py", ["--method", "relief", "--out",
                                                                "{d}/pf"], {}),
    "pack_frame unaligned framebuffer": ("scripts/pack_frame.py", ["--size", "8", "--fb-base",
                                                                   "0x70000001", "--out", "{d}/pf"],
                                         {}),
    "pack_frame out is a file": ("scripts/pack_frame.py", ["--size", "8", "--out", "{d}/afile"], {}),
    "animate frames 0": ("scripts/animate.py", ["--frames", "0", "--out", "{d}/an"], {}),
    "animate unknown motion": ("scripts/animate.py", ["--motion", "nope", "--out", "{d}/an"], {}),
    "unit_miter timeout not a number": ("scripts/flow/unit_miter.py", ["--timeout", "x"], {}),
    "unit_miter width out of range": ("scripts/flow/unit_miter.py",
                                      ["--unit", "round_index", "--width", "17"], {}),
    "formal no formal dir": ("scripts/flow/formal.py", ["--root", "{d}/emptydir"], {}),
    "formal jobs 0": ("scripts/flow/formal.py", ["--jobs", "0"], {}),
    "formal unknown task": ("scripts/flow/formal.py", ["--only", "nope_task", "--list"], {}),
    "mutate jobs 0": ("scripts/bench/mutate.py", ["--jobs", "0"], {}),
    "mutate target above 1": ("scripts/bench/mutate.py", ["--target", "2"], {}),
    "mutate missing list": ("scripts/bench/mutate.py", ["--list", "{d}/nope.toml", "--check"], {}),
    "ring_probe bad frame": ("scripts/bench/ring_probe.py", ["--frames", "bump"], {}),
    "ring_probe bad param": ("scripts/bench/ring_probe.py", ["--param", "SLOTS"], {}),
    "ring_queue gap 0": ("scripts/bench/ring_queue.py", ["--gap", "0"], {}),
    "ring_queue unknown scene": ("scripts/bench/ring_queue.py", ["--frames", "nope:oblique"], {}),
    # python -m tb.harness.traverse_system / tb.harness.dm_pipeline
    "traverse_system size not a number": ("-m tb.harness.traverse_system", ["--size", "x"], {}),
    "traverse_system unknown method": ("-m tb.harness.traverse_system", ["--method", "nope", "--size", "8",
                                                          "--rays", "10"],
                                  {}),
    "traverse_system latency 0": ("-m tb.harness.traverse_system", ["--latency", "0", "--size", "8", "--rays",
                                                     "10"],
                             {}),
    "traverse_system size 0": ("-m tb.harness.traverse_system", ["--size", "0", "--rays", "10"],
                          {}),
    "dm_pipeline unknown scene": ("-m tb.harness.dm_pipeline", ["--scene", "nope", "--size", "8"],
                                   {}),
    "dm_pipeline unknown method": ("-m tb.harness.dm_pipeline", ["--method", "nope", "--size", "8"],
                                    {}),
    "dm_pipeline size 0": ("-m tb.harness.dm_pipeline", ["--size", "0"],
                            {}),
    "dm_pipeline unknown variant": ("-m tb.harness.dm_pipeline", ["--variant", "nope"],
                                     {}),
}


def _tool_params() -> list:
    out = []
    for name, (_, _, opts) in TOOL_CASES.items():
        marks = [pytest.mark.xfail(strict=True, reason=opts["xfail"])] if "xfail" in opts else []
        out.append(pytest.param(name, marks=marks, id=name.replace(" ", "-")))
    return out


#: Cases of the model drivers that reach their harness build before failing: run only when the
#: harness is already built (a fresh checkout would otherwise build it here, minutes of work).
#: (dm_pipeline's main checks --scene, --method and --size before its build: its cases always run.)
_AFTER_BUILD = {"traverse_system unknown method", "traverse_system latency 0", "traverse_system size 0"}


@pytest.mark.parametrize("case", _tool_params())
def test_tool_errors(files, case: str) -> None:
    tool, args, _ = TOOL_CASES[case]
    if case in _AFTER_BUILD:
        from tb.harness import traverse_system

        # the variant the tool builds: the one its runs use (checked under this suite's
        # RTL_ENGINE_CHECKED=1)
        if not traverse_system.is_built(traverse_system.default_variant()):
            pytest.skip("the harness is not built (the case would build it first)")
    cmd = tool.split() + [a.format(d=files) for a in args]
    p = run(*cmd)
    text = (p.stdout + "\n" + p.stderr).strip()
    lines = [ln for ln in text.splitlines() if ln.strip()]
    assert "Traceback" not in text, (case, text[-2000:])
    assert p.returncode == 2, (case, p.returncode, text[-2000:])
    assert len(lines) == 1, (case, text[-2000:])


def test_every_tool_has_cases() -> None:
    """Each scripts/**/*.py with a command line (an argument parser) and both model drivers have at
    least one case above: a new tool must add its own."""
    tools = {t for t, _, _ in TOOL_CASES.values()} | {"scripts/trace.py"}
    clis = {p.relative_to(ROOT).as_posix() for p in sorted((ROOT / "scripts").rglob("*.py"))
            if "ArgumentParser(" in p.read_text() or "Parser(prog" in p.read_text()}
    clis |= {"-m tb.harness.traverse_system", "-m tb.harness.dm_pipeline"}
    assert clis - tools == set(), f"tools without error cases: {sorted(clis - tools)}"


_CLIS = sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "scripts").rglob("*.py")
               if "ArgumentParser(" in p.read_text() or "Parser(prog" in p.read_text())


@pytest.mark.parametrize("tool", _CLIS)
def test_help(tool: str) -> None:
    """--help prints the usage and exits 0 (argparse formats help strings with %: a bare % in
    one breaks --help, as it did in synth.py's --router text)."""
    p = run(tool, "--help")
    assert p.returncode == 0, (tool, p.stderr[-2000:])
    assert "usage:" in p.stdout and "Traceback" not in p.stderr
