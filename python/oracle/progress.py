"""Progress of a long run (import, export, load, evaluate, tune) as a bar with rate and ETA.

The long-running functions take an optional ``Tick`` (a plain callable), so the library never
imports the command line; the commands make one with ``bar``, which draws with tqdm on a
terminal's stderr and stays quiet otherwise (a log file or a pipe gets no redrawn lines).
"""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Callable, Iterator
from typing import IO, Any

#: What a long run calls as it goes: ``tick(done, total)`` (``total`` None when unknown).
Tick = Callable[[int, int | None], None]


def shown(stream: IO[str] | None = None) -> bool:
    """Whether progress is drawn: only on a terminal."""
    stream = sys.stderr if stream is None else stream
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


@contextlib.contextmanager
def bar(label: str, unit: str = "it", total: int | None = None, stream: IO[str] | None = None) -> Iterator[Tick]:
    """A ``Tick`` drawing one tqdm bar labelled ``label`` on ``stream`` (default stderr) while
    the block runs; a no-op off a terminal. The bar is closed (its line ended) however the
    block ends, so an error or Ctrl-C prints on a line of its own."""
    stream = sys.stderr if stream is None else stream
    if not shown(stream):
        yield _quiet
        return
    from tqdm import tqdm  # type: ignore[import-untyped]  # here: only a terminal run pays its import

    import shutil

    sized = shutil.get_terminal_size((0, 0)).columns > 0  # a pty of no size (script, some CI) draws at 80
    drawn: Any = tqdm(total=total, desc=label, unit=f" {unit}", file=stream, dynamic_ncols=sized, ncols=None if sized else 80,
                      nrows=None if sized else 24,
                      mininterval=0.2, leave=True)

    def tick(done: int, total_now: int | None = None) -> None:
        if total_now is not None and total_now != drawn.total:
            drawn.total = total_now
        drawn.update(done - drawn.n)

    try:
        yield tick
    finally:
        drawn.close()


def _quiet(done: int, total: int | None = None) -> None:
    """The ``Tick`` off a terminal: nothing is drawn."""
