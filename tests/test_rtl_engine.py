# SPDX-License-Identifier: Apache-2.0
"""The RTL engine (tb/harness/traverse_system.py: traverse_system in the Verilator harness) against the golden
model, bit for bit: model.traverse.trace(pyr, rays, method, "f24") must give the same t, u, v, hit,
invalid and iterations, and the unit's statistics must match the model's per-action counts.

Batches of a few thousand adversarial rays (tests/test_traverse.py) on a 64x64 map and a
non-square unorm16 map, for several methods, with random AXI latency, ray-stream gaps and result
back-pressure, the pyramid at aligned and unaligned addresses; plus the AXI error path and the
harness's timeout.  The harness build (about half a
minute, cached in build/harness/fast) happens once; every test here runs on one xdist worker.

Skipped (with the reason) only while rtl/cache/height_cache.sv does not exist.
"""
from __future__ import annotations

import numpy as np
import pytest

from model import f24, heightmap, scenes, traverse
from model.rays import Rays
from tb.common.traverse_stimulus import adversarial_rays, height_field
from tb.harness import traverse_system

pytestmark = [
    pytest.mark.xdist_group("rtl_engine"),
    pytest.mark.skipif(not traverse_system.cache_available(),
                       reason="rtl/cache/height_cache.sv does not exist yet: traverse_system needs "
                              "the height cache"),
]

#: (height, width, unorm bits, height-field kind, methods, latency, back-pressure, base address)
CASES = [
    (64, 64, 8, 0, ("oh", "park", "park-xor", "drobot"), (10, 40), 0.0, traverse_system.DEFAULT_BASE),
    (37, 100, 16, 2, ("tevs", "multi-down", "selective", "park-gpu"), (1, 60), 0.15, 0x1234_5672),
    (64, 64, 8, 1, ("start-level", "coherent"), 20, 0.05, 0),
]
NRAYS = 3000


@pytest.fixture(scope="module")
def harness() -> None:
    traverse_system.build("checked")


