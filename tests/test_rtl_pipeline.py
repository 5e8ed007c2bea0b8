# SPDX-License-Identifier: Apache-2.0
"""The pipeline RTL as a renderer (tb/harness/dm_pipeline.py: dm_pipeline in the Verilator harness
tb/harness/pipeline_harness.cpp) and ``scripts/render.py --engine rtl`` (what ``make render`` runs).

Small frames through the harness must equal ``model.shade.render_pixels`` with the f24 engine bit
for bit (colour, hit, invalid, iterations), under random AXI latency, fragment gaps, pixel
back-pressure, arready stalls and rvalid bubbles; a user's non-square, odd-sized height map and
texture through render.py; the statistics' keys and their consistency; the AXI error flags; the
watchdogs and the input checks of the harness; bad arguments (one line, exit status 2).

The harness variant is the ``checked`` one (the RTL's SVA assertions on) under the test suite's
``RTL_ENGINE_CHECKED=1`` (tests/conftest.py); its build (about a minute, cached in
build/harness/pipeline/checked) happens once.  Every test here runs on one xdist worker.
"""
from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from model import camera, heightmap, scenes, shade, texture, traverse
from tb.harness import dm_pipeline, pipeline_words
from tb.harness.build import RtlEngineError
from tb.common import report

ROOT = Path(__file__).resolve().parents[1]
RENDER = ROOT / "scripts" / "render.py"

pytestmark = pytest.mark.xdist_group("rtl_pipeline")


@pytest.fixture(scope="module")
def harness() -> Path:
    return dm_pipeline.build(dm_pipeline.default_variant())


def make_frame(name: str, size: int, angle: str, image: int, method: str, mip: bool = True,
               bits: int = 8) -> tuple[shade.Frame, camera.Camera]:
    sc = scenes.load_scene(name, size)
    pyr = heightmap.build(sc.heights, bits)
    tex = texture.build(sc.texture)
    ntex = texture.build(scenes.encode_normals(sc.normals))
    cam = camera.Camera.for_view(angle, size, size, image, image, depth_scale=sc.depth_scale)
    frame = shade.Frame(pyr=pyr, colour=tex, normals=ntex, depth_scale=sc.depth_scale,
                        log2pb_colour=cam.log2_pb(tex.width, tex.height),
                        log2pb_normal=cam.log2_pb(ntex.width, ntex.height),
                        method=method, engine="f24", mip=mip)
    return frame, cam


def mismatches(img: shade.Image, ref: shade.PixelOutputs) -> str:
    bad = dm_pipeline.compare(img.out, ref)
    rows = [f"pixel {i}: rtl {img.out.rgb[i]} h{img.out.hit[i]:d} i{img.out.invalid[i]:d} "
            f"it{img.out.iterations[i]}, model {ref.rgb[i]} h{ref.hit[i]:d} i{ref.invalid[i]:d} "
            f"it{ref.iterations[i]}" for i in bad[:5]]
    return f"{len(bad)} of {len(ref.hit)} pixels differ; " + "; ".join(rows)


#: scene, map side, view, image side, method, MIP, unorm bits, fragment tile, harness knobs
CASES = [
    ("rocks", 32, "oblique", 32, "park", True, 8, 8,
     {"latency": (5, 40), "frag_gap": 0.2, "px_stall": 0.3, "ar_stall": 0.2, "rvalid_gap": 0.2}),
    ("wall", 40, "grazing", 28, "park-xor", True, 16, 1,
     {"h_latency": 1, "t_latency": (30, 90), "px_stall": 0.6}),
    ("four-shapes", 24, "front", 24, "oh", False, 8, 4, {"latency": 20}),
]


