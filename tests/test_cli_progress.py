# SPDX-License-Identifier: Apache-2.0
"""model.cli.Progress writes its progress line only to a terminal: a log file or a pipe gets none."""
from __future__ import annotations

import io
import sys

import pytest

from model.cli import Progress


class _Tty(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_no_progress_when_not_a_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    err = io.StringIO()
    monkeypatch.setattr(sys, "stderr", err)
    prog = Progress("work", 3)
    for k in range(1, 4):
        prog.update(k)
    assert err.getvalue() == ""


def test_progress_on_a_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    err = _Tty()
    monkeypatch.setattr(sys, "stderr", err)
    prog = Progress("work", 3)
    prog.update(3)
    assert err.getvalue().startswith("\rwork: 3/3 (100%)")
    quiet = Progress("work", 3, enabled=False)
    err.truncate(0)
    err.seek(0)
    quiet.update(3)
    assert err.getvalue() == ""
