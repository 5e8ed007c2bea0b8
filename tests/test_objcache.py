# SPDX-License-Identifier: Apache-2.0
"""tb/common/objcache.py: a compile is reused only for the same compiler, arguments and
preprocessed text; anything else runs the real compiler."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CACHE = ROOT / "tb" / "common" / "objcache.py"
CXX = shutil.which("c++") or shutil.which("g++")

pytestmark = pytest.mark.skipif(CXX is None, reason="no C++ compiler on PATH")


def compile_(tmp: Path, *args: str) -> str:
    env = dict(os.environ, OBJCACHE_DIR=str(tmp / "store"), OBJCACHE_STATS="1")
    p = subprocess.run([sys.executable, str(CACHE), CXX, *args], cwd=tmp, env=env,
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return p.stderr


def test_hit_miss_and_dependencies(tmp_path: Path) -> None:
    (tmp_path / "k.h").write_text("#define K 3\n")
    (tmp_path / "a.cpp").write_text('#include "k.h"\nint f() { return K; }\n')
    args = ["-O1", "-MMD", "-c", "-o", "a.o", "a.cpp"]
    assert "objcache: miss a.o" in compile_(tmp_path, *args)
    first = (tmp_path / "a.o").read_bytes()
    (tmp_path / "a.o").unlink()
    (tmp_path / "a.d").unlink()
    assert "objcache: hit a.o" in compile_(tmp_path, *args)
    assert (tmp_path / "a.o").read_bytes() == first
    assert "k.h" in (tmp_path / "a.d").read_text()       # the dependency file comes back too
    # a changed header, other options: the real compiler again
    (tmp_path / "k.h").write_text("#define K 4\n")
    assert "objcache: miss a.o" in compile_(tmp_path, *args)
    assert (tmp_path / "a.o").read_bytes() != first
    assert "objcache: miss a.o" in compile_(tmp_path, "-O0", "-MMD", "-c", "-o", "a.o", "a.cpp")


def test_other_calls_pass_through(tmp_path: Path) -> None:
    (tmp_path / "m.cpp").write_text("int main() { return 0; }\n")
    assert "objcache" not in compile_(tmp_path, "-o", "m", "m.cpp")          # compile and link
    assert (tmp_path / "m").is_file()
    assert "objcache" not in compile_(tmp_path, "-fprofile-generate", "-c", "m.cpp")
    p = subprocess.run([sys.executable, str(CACHE), CXX, "-c", "missing.cpp"], cwd=tmp_path,
                       env=dict(os.environ, OBJCACHE_DIR=str(tmp_path / "store")),
                       capture_output=True, text=True)
    assert p.returncode != 0 and "missing.cpp" in p.stderr               # the compiler's error