@pytest.mark.parametrize("case", range(len(CASES)), ids=[f"{c[0]}-{c[2]}-{c[4]}" for c in CASES])
def test_frame_equals_model(case: int, harness: Path, rng: np.random.Generator) -> None:
    name, size, angle, image, method, mip, bits, tile, knobs = CASES[case]
    frame, cam = make_frame(name, size, angle, image, method, mip, bits)
    img, st = dm_pipeline.render_rtl(frame, cam, tile=tile, seed=int(rng.integers(1 << 31)),
                                     **knobs)
    ref = shade.render(frame, cam)
    report.record("rtl_pipeline (harness)", "pixels vs model.shade f24", len(ref.frags),
                  len(dm_pipeline.compare(img.out, ref.out)))
    assert np.array_equal(img.rgb, ref.rgb), mismatches(img, ref.out)
    assert not len(dm_pipeline.compare(img.out, ref.out)), mismatches(img, ref.out)
    n = len(ref.frags)
    assert st["pixels"] == n and st["errors"] == 0
    assert st["iterations"] == int(ref.out.iterations.sum())
    assert st["hits"] == int(ref.out.hit.sum()) and st["invalid"] == int(ref.out.invalid.sum())
    # every hit reads two quads (colour, normal map); lookups = hits + misses
    assert st["texture_requests"] == 2 * st["hits"]
    # texel-level hits: a hit quad is four; each missed line lookup leaves at least one texel out
    req, th = st["texture_requests"], st["texture_texel_hits"]
    assert 4 * st["texture_quad_hits"] <= th <= 4 * req
    assert st["texture_line_misses"] <= 4 * req - th
    assert st["texture_cache_hit_rate"] == pytest.approx(th / max(4 * req, 1), abs=1e-6)
    # a lookup that hit: an iteration, or a redo of locate's exit check (one per relocation the
    # model counts, at most)
    _, inp = shade.pixel_inputs(cam)
    mst: dict[str, int] = {}
    traverse.trace(frame.pyr, shade.pixel_rays(frame, inp)[0], frame.method, frame.engine,
                   stats=mst)
    assert (st["iterations"] <= st["height_cache_hits"]
            <= st["iterations"] + mst.get("relocate", 0))
    assert st["mem_bytes"] == st["height_mem_bytes"] + st["texture_mem_bytes"]
    assert st["height_mem_bytes"] == st["axi_h_bytes"]
    assert st["texture_mem_bytes"] == st["axi_t_bytes"]
    assert st["axi_h_slverr_beats"] == st["axi_t_slverr_beats"] == 0
    assert st["axi_h_decerr_beats"] == st["axi_t_decerr_beats"] == 0
    assert 0 < st["cycles"] <= st["sim_clocks"]
    assert st["cycles_per_pixel"] == pytest.approx(st["cycles"] / n)


def test_short_reset(harness: Path, rng: np.random.Generator) -> None:
    """A reset of one clock from random register values (the harness's X values follow its seed):
    no assertion fires and the frame is exact.  A stage flag left out of the reset (the traverse
    ring's, before its fix) showed up as a check on a power-up value right after reset."""
    name, size, angle, image, method, mip, bits, tile, knobs = CASES[1]
    frame, cam = make_frame(name, size, angle, image, method, mip, bits)
    ref = shade.render(frame, cam)
    for _ in range(3):
        img, st = dm_pipeline.render_rtl(frame, cam, tile=tile, seed=int(rng.integers(1 << 31)),
                                         reset=1, **knobs)
        assert not len(dm_pipeline.compare(img.out, ref.out)), mismatches(img, ref.out)
        assert st["pixels"] == len(ref.frags) and st["errors"] == 0