def bits_equal(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """float64 values equal bit for bit (so -0 != +0; NaN == NaN as the model writes it)."""
    return np.ascontiguousarray(a).view(np.uint64) == np.ascontiguousarray(b).view(np.uint64)


@pytest.mark.parametrize("case", range(len(CASES)), ids=[f"{c[0]}x{c[1]}u{c[2]}k{c[3]}"
                                                         for c in CASES])
def test_rtl_equals_model(case: int, harness: None, rng: np.random.Generator) -> None:
    hh, ww, bits, kind, methods, latency, bp, base = CASES[case]
    pyr = heightmap.build(height_field(rng, hh, ww, kind), bits)
    rays = adversarial_rays(rng, ww, hh, NRAYS)
    failures = []
    for method in methods:
        st_model: dict[str, int] = {}
        ref = traverse.trace(pyr, rays, method, "f24", stats=st_model)
        res, st = traverse_system.trace_rtl(pyr, rays, method, latency=latency,
                                            seed=int(rng.integers(1 << 31)), backpressure=bp,
                                            base=base)
        bad = ~(bits_equal(res.t, ref.t) & bits_equal(res.u, ref.u) & bits_equal(res.v, ref.v) &
                (res.hit == ref.hit) & (res.invalid == ref.invalid) &
                (res.iterations == ref.iterations))
        for i in np.nonzero(bad)[0][:5]:
            failures.append(
                f"{method} ray {i}: rtl hit={res.hit[i]} inv={res.invalid[i]} "
                f"it={res.iterations[i]} t={res.t[i]!r} u={res.u[i]!r} v={res.v[i]!r}; model "
                f"hit={ref.hit[i]} inv={ref.invalid[i]} it={ref.iterations[i]} t={ref.t[i]!r} "
                f"u={ref.u[i]!r} v={ref.v[i]!r}")
        if bad.any():
            failures.append(f"{method}: {int(bad.sum())} of {len(rays)} rays differ")
        iters = int(ref.iterations.sum())
        want = {"rays": len(rays), "rays_in": len(rays), "rays_out": len(rays),
                "iterations": iters, "stat_iterations": iters, "errors": 0, "capped": 0,
                "descents": st_model.get("down", 0), "crossings": st_model.get("cross", 0),
                "level_ups": st_model.get("up", 0), "hits": int(ref.hit.sum()),
                "invalid": int(ref.invalid.sum())}
        for k, v in want.items():
            if st[k] != v:
                failures.append(f"{method}: stats {k} = {st[k]}, expected {v}")
        if not (st["cycles"] > 0 and st["mem_bytes"] > 0 and st["lookups"] >= iters
                and st["height_cache_hits"] + st["height_cache_misses"] == st["lookups"]
                and st["mem_bytes"] == st["axi_bytes"] and st["axi_slverr_beats"] == 0
                and st["axi_decerr_beats"] == 0):
            failures.append(f"{method}: implausible stats {st}")
    assert not failures, "\n".join(failures)


def test_axi_errors_finish_rays_with_err(harness: None, rng: np.random.Generator) -> None:
    """SLVERR on every read: a ray that reads a height finishes with err, no hit, 0 iterations."""
    pyr = heightmap.build(height_field(rng, 32, 32, 0), 8)
    rays = adversarial_rays(rng, 32, 32, 400)
    ref = traverse.trace(pyr, rays, "park", "f24")
    base = traverse_system.DEFAULT_BASE
    out, st = traverse_system.run_batch(pyr, rays, "park", latency=(5, 30), seed=3,
                                        err_ranges=[(base, base + len(pyr.memory_image()))])
    res = traverse_system.to_result(out)
    err = (out["flags"] & traverse_system.FLAG_ERR) != 0
    reads = ref.iterations > 0
    assert np.array_equal(err, reads), "err flag on exactly the rays that read a height"
    assert not res.hit.any() and not res.iterations.any()
    assert np.array_equal(res.invalid, ref.invalid)
    assert st["errors"] == int(reads.sum()) and st["axi_slverr_beats"] > 0


def test_harness_timeout_fails_loudly(harness: None, rng: np.random.Generator) -> None:
    pyr = heightmap.build(height_field(rng, 16, 16, 0), 8)
    rays = adversarial_rays(rng, 16, 16, 100)
    with pytest.raises(traverse_system.RtlEngineError, match="timeout"):
        traverse_system.trace_rtl(pyr, rays, "oh", timeout=50)


def test_input_file_layout(tmp_path) -> None:
    """The input file the harness reads: header fields, image, f24 ray words (traverse_harness.h)."""
    pyr = heightmap.build(np.arange(12).reshape(3, 4) / 11.0, 16)
    rays = adversarial_rays(np.random.default_rng(0), 4, 3, 16)
    traverse_system.write_input(tmp_path / "in.bin", pyr, rays, "park-xor", base=0x1000)
    raw = (tmp_path / "in.bin").read_bytes()
    head = np.frombuffer(raw[:128], dtype="<u4")
    img = pyr.memory_image()
    assert raw[:8] == b"TRVHIN01" and head[2] == 1 and head[3] == 128
    assert list(head[4:14]) == [traverse.METHOD_CODES["park-xor"], 4, 3, 2, 1, 0x1000,
                                int(pyr.levels[2][0, 0]), traverse.iteration_cap(pyr), 16, len(img)]
    assert list(head[14:14 + pyr.n + 1]) == pyr.level_offsets() and not head[14 + pyr.n + 1:].any()
    pad = -len(img) % 4
    assert raw[128:128 + len(img)] == img
    words = np.frombuffer(raw[128 + len(img) + pad:], dtype="<u4").reshape(-1, 4)
    with np.errstate(invalid="ignore"):
        assert np.array_equal(words[:, 0], f24.from_float(rays.u0))
        assert np.array_equal(words[:, 3], f24.from_float(rays.dv))


def test_bench_rtl_small(harness: None, tmp_path) -> None:
    """scripts/bench/bench_rtl.py end to end on a small map: JSON and table written, RTL == f24 engine,
    cold-run statistics consistent with the definitions in its docstring."""
    import json
    import subprocess
    import sys

    out, md = tmp_path / "rtl.json", tmp_path / "rtl.md"
    p = subprocess.run([sys.executable, str(traverse_system.ROOT / "scripts" / "bench" / "bench_rtl.py"),
                        "--scenes", "bump", "--angles", "oblique,grazing", "--methods", "park",
                        "--size", "32", "--image", "24", "--tile", "4",
                        "--out", str(out), "--md", str(md)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    d = json.loads(out.read_text())
    assert d["mismatches"] == 0 and len(d["rows"]) == 2
    for r in d["rows"]:
        for key in ("cold", "warm"):
            c = r[key]
            assert c["iterations"] == r["iterations"] and c["mismatches"] == 0
            # a lookup that hit: an iteration, or a redo of locate's exit check (one per
            # relocation at most)
            assert c["iterations"] <= c["height_cache_hits"] <= c["iterations"] + r["relocations"]
            assert r[f"clk_per_iter_{key}"] == pytest.approx(c["cycles"] / c["iterations"])
        # a 32x32 pyramid (1,408 bytes) fits the cache: the warm run reads nothing from memory
        assert r["warm"]["mem_bytes"] == 0 and r["cold"]["mem_bytes"] > 0
    assert "| bump | oblique | park |" in md.read_text()


def test_bench_rtl_rejects_bad_arguments() -> None:
    import subprocess
    import sys

    for args, msg in ((["--scenes", "nope"], "unknown scene 'nope'"),
                      (["--methods", "relief"], "unknown method 'relief'"),
                      (["--tile", "0"], "--tile must be >= 1")):
        p = subprocess.run([sys.executable, str(traverse_system.ROOT / "scripts" / "bench" / "bench_rtl.py"),
                            *args], capture_output=True, text=True)
        assert p.returncode == 2 and msg in p.stderr and len(p.stderr.strip().splitlines()) == 1


def test_harness_spec_params() -> None:
    """traverse_system.spec: no params -> the default builds unchanged; params -> a build of its own
    whose directory names the settings away from the defaults, with the parameters passed on."""
    assert traverse_system.spec() is traverse_system.TRAVERSE
    assert traverse_system.spec(park=True) is traverse_system.TRAVERSE_PARK
    s = traverse_system.spec(park=True, params={"MSHRS": 16, "AXI_ID_W": 6, "PARK_WAIT": 32})
    assert s.params == {**traverse_system.PARK_PARAMS, "MSHRS": 16, "AXI_ID_W": 6, "PARK_WAIT": 32}
    assert s.build_dir.name == "traverse_axi_id_w6_mshrs16_park1_park_wait32"
    assert s.build_dir not in (traverse_system.TRAVERSE.build_dir,
                               traverse_system.TRAVERSE_PARK.build_dir)
    s8 = traverse_system.spec(params={"MSHRS": 8})
    assert "PARK" not in s8.params and s8.build_dir.name == "traverse_mshrs8"


def test_harness_waves_fst(tmp_path, rng: np.random.Generator) -> None:
    """trace_rtl(..., waves=FILE) writes an FST that a reader decodes (pywellen): the clock
    toggles every half period, the ray and AXI handshakes are visible, and the results are
    still the f24 engine's."""
    import pywellen

    pyr = heightmap.build(height_field(rng, 16, 16, 0), 8)
    rays = adversarial_rays(rng, 16, 16, 40)
    fst = tmp_path / "w.fst"
    res, st = traverse_system.trace_rtl(pyr, rays, "park", latency=5, waves=fst)
    ref = traverse.trace(pyr, rays, "park", "f24")
    assert np.array_equal(res.iterations, ref.iterations) and np.array_equal(res.hit, ref.hit)
    w = pywellen.Waveform(str(fst))
    assert w.file_format == "FST"
    names = {v.full_name: v for v in w.all_vars()}
    top = [n for n in names if n.endswith("traverse_system.clk_i")]
    assert top, "no traverse_system scope in the waves"
    scope = top[0][: -len("clk_i")]
    clk = names[scope + "clk_i"].signal
    steps = 2 * st["sim_clocks"]
    assert [clk.value_at(t) for t in range(2, 12)] == [0, 1] * 5
    arvalid = names[scope + "m_axi_arvalid"].signal
    assert any(arvalid.value_at(t) == 1 for t in range(0, steps, 2))
    assert any(n.startswith(scope + "u_unit.u_loop.") for n in names)


def test_ray_steps_waves_state(tmp_path) -> None:
    """scripts/ray_steps.py --waves (the README's walk through one ray): the RTL reads the
    model's addresses and codes in order, and S1's ring registers hold each row's level, cell, t
    and iteration - 1 at the row's lookup; compare_states names a row that differs."""
    import subprocess
    import sys

    from scripts import ray_steps

    fst = tmp_path / "ray.fst"
    p = subprocess.run([sys.executable, str(traverse_system.ROOT / "scripts" / "ray_steps.py"),
                        "--scene", "rocks", "--map-size", "64", "--ray", "10.3", "20.7", "3.1",
                        "-2.2", "--method", "park", "--waves", str(fst)],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert "identical to the model" in p.stdout
    assert "lookups: the RTL reads the model's addresses and codes in order" in p.stdout
    assert "t_q[1] and stat_q[1].iters hold the row's level, cell, t and iteration - 1" \
        in p.stdout and p.stdout.split("state: ")[1].splitlines()[0].endswith(": yes")
    looks = ray_steps.rtl_lookups(fst)
    states = ray_steps.ring_states(fst, looks)
    assert states is not None and [s["iters"] for s in states] == list(range(len(states)))
    rows = [{"iteration": i + 1, "level": s["level"], "cx": s["cx"], "cy": s["cy"],
             "t": float(f24.to_float(np.array([s["t"]], dtype=np.uint32))[0])}
            for i, s in enumerate(states)]
    assert ray_steps.compare_states(rows, states) is None
    rows[-1]["cx"] += 1
    assert f"iteration {len(rows)}" in ray_steps.compare_states(rows, states)


def test_ray_steps_waves_redo(tmp_path) -> None:
    """A ray whose descent's locate moves its estimate one cell on (found by the model's
    `relocate` count): the ring reads the estimate once more before the next iteration (the
    redo of locate's exit check), and ray_steps' expected reads, checked against the waves,
    have that read in its place."""
    import subprocess
    import sys

    from scripts import ray_steps

    ray = ("10.3", "43.9", "-16.5", "20.5")
    pyr = heightmap.build(scenes.load_scene("rocks", 64).heights)
    rays = Rays(*(np.array([float(x)]) for x in ray))
    st: dict[str, int] = {}
    res = traverse.trace(pyr, rays, "park", "f24", stats=st)
    assert st.get("relocate") == 1, st
    fst = tmp_path / "redo.fst"
    p = subprocess.run([sys.executable, str(traverse_system.ROOT / "scripts" / "ray_steps.py"),
                        "--scene", "rocks", "--map-size", "64", "--ray", *ray, "--method", "park",
                        "--waves", str(fst)], capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "identical to the model" in p.stdout
    assert "lookups: the RTL reads the model's addresses and codes in order" in p.stdout
    assert p.stdout.split("state: ")[1].splitlines()[0].endswith(": yes")
    assert "= the redo before iteration 7 (locate's exit check)" in p.stdout
    # the RTL's lookups against the model's rows: the redo reads the estimate right after the
    # descent's lookup; without it in the expected reads, the lookups differ there
    rec, _, _ = ray_steps.steps(pyr, rays, "park", "f24", ray_steps.DEFAULT_BASE)
    looks = ray_steps.rtl_lookups(fst)
    assert len(rec) == int(res.iterations[0])
    reads = ray_steps.expected_reads(rec)
    assert ray_steps.compare_lookups(reads, looks) is None
    redo = next(r for r in reads if r.get("redo"))
    redo["address"] -= 1  # (the corrected cell, one on towards -u: read without the redo)
    assert "the redo before iteration 7" in ray_steps.compare_lookups(reads, looks)
