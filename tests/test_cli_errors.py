"""Every command-line tool rejects bad files and arguments with one line and exit status 2."""
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