def test_every_method(harness: Path, rng: np.random.Generator) -> None:
    """Each exact method once (the method is a run-time input), scenes and views in turn, random
    latency and back-pressure: bit-exact."""
    names = [s for s in scenes.SCENES if s != "rocks"]
    failures = []
    for k, method in enumerate(traverse.EXACT_METHODS):
        name, angle = names[k % len(names)], list(camera.VIEWS)[k % len(camera.VIEWS)]
        frame, cam = make_frame(name, 64, angle, 64, method)
        knobs = {"latency": (1, int(rng.integers(2, 80))), "frag_gap": float(rng.uniform(0, 0.5)),
                 "px_stall": float(rng.uniform(0, 0.7)), "rvalid_gap": float(rng.uniform(0, 0.3)),
                 "seed": int(rng.integers(1 << 31))}
        img, st = dm_pipeline.render_rtl(frame, cam, tile=int(rng.integers(1, 17)), **knobs)
        ref = shade.render(frame, cam)
        bad = len(dm_pipeline.compare(img.out, ref.out))
        report.record("rtl_pipeline (harness)", "pixels vs model.shade f24", len(ref.frags), bad)
        if bad or st["pixels"] != len(ref.frags):
            failures.append(f"{name} {angle} {method} {knobs}: {mismatches(img, ref.out)}")
    assert not failures, "\n".join(failures)


def test_axi_errors_flag_exactly_the_pixels_that_read(harness: Path) -> None:
    """SLVERR on the whole pyramid: a pixel whose ray reads a height comes back with err, no hit
    and the miss colour; SLVERR on the textures: exactly the hits come back with err."""
    frame, cam = make_frame("bump", 16, "oblique", 16, "park")
    fi = dm_pipeline.frame_image(frame)
    _, inp = shade.pixel_inputs(cam)
    words = dm_pipeline.fragment_words(inp)
    ref = shade.render_pixels(frame, inp)
    h_base, h_img = fi.cfg.height
    px, st = dm_pipeline.run_pixels(fi, words, latency=(3, 30),
                                    h_err=[(h_base, h_base + len(h_img))])
    reads = ref.iterations > 0
    assert np.array_equal(px.err, reads) and not px.hit.any() and not px.iterations.any()
    assert (px.rgb == shade.MISS_COLOUR).all() and np.array_equal(px.invalid, ref.invalid)
    assert st["errors"] == int(reads.sum()) and st["axi_h_slverr_beats"] > 0
    px, st = dm_pipeline.run_pixels(fi, words,
                                    t_err=[(fi.tex_base, fi.tex_base + len(fi.tex_image))])
    assert np.array_equal(px.err, ref.hit) and np.array_equal(px.hit, ref.hit)
    assert np.array_equal(px.iterations, ref.iterations) and st["axi_t_slverr_beats"] > 0


def test_watchdogs_fail_loudly(harness: Path) -> None:
    frame, cam = make_frame("rocks", 16, "grazing", 16, "oh")
    fi = dm_pipeline.frame_image(frame)
    _, inp = shade.pixel_inputs(cam)
    words = dm_pipeline.fragment_words(inp)
    with pytest.raises(RtlEngineError,
                       match=r"(?s)exit status 2: .*no pixel came out for 20 clocks"):
        dm_pipeline.run_pixels(fi, words, stall=20)
    with pytest.raises(RtlEngineError, match=r"(?s)exit status 2: .*timeout 300 clocks"):
        dm_pipeline.run_pixels(fi, words, timeout=300)


