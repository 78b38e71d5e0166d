"""Runs one command line in-process the way a user would, and reports what it did.

The bad-input corpus (tests/corpus/README.md) runs hundreds of command lines; a fresh Python per
line would take minutes, so each one calls ``oracle.cli.main`` with its argv and captures stdout,
stderr (also at the file-descriptor level, where SWI-Prolog writes) and the exit code.
"""

from __future__ import annotations

import contextlib
import gc
import hashlib
import io
import json
import os
import signal
import sys
import tempfile
import traceback
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Outcome:
    """What one command line did."""

    code: int
    stdout: str
    stderr: str
    #: The formatted traceback when the command raised instead of returning (a bug).
    crash: str | None


@contextlib.contextmanager
def _fd2_to(path: Path):  # noqa: ANN202 - a context manager
    """Send file descriptor 2 (C-level stderr, used by SWI-Prolog) to ``path`` meanwhile."""
    saved = os.dup(2)
    with open(path, "wb") as sink:
        os.dup2(sink.fileno(), 2)
    try:
        yield
    finally:
        os.dup2(saved, 2)
        os.close(saved)


class Hung(Exception):
    """A command ran past its time limit (an input that makes it work without bound)."""


def _hang(signum: int, frame: object) -> None:
    raise Hung("the command ran longer than its time limit")


def run_cli(argv: Sequence[str], *, stdin: str = "", limit_s: int = 60) -> Outcome:
    """``python -m oracle ARGV`` in this process (at most ``limit_s`` seconds)."""
    from oracle.cli import main

    out, err = io.StringIO(), io.StringIO()
    crash = None
    code: int
    with tempfile.TemporaryDirectory() as tmp:
        fd_err = Path(tmp) / "fd2"
        old_stdin = sys.stdin
        sys.stdin = io.StringIO(stdin)
        try:
            previous = signal.signal(signal.SIGALRM, _hang)
            signal.alarm(limit_s)
            with _fd2_to(fd_err), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                try:
                    code = int(main(list(argv)) or 0)
                except SystemExit as stop:
                    code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
                except BaseException:  # noqa: BLE001 - a traceback is exactly what is looked for
                    code = -1
                    crash = traceback.format_exc()
        finally:
            signal.alarm(0)
            signal.signal(signal.SIGALRM, previous)
            sys.stdin = old_stdin
            gc.collect(0)  # close what a failing command left open, as process exit would
        low_level = fd_err.read_bytes().decode("utf-8", "replace")
    return Outcome(code, out.getvalue(), err.getvalue() + low_level, crash)


def store_state(path: Path) -> str:
    """A digest of a SQLite store's files: equal digests mean the store was not touched."""
    digest = hashlib.sha256()
    for suffix in ("", "-wal"):
        part = Path(f"{path}{suffix}")
        if part.exists() and part.stat().st_size > 0:
            digest.update(suffix.encode() + part.read_bytes())
    return digest.hexdigest()


def sample_chains(out: Path, per_user: int, users: int = 2) -> Path:
    """The first ``per_user`` rows of the first ``users`` users of the packaged sample chains,
    written to ``out``: the valid file the corpus cases start from."""
    root = Path(__file__).resolve().parents[2]
    rows: list[str] = []
    counts: dict[str, int] = {}
    for line in (root / "ontology" / "sample-chains.jsonl").read_text().splitlines():
        user = json.loads(line)["user"]
        counts[user] = counts.get(user, 0) + 1
        if counts[user] <= per_user and len(counts) <= users:
            rows.append(line)
    out.write_text("\n".join(rows) + "\n")
    return out


#: Passwords the corpus's inputs carry; no message may show one.
SECRETS = ("s3cret", "p@ss", "pa/ss", "pa:ss", "s3cr%zzet")


def assert_refused(outcome: Outcome, expected: str) -> None:
    """A refused input: no traceback, a failing exit, one line on stderr holding ``expected``,
    and no password in any output."""
    assert outcome.crash is None, f"traceback:\n{outcome.crash}"
    assert outcome.code not in (0, -1), f"exit {outcome.code}; stdout {outcome.stdout[:300]!r}"
    lines = outcome.stderr.strip().splitlines()
    assert len(lines) == 1, f"expected one line on stderr, got {len(lines)}: {outcome.stderr[:600]!r}"
    assert expected in lines[0], lines[0]
    for secret in SECRETS:
        assert secret not in outcome.stderr + outcome.stdout
