# SPDX-License-Identifier: Apache-2.0
"""A small compiler cache for Verilator builds (what ``ccache`` does, for a machine without it).

Every testbench build compiles Verilator's runtime (``verilated.cpp``, ``verilated_vpi.cpp``,
``verilated_threads.cpp``, ...) and cocotb's ``verilator.cpp`` again, although their text is the
same in every build: about 20 s of the 30 s a small unit's build takes.  Verilator's makefiles put
``$(OBJCACHE)`` in front of each compiler call, so :mod:`tb.common.runner` and
:mod:`tb.harness.traverse_system` set ``OBJCACHE`` to :data:`COMMAND`::

    <python> tb/common/objcache.py

and this script receives ``<compiler> <arguments...>``.  For a ``-c`` compile it preprocesses the
source with the same arguments (``-E``, dependency options removed) and hashes the compiler's
path and version, the arguments and the preprocessed text.  A hit copies the stored object and
dependency file into place; a miss runs the real compile and stores both.  Anything else (links,
``-E`` calls, several sources, profile-guided compiles) runs unchanged.  The preprocessed text
holds the path of every header it read, so an object is only reused where it was built from the
same files.

The store is ``build/objcache`` (``OBJCACHE_DIR`` overrides it); entries are written to a
temporary name and renamed, so parallel builds (pytest-xdist) can share it.  ``OBJCACHE_STATS=1``
prints ``objcache: hit|miss <object>`` on standard error.
"""
from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
#: The value of OBJCACHE that puts this script in front of Verilator's compiles.
COMMAND = f"{sys.executable} {Path(__file__).resolve()}"
SOURCE_SUFFIXES = (".c", ".cc", ".cpp", ".cxx")
DEP_OPTIONS_WITH_ARG = ("-MF", "-MT", "-MQ")
DEP_OPTIONS = ("-MD", "-MMD", "-MP")


def _plan(argv: list[str]) -> tuple[Path, Path, list[str]] | None:
    """(source, object, preprocess command) of a cacheable compile, else None."""
    if "-c" not in argv or "-E" in argv or any(a.startswith("-fprofile") for a in argv):
        return None  # not a compile, or one that reads profile data the key does not hold
    sources = [a for a in argv[1:] if a.endswith(SOURCE_SUFFIXES) and not a.startswith("-")]
    if len(sources) != 1:
        return None
    source = Path(sources[0])
    out = None
    pre: list[str] = []
    skip = False
    for i, a in enumerate(argv):
        if skip:
            skip = False
            continue
        if a == "-o":
            out = argv[i + 1]
            skip = True
            continue
        if a in DEP_OPTIONS_WITH_ARG:
            skip = True
            continue
        if a in DEP_OPTIONS or a == "-c":
            continue
        pre.append(a)
    obj = Path(out) if out else Path(source.stem + ".o")
    return source, obj, pre + ["-E"]


def _compiler_id(compiler: str) -> bytes:
    """The compiler's resolved path and version line (a new compiler means a new key)."""
    path = shutil.which(compiler) or compiler
    res = subprocess.run([path, "--version"], capture_output=True, check=False)
    return os.path.realpath(path).encode() + b"\0" + res.stdout.split(b"\n", 1)[0]


def _store(src: Path, dst: Path) -> None:
    """Copy ``src`` to ``dst`` through a temporary file in ``dst``'s directory (atomic rename)."""
    fd, tmp = tempfile.mkstemp(dir=dst.parent, prefix=dst.name + ".")
    os.close(fd)
    shutil.copyfile(src, tmp)
    os.replace(tmp, dst)


def main(argv: list[str]) -> int:
    if not argv:
        print("objcache: usage: objcache.py <compiler> <arguments...>", file=sys.stderr)
        return 2
    plan = _plan(argv)
    if plan is None:
        return subprocess.call(argv)
    source, obj, pre = plan
    pp = subprocess.run(pre, capture_output=True, check=False)
    if pp.returncode != 0:  # let the real compile report the error
        return subprocess.call(argv)
    h = hashlib.sha256()
    for part in (_compiler_id(argv[0]), "\0".join(a for a in argv if a != str(obj)).encode(),
                 pp.stdout):
        h.update(part)
        h.update(b"\1")
    key = h.hexdigest()
    store = Path(os.environ.get("OBJCACHE_DIR") or ROOT / "build" / "objcache") / key[:2]
    store.mkdir(parents=True, exist_ok=True)
    cached_obj, cached_dep = store / (key + ".o"), store / (key + ".d")
    dep = obj.with_suffix(".d")
    wants_dep = any(a in DEP_OPTIONS for a in argv)
    stats = os.environ.get("OBJCACHE_STATS") == "1"
    if cached_obj.is_file() and (cached_dep.is_file() or not wants_dep):
        _store(cached_obj, obj)
        if wants_dep:
            _store(cached_dep, dep)
        if stats:
            print(f"objcache: hit {obj}", file=sys.stderr)
        return 0
    rc = subprocess.call(argv)
    if rc == 0 and obj.is_file():
        if wants_dep and dep.is_file():
            _store(dep, cached_dep)
        _store(obj, cached_obj)  # the object last: a present object means a complete entry
        if stats:
            print(f"objcache: miss {obj}", file=sys.stderr)
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