def test_input_file_checks(harness: Path, tmp_path: Path) -> None:
    """The file layout of pipeline_harness.h, and the harness refusing a damaged file."""
    frame, cam = make_frame("dent", 8, "front", 6, "park")
    fi = dm_pipeline.frame_image(frame)
    _, inp = shade.pixel_inputs(cam)
    words = dm_pipeline.fragment_words(inp)
    path = tmp_path / "in.bin"
    dm_pipeline.write_input(path, fi, words)
    raw = path.read_bytes()
    head = np.frombuffer(raw[:64], dtype="<u4")
    assert raw[:8] == b"PIPHIN01" and list(head[2:5]) == [2, 64, len(dm_pipeline.CFG_PORTS)]
    assert head[7] == len(words) and head[8] == pipeline_words.HEIGHT_BASE
    assert head[9] == len(fi.cfg.height[1]) and head[10] == fi.tex_base
    assert head[11] == len(fi.tex_image) and head[12] == 16
    # the level-table writes follow the triangle table's: the height level offsets, both
    # textures' offsets and sizes
    assert head[13] == len(fi.cfg.lvt_writes) == 5 * pipeline_words.TEX_LEVELS
    at = 64 + 4 * int(head[5]) + 8 * int(head[6])
    lvt = np.frombuffer(raw[at:at + 8 * int(head[13])], dtype="<u4").reshape(-1, 2)
    assert [tuple(int(x) for x in w) for w in lvt] == fi.cfg.lvt_writes
    cfg = np.frombuffer(raw[64:64 + 4 * int(head[5])], dtype="<u4")
    assert cfg[0] == 4 and cfg[1] == fi.cfg.ports["cfg_method_i"]   # first port: bits, value
    assert raw.endswith(words.astype("<u4").tobytes())
    # the fragment words are the cocotb test's (tb.harness.pipeline_words.fragment_words)
    ref = pipeline_words.fragment_words(inp)
    assert np.array_equal(words[:, 0], ref["frag_u0_i"])
    assert np.array_equal(words[:, 3], ref["frag_tri_i"])
    for k in range(len(words)):
        assert pipeline_words.pack(words[k, 4:13], 24) == ref["frag_tbn_i"][k]
        assert pipeline_words.pack(words[k, 13:16], 24) == ref["frag_view_i"][k]
    cases = {"short fragment list": raw[:-4], "trailing bytes": raw + b"\0\0\0\0",
             "bits in the file": raw[:64] + (5).to_bytes(4, "little") + raw[68:],
             "not a pipeline harness input": b"X" + raw[1:]}
    for msg, data in cases.items():
        path.write_bytes(data)
        p = subprocess.run([str(harness), "--in", str(path), "--out", str(tmp_path / "o.bin")],
                           capture_output=True, text=True)
        assert p.returncode == 1 and msg in p.stderr, (msg, p.stderr)


def test_limits_are_one_line_errors() -> None:
    frame, _ = make_frame("bump", 8, "front", 8, "park")
    big = texture.Texture([np.zeros((1, 1, 4), np.uint8)] * (pipeline_words.TEX_LEVELS + 1))
    for fr, msg in ((shade.Frame(**{**frame.__dict__, "method": "relief", "engine": "f64"}),
                     "has no RTL"),
                    (shade.Frame(**{**frame.__dict__, "colour": big}), "MIP levels")):
        with pytest.raises(dm_pipeline.RtlLimitError, match=msg) as e:
            dm_pipeline.check_limits(fr)
        assert "\n" not in str(e.value)


# ---- scripts/render.py --engine rtl -------------------------------------------------------------

def write_png(path: Path, a: np.ndarray, u16: bool = False) -> None:
    import OpenImageIO as oiio

    a = np.ascontiguousarray(a)
    ch = 1 if a.ndim == 2 else a.shape[2]
    out = oiio.ImageOutput.create(str(path))
    assert out is not None
    assert out.open(str(path), oiio.ImageSpec(a.shape[1], a.shape[0], ch,
                                              oiio.UINT16 if u16 else oiio.UINT8))
    assert out.write_image(a)
    out.close()


def read_png(path: Path) -> np.ndarray:
    import OpenImageIO as oiio

    return np.asarray(oiio.ImageBuf(str(path)).get_pixels(oiio.UINT8))


