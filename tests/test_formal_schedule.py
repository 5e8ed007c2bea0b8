# SPDX-License-Identifier: Apache-2.0
"""scripts/flow/formal.py's scheduling and timing: the longest tasks start first (by the process
times of the last run of each task, else by an estimate from the files read and the depth), and
each task's process time and timeout come from run_counted."""
from __future__ import annotations

import importlib.util
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def load_formal():
    """scripts/flow/formal.py as a module."""
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    spec = importlib.util.spec_from_file_location("formal_driver", ROOT / "scripts/flow/formal.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["formal_driver"] = mod          # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod


def test_previous_times_order(tmp_path: Path):
    formal = load_formal()
    (tmp_path / "a.sv").write_text("x" * 40000)
    (tmp_path / "b.sv").write_text("x" * 1000)
    summary = tmp_path / "summary.json"
    summary.write_text(json.dumps({"tasks": [
        {"sby": "s", "task": "prove", "seconds": 9.0, "cpu_seconds": 3.0},
        {"sby": "s", "task": "bmc", "seconds": 50.0},             # an older summary: wall only
    ]}))
    before = formal.previous_times(summary)
    assert before == {("s", "prove"): 3.0, ("s", "bmc"): 50.0}
    tasks = [formal.Task("s", "prove", "prove", ["b.sv"], 2),
             formal.Task("s", "bmc", "bmc", ["b.sv"], 8),
             formal.Task("t", "cover", "cover", ["a.sv"], 20),    # not in the summary: estimated
             formal.Task("u", "cover", "cover", ["b.sv"], 20)]
    est = [formal.estimate(tmp_path, t, before) for t in tasks]
    assert est[0] == 3.0 and est[1] == 50.0
    assert est[2] > est[3] > 0                                   # more to read, longer
    # task_times.json keeps the tasks a run (--only) did not run, with this run's times
    r = formal.Result("t", "cover", "cover", "PASS", 4.0, 2.5, 0, 1, 1, "w")
    formal.save_times(tmp_path / "task_times.json", before, [r])
    assert formal.previous_times(tmp_path / "task_times.json") == {
        ("s", "prove"): 3.0, ("s", "bmc"): 50.0, ("t", "cover"): 2.5}
    assert formal.previous_times(tmp_path / "missing.json") == {}
    (tmp_path / "bad.json").write_text("{")
    assert formal.previous_times(tmp_path / "bad.json") == {}


def test_run_counted_time_and_timeout(tmp_path: Path):
    formal = load_formal()
    env = {"PATH": "/usr/bin:/bin"}
    out, rc, cpu, killed = formal.run_counted(
        [sys.executable, "-c", "import sys; s = sum(range(3_000_000)); print(s); sys.exit(3)"],
        tmp_path, env, 60)
    assert (out.strip(), rc, killed) == (str(sum(range(3_000_000))), 3, False)
    assert cpu > 0.01
    t0 = time.time()
    out, rc, cpu, killed = formal.run_counted(["sleep", "30"], tmp_path, env, 0.5)
    assert killed and rc != 0 and time.time() - t0 < 10


def test_bmc_unproven_runs_the_bmc_of_unproven_files_only(tmp_path: Path, monkeypatch, capsys):
    """--bmc unproven: the prove and cover tasks first; then the bmc tasks of the files one of
    whose prove tasks did not pass, and no other bmc task.  --bmc all runs every task."""
    formal = load_formal()
    ran: list[tuple[str, str]] = []

    def fake(root, out, t, env):  # type: ignore[no-untyped-def]
        ran.append((t.sby, t.name))
        status = "FAIL" if (t.sby, t.mode) == ("skid_buffer", "prove") else "PASS"
        return formal.Result(t.sby, t.name, t.mode, status, 0.0, 0.0, 1, 1, 1, str(tmp_path))

    monkeypatch.setattr(formal, "run_task", fake)
    only = ["--only", "skid_buffer", "--only", "pipe_credit", "--out", "build/formal_sched_test"]
    assert formal.main(["--jobs", "1", "--bmc", "unproven", *only]) == 1
    modes = {n: n.split("_")[0] for _, n in ran}
    bmc = [(s, n) for s, n in ran if modes[n] == "bmc"]
    assert bmc and all(s == "skid_buffer" for s, _ in bmc), ran
    assert ran.index(bmc[0]) > max(i for i, (_, n) in enumerate(ran) if modes[n] != "bmc")
    assert "bmc tasks not run" in capsys.readouterr().out
    ran.clear()
    assert formal.main(["--jobs", "1", *only]) == 1
    assert any(s == "pipe_credit" and n.startswith("bmc") for s, n in ran), ran
