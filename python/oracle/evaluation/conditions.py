"""Condition-matched development sets: a chains file with fields dropped, so that a development set
made by the persona generator can stand for data that lacks them (docs/algorithm.md, "Selection
protocol").

``open`` drops the available sets: the replay then offers every distinct action of the user, as on
the Kasteren and EGTEA rows. ``clockless`` also drops the clock (``time``, ``end``): no part of day,
no idle gaps, as the EGTEA rows (and ``import --no-clock``). Order, users and actions stay as they
were; nothing is added, so a derived set holds no information its source lacked.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator
from dataclasses import replace
from pathlib import Path

from oracle.files import private_file
from oracle.chains import ChainRow, read_chains

#: Each condition and the fields it drops (``duration`` is read into ``end``).
CONDITIONS: dict[str, tuple[str, ...]] = {
    "open": ("available",),
    "clockless": ("available", "time", "end"),
}


def derive(rows: Iterable[ChainRow], condition: str) -> Iterator[ChainRow]:
    """The rows with the fields of ``condition`` dropped (ValueError for an unknown condition)."""
    if condition not in CONDITIONS:
        raise ValueError(f"unknown condition {condition!r}: expected one of {', '.join(CONDITIONS)}")
    clockless = "time" in CONDITIONS[condition]
    for row in rows:
        if clockless:
            yield replace(row, available=None, time=None, end=None)
        else:
            yield replace(row, available=None)


def write_conditions(source: Path | str, out: Path | str) -> dict[str, Path]:
    """Write ``out/CONDITION/NAME.jsonl`` for every condition from the chains file ``source``
    (NAME its file name); the whole file is read and checked before anything is written."""
    source = Path(source)
    rows = list(read_chains(source))
    written = {}
    for condition in CONDITIONS:
        target = Path(out) / condition / source.name
        with private_file(target) as handle:  # a person's chains: 0600 in 0700 folders
            for row in derive(rows, condition):
                handle.write(json.dumps(row.to_json()) + "\n")
        written[condition] = target
    return written


__all__ = ["CONDITIONS", "derive", "write_conditions"]