def test_render_user_heightmap(harness: Path, tmp_path: Path, rng: np.random.Generator) -> None:
    """A 16-bit PNG height map of 23 x 41 texels and a 13 x 9 texture through render.py: RTL and
    model identical, the statistics of CONVENTIONS present and consistent."""
    h = scenes.height("stones", (23, 41))
    write_png(tmp_path / "h.png", np.rint(h * 65535).astype(np.uint16), u16=True)
    write_png(tmp_path / "t.png", rng.integers(0, 256, (9, 13, 3), dtype=np.uint8))
    out, mout, st = tmp_path / "r.png", tmp_path / "m.png", tmp_path / "s.json"
    p = subprocess.run([sys.executable, str(RENDER), "--engine", "rtl", "--heightmap",
                        str(tmp_path / "h.png"), "--texture", str(tmp_path / "t.png"),
                        "--angle", "30", "--method", "park-gpu", "--size", "36",
                        "--latency", "2:60", "--seed", "7", "--out", str(out),
                        "--model-out", str(mout), "--stats", str(st)],
                       capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    d = json.loads(st.read_text())
    for k in ("pixels", "cycles", "iterations", "identical", "height_cache_hit_rate",
              "texture_cache_hit_rate", "mem_bytes", "cycles_per_pixel", "iterations_per_pixel",
              "bytes_per_pixel", "harness_wall_seconds", "mpixels_per_second", "clock_mhz",
              "clock_source"):
        assert k in d, k
    assert d["identical"] is True and d["mismatches"] == 0 and d["map"] == [23, 41]
    assert d["pixels"] == d["covered_pixels"] == d["model"]["covered_pixels"] > 0
    assert d["iterations"] == d["model"]["iterations"] and d["hits"] == d["model"]["hits"]
    assert d["cycles_per_pixel"] == pytest.approx(d["cycles"] / d["pixels"], abs=1e-4)
    assert d["bytes_per_pixel"] == pytest.approx(d["mem_bytes"] / d["pixels"], abs=1e-4)
    assert 0 <= d["height_cache_hit_rate"] <= 1 and 0 <= d["texture_cache_hit_rate"] <= 1
    assert d["mpixels_per_second"] == pytest.approx(d["clock_mhz"] / d["cycles_per_pixel"],
                                                    rel=1e-3)
    a, b = read_png(out), read_png(mout)
    assert a.shape == (36, 36, 3) and np.array_equal(a, b)
    assert "identical" in p.stdout and "Mpixels/s" in p.stdout


def _render_main():
    spec = importlib.util.spec_from_file_location("render_script_rtl", RENDER)
    mod = importlib.util.module_from_spec(spec)
    assert spec.loader is not None
    spec.loader.exec_module(mod)
    return mod.main


def test_render_bad_arguments_exit_2_one_line(tmp_path: Path, capsys: pytest.CaptureFixture,
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    main = _render_main()
    np.save(tmp_path / "h.npy", np.random.default_rng(0).random((9, 7)))
    write_png(tmp_path / "t.png", np.zeros((20, 20, 3), np.uint8))
    cases = [
        (["--method", "relief"], "has no pipeline RTL"),
        (["--method", "pom", "--engine", "rtl"], "has no pipeline RTL"),
        (["--latency", "0"], "--latency"),
        (["--latency", "9:3"], "--latency"),
        (["--latency", "x"], "--latency"),
        (["--rtl-tile", "0"], "--rtl-tile"),
        (["--seed", "-1"], "--seed"),
        (["--clock-mhz", "fast"], "--clock-mhz"),
        (["--out", str(tmp_path / "same.png"), "--model-out", str(tmp_path / "same.png")],
         "same file"),
        (["--engine", "f24", "--model-out", str(tmp_path / "m.png")], "goes with --engine rtl"),
        # beyond the RTL's configuration (the limit lowered to reach it with a small file)
        (["--heightmap", str(tmp_path / "h.npy"), "--texture", str(tmp_path / "t.png")],
         "the pipeline RTL cannot render this: texture 20 x 20"),
    ]
    monkeypatch.setattr(dm_pipeline, "MAX_TEX_SIDE", 16)
    for args, msg in cases:
        argv = ["--engine", "rtl", "--size", "8", "--stats", str(tmp_path / "s.json"), "--quiet"]
        argv = ([a for a in argv if a not in ("--engine", "rtl")] if "--engine" in args else argv)
        argv += args
        if "--out" not in args:
            argv += ["--out", str(tmp_path / "o.png")]
        with pytest.raises(SystemExit) as ei:
            main(argv)
        err = capsys.readouterr().err.strip().splitlines()
        assert ei.value.code == 2 and len(err) == 1 and msg in err[0], (args, err)


def test_render_reports_a_difference(tmp_path: Path, capsys: pytest.CaptureFixture,
                                     monkeypatch: pytest.MonkeyPatch) -> None:
    """An RTL configured with another miss colour than the model's: render.py exits 1, names the
    count and the first pixels, and the statistics say identical false."""
    main = _render_main()
    real = dm_pipeline.frame_image

    def other_miss_colour(frame: shade.Frame) -> dm_pipeline.FrameImage:
        fi = real(frame)
        fi.cfg.ports["cfg_miss_rgb_i"] = 0x030201
        return fi

    monkeypatch.setattr(dm_pipeline, "frame_image", other_miss_colour)
    st = tmp_path / "s.json"
    rc = main(["--engine", "rtl", "--scene", "rocks", "--map-size", "16", "--angle", "grazing",
               "--size", "16", "--out", str(tmp_path / "r.png"), "--model-out",
               str(tmp_path / "m.png"), "--stats", str(st), "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    d = json.loads(st.read_text())
    misses = d["covered_pixels"] - d["hits"]
    assert rc == 1 and misses > 0 and d["identical"] is False and d["mismatches"] == misses
    assert len(err) == 1 and f"differ in {misses} of {d['covered_pixels']} pixels" in err[0]
    assert "rtl rgb (1, 2, 3)" in err[0] and "model rgb (0, 0, 0)" in err[0]


def test_clock_from_synthesis_report(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Mpixels/s are quoted at out/synth/report.json's top fmax when there is one, else (with no
    committed routed result) at the paper's 84 MHz, labelled as assumed."""
    from tb.harness import dm_pipeline as mod

    rep = tmp_path / "report.json"
    monkeypatch.setattr(mod, "SYNTH_REPORT", rep)
    monkeypatch.setattr(mod, "ROUTED_RESULTS", tmp_path / "none.json")
    assert mod.synth_clock() is None
    assert mod.pipeline_clock() == (84.0, mod.pipeline_clock()[1])
    assert "assumed" in mod.pipeline_clock()[1]
    rep.write_text(json.dumps({"top": "dm_pipeline_fpga_top", "fmax_mhz": 61.25,
                               "settings": {"device_name": "LFE5U-85F"}, "blocks": {}}))
    mhz, src = mod.synth_clock()
    assert mhz == 61.25 and "dm_pipeline_fpga_top" in src and "LFE5U-85F" in src
    assert mod.pipeline_clock() == (mhz, src)
    rep.write_text(json.dumps({"top": "dm_pipeline_fpga_top", "blocks": {}}))  # no P&R yet
    assert mod.synth_clock() is None
    # the top not placed: the slowest pipeline block out of context bounds the clock (blocks
    # outside the pipeline, like f24_sqrt, do not count)
    rep.write_text(json.dumps({"top": "dm_pipeline_fpga_top", "fmax_mhz": None,
                               "blocks": {"view_calc": {"fmax_mhz": 17.0},
                                          "tex_filter": {"fmax_mhz": 63.3},
                                          "f24_sqrt": {"fmax_mhz": 9.0},
                                          "shade_unit": {"lut": 5}}}))
    mhz, src = mod.synth_clock()
    assert mhz == 17.0 and "view_calc" in src and "out of context" in src
    assert mod.pipeline_clock() == (mhz, src)     # no committed routed result either
    rep.write_text("[1, 2]")
    assert mod.synth_clock() is None


def test_clock_from_committed_routed_result(tmp_path: Path,
                                            monkeypatch: pytest.MonkeyPatch) -> None:
    """Without a local routed top, Mpixels/s are quoted at the committed routed fmax of the
    one-pipeline top (docs/results/synth-ecp5.json), which names its run; a local report with
    the top routed comes first, a local report's bound from the blocks after it."""
    from tb.harness import dm_pipeline as mod

    monkeypatch.setattr(mod, "SYNTH_REPORT", tmp_path / "report.json")
    # the committed file: its fmax, read from the file (not written here)
    doc = json.loads(mod.ROUTED_RESULTS.read_text())
    top = next(t for t in doc["tops"] if t["name"] == "dm_pipeline_fpga_top" and t["rings"] == 1)
    mhz, src = mod.pipeline_clock()
    assert mhz == top["fmax_mhz"] and "docs/results/synth-ecp5.json" in src
    assert "routed" in src and f"seed {top['seed']}" in src and top["rtl_commit"] in src
    # another file: a two-ring entry and a broken one are passed over
    res = tmp_path / "routed.json"
    monkeypatch.setattr(mod, "ROUTED_RESULTS", res)
    res.write_text(json.dumps({"tops": [
        {"name": "dm_pipeline_fpga_top", "rings": 2, "fmax_mhz": 40.0},
        {"name": "dm_pipeline_fpga_top", "rings": 1, "fmax_mhz": "x"},
        {"name": "dm_pipeline_fpga_top", "rings": 1, "fmax_mhz": 57.5, "seed": 3}]}))
    mhz, src = mod.pipeline_clock()
    assert mhz == 57.5 and "seed 3" in src
    (tmp_path / "report.json").write_text(json.dumps({"top": "dm_pipeline_fpga_top",
                                                      "fmax_mhz": None,
                                                      "blocks": {"view_calc": {"fmax_mhz": 17.0}}}))
    assert mod.pipeline_clock()[0] == 57.5      # the routed top beats a bound from the blocks
    (tmp_path / "report.json").write_text(json.dumps({"top": "dm_pipeline_fpga_top",
                                                      "fmax_mhz": 61.0, "blocks": {}}))
    assert mod.pipeline_clock()[0] == 61.0      # a local routed top beats the committed one
    res.write_text(json.dumps({"tops": []}))
    (tmp_path / "report.json").unlink()
    assert "assumed" in mod.pipeline_clock()[1] and mod.pipeline_clock()[0] == mod.PAPER_MHZ


def test_bench_pipeline(harness: Path, tmp_path: Path) -> None:
    """scripts/bench/bench_pipeline.py on two small frames (MIP on and off): both identical to the
    model, the figures consistent with their definitions, the targets listed; bad arguments
    exit 2 with one line."""
    bench = ROOT / "scripts" / "bench" / "bench_pipeline.py"
    out, md = tmp_path / "b.json", tmp_path / "b.md"
    p = subprocess.run([sys.executable, str(bench), "--scenes", "bump", "--views", "oblique",
                        "--mip", "on,off", "--map", "32", "--image", "40", "--jobs", "1",
                        "--out", str(out), "--md", str(md)],
                       capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    d = json.loads(out.read_text())
    assert [c["mip"] for c in d["cases"]] == [True, False]
    for c in d["cases"]:
        assert c["mismatches"] == 0 and c["pixels"] > 0
        assert c["cycles_per_iteration"] == pytest.approx(c["cycles"] / c["iterations"])
        assert c["bytes_per_pixel"] == pytest.approx(c["height_bytes_per_pixel"]
                                                     + c["texture_bytes_per_pixel"])
        assert 0 < c["texture_quad_hit_rate"] <= c["texture_cache_hit_rate"] <= 1
        # a cold cache fills every line the rays touch at least once
        assert c["height_line_bytes"] == 32 and c["height_lines_touched"] > 0
        assert c["height_fills_per_bound"] >= 1.0
        assert c["height_reads_served"] <= c["height_served_bound"] < 1.0
    # the same rays either way: MIP changes only the texture path
    on, off = d["cases"]
    assert on["iterations"] == off["iterations"] and on["pixels"] == off["pixels"]
    assert d["summary"]["mismatches"] == 0 and len(d["targets"]) == 4
    assert "| bump | oblique | on |" in md.read_text()
    for bad in (["--scenes", "nosuch"], ["--mip", "maybe"], ["--image", "0"],
                ["--method", "relief"]):
        p = subprocess.run([sys.executable, str(bench), *bad], capture_output=True, text=True,
                           cwd=ROOT)
        assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, (bad, p.stderr)
