# SPDX-License-Identifier: Apache-2.0
"""Shared pieces of the command-line tools: one-line errors with exit status 2, progress."""
from __future__ import annotations

import argparse
import sys
import time
from typing import NoReturn


class UserError(Exception):
    """A problem with the user's input: reported as one line, exit status 2."""


class Parser(argparse.ArgumentParser):
    """argparse with the project's error convention: one line naming the problem, status 2."""

    def error(self, message: str) -> NoReturn:  # noqa: D401 - argparse API
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        sys.exit(2)


def fail(prog: str, message: str) -> NoReturn:
    sys.stderr.write(f"{prog}: error: {message}\n")
    sys.exit(2)


class Progress:
    """A progress line on stderr for long work: only when stderr is a terminal (a log file or a
    pipe gets no carriage-return lines) and the caller enables it (not for short jobs)."""

    def __init__(self, what: str, total: int, enabled: bool = True) -> None:
        self.what, self.total = what, max(total, 1)
        self.enabled = enabled and sys.stderr.isatty()
        self.t0 = time.time()
        self.last = 0.0

    def update(self, done: int) -> None:
        now = time.time()
        if not self.enabled or (now - self.last < 1.0 and done < self.total):
            return
        self.last = now
        rate = done / max(now - self.t0, 1e-9)
        pace = f"{rate:,.0f}/s" if rate >= 10 else f"{rate:.2f}/s"
        sys.stderr.write(f"\r{self.what}: {done}/{self.total} ({100 * done / self.total:.0f}%), "
                         f"{pace}")
        if done >= self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()
