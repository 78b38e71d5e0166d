"""Bulk import: a chains JSONL file logged into one NEEM per user.

Two passes: the first checks every row the way the logger would (syntax, task and objects,
roles, time order and ids per user) and notes each user's last line, so a bad row anywhere writes
nothing; the second logs, committing a user's NEEM when that user's last row is logged
(docs/store.md, "Durability"). The first pass keeps the rows it parsed for the second, up to
``KEPT_ROWS``; a longer file is read again, so memory stays bounded. A log without clock times
imports only when asked (``no_clock``): each user's actions then lie on the sequence clock, in
file order (docs/time.md, "Logs without a clock").
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from oracle.chains import ChainRow, TaskCall, read_chains
from oracle.errors import LoggingError
from oracle.neem.lifecycle import wipe_temporary_neems
from oracle.neem.writer import NeemLogger, check_call, check_performer
from oracle.ontology.model import OdbOntology
from oracle.progress import Tick
from oracle.store import Store
from oracle.store.ontology_tbox import tbox_for
from oracle.store.tbox import TBox
from oracle.neem.records import checked_instant
from oracle.timeline import CLOCK_KEY, IDLE_THRESHOLD_S, SEQUENCE_CLOCK, TimeValueError, seconds_of, sequence_instant

if TYPE_CHECKING:
    from oracle.writtenview import WrittenView  # loaded only when asked for (it loads oracle.bridge)

#: Registry key of a NEEM whose import has not reached its user's last row: set when the
#: NEEM is made, cleared once that row is committed. ``neems`` names such a NEEM incomplete
#: and the next import of the same user replaces it.
INCOMPLETE_KEY = "import_incomplete"
#: What an import does with a user who already has a complete NEEM in the store.
EXISTING = ("refuse", "replace", "new")

#: The first pass keeps at most this many parsed rows for the second (about 0.5 kB each with
#: their calls shared); beyond it the file is read again.
KEPT_ROWS = 100_000


@dataclass
class _UserPlan:
    """What the first pass learned about one user's rows."""

    last_line: int = 0
    rows: int = 0
    last_begin: float | None = None
    ids: set[str] = field(default_factory=set)


@dataclass(frozen=True)
class CheckedChains:
    """What the first pass found: each user's plan, and the rows themselves (None when the file
    had more than ``KEPT_ROWS``: the second pass reads it again)."""

    plans: dict[str, _UserPlan]
    rows: tuple[ChainRow, ...] | None


def check_chains(onto: OdbOntology, path: str | Path, *, no_clock: bool = False,
                 progress: Tick | None = None) -> CheckedChains:
    """Check every row of a chains file as the logger will; return each user's plan and the rows.
    With ``no_clock`` every row must be time-less (no ``time``, ``end`` or ``duration``).
    ``progress`` (oracle.progress) is told the line reached after each row.

    Raises LoggingError naming the file and line of the first bad row."""
    plans: dict[str, _UserPlan] = {}
    where = str(path)
    checked = _Checked()
    kept: list[ChainRow] | None = []
    try:
        for row in read_chains(path):
            where = f"{path}:{row.line}"
            plan = plans.setdefault(row.user, _UserPlan())
            _check_row(onto, row, plan, checked, no_clock)
            plan.last_line, plan.rows = row.line, plan.rows + 1
            if progress is not None:
                progress(row.line, None)
            if kept is not None:
                kept.append(row)
                if len(kept) > KEPT_ROWS:
                    kept = None
    except LoggingError as error:
        raise LoggingError(f"{where}: {error}") from None
    if not plans:
        raise LoggingError(f"{path}: no rows to import (every line is blank or a # comment)")
    return CheckedChains(plans, tuple(kept) if kept is not None else None)


@dataclass
class _Checked:
    """The calls a first pass found good, and the available sets it checked whole: rows that
    share a set share its tuple (``read_chains``), which is kept here so that its id stays its own."""

    calls: set[TaskCall] = field(default_factory=set)
    sets: dict[int, tuple[TaskCall, ...]] = field(default_factory=dict)

    def check(self, onto: OdbOntology, calls: Iterable[TaskCall]) -> None:
        known = self.calls
        for call in calls:
            if call not in known:
                check_call(onto, call)
                if len(known) < 100_000:
                    known.add(call)

    def check_set(self, onto: OdbOntology, available: tuple[TaskCall, ...]) -> None:
        if self.sets.get(id(available)) is not available:
            self.check(onto, available)
            if len(self.sets) < 100_000:
                self.sets[id(available)] = available


def _check_row(onto: OdbOntology, row: ChainRow, plan: _UserPlan, checked: _Checked, no_clock: bool) -> None:
    if no_clock:
        if row.time is not None or row.end is not None:
            raise LoggingError("the row has a time, but a log without a clock (--no-clock) must have none")
    elif row.time is None:
        raise LoggingError("'time' is required to log an action (a log without clock times: import --no-clock)")
    checked.check(onto, (row.action,))
    if row.available:
        checked.check_set(onto, row.available)
    check_performer(row.extra.get("performed_by", "robot"))
    if row.time is None:  # the sequence clock: in order by construction
        return _check_id(row, plan)
    try:
        begin = seconds_of(row.time)
        end = begin if row.end is None else seconds_of(row.end)
    except TimeValueError as error:
        raise LoggingError(str(error)) from None
    del end  # the writer's rule (NeemLogger._check_time): no action starts before the one before
    if plan.last_begin is not None and begin < plan.last_begin:
        raise LoggingError(
            f"time goes backwards: action {row.action} at {begin:.3f} is before the start of the last action"
            f" ({plan.last_begin:.3f}) of user {row.user!r}"
        )
    plan.last_begin = begin
    _check_id(row, plan)


def _check_id(row: ChainRow, plan: _UserPlan) -> None:
    action_id = row.extra.get("id")
    if action_id is not None:
        key = str(action_id)
        if key in plan.ids:
            raise LoggingError(f"duplicate action id {key!r} for user {row.user!r}")
        plan.ids.add(key)


def import_chains(
    store: Store,
    onto: OdbOntology,
    path: str | Path,
    *,
    replace: bool = False,
    report: dict[str, int] | None = None,
    idle_threshold: float = IDLE_THRESHOLD_S,
    commit_every: int = 1,
    tbox: TBox | None = None,
    session: bool = False,
    checked: CheckedChains | None = None,
    no_clock: bool = False,
    stop: Callable[[], bool] | None = None,
    existing: str | None = None,
    refused: list[str] | None = None,
    views: dict[str, WrittenView] | None = None,
) -> dict[str, int]:
    """Log a chains JSONL file, one NEEM per user; return {NEEM id: actions committed}.

    With ``session`` the NEEMs are temporary (thesis 3.5): earlier temporary NEEMs are wiped
    first, and these are wiped by the next session unless ``persist`` keeps them.

    Rows may carry ``id`` and ``performed_by`` besides the chain fields (``end``/``duration``
    are chain fields, see oracle.chains). A bad row anywhere raises an error naming the file and
    line before anything is written. Rows are committed in groups of ``commit_every`` and when
    a user's last row is logged; with ``replace`` a user's old NEEM is swapped for the new one
    only then (until then, and after any error, the old one is untouched). Session NEEMs, too,
    appear only when complete, so two session imports at once do not wipe each other's.
    ``checked`` is what ``check_chains`` returned for this file, when the caller checked it.
    With ``no_clock`` the rows have no times: a user's n-th action (from 0) spans positions n to
    n + 1 of the sequence clock, and the NEEMs are marked as having no clock.
    ``stop`` is asked before each row; when it says True (Ctrl-C was pressed) the import ends
    there with KeyboardInterrupt, between two rows, so ``report`` counts exactly what is stored.

    ``existing`` says what happens to a user who already has a complete NEEM: ``refuse`` (the
    default) skips that user's rows and appends one line saying so to ``refused``, ``replace``
    (also ``replace=True``) replaces the NEEM, ``new`` adds another. A user's NEEM that an
    earlier import left incomplete (killed before the user's last row) is always replaced.

    ``views``, when given, gets each user's ``WrittenView`` (oracle.writtenview) of the rows
    logged, told each action as the logger writes it, with the same instants: the history view
    is kept from it (``keep_written``) without a second pass over the rows.
    """
    if commit_every < 1:
        raise LoggingError(f"commit_every must be at least 1, got {commit_every}")
    existing = existing or ("replace" if replace else "refuse")
    if existing not in EXISTING:
        raise LoggingError(f"existing must be one of {', '.join(EXISTING)}, got {existing!r}")
    refused = [] if refused is None else refused
    checked = check_chains(onto, path, no_clock=no_clock) if checked is None else checked
    plans = checked.plans
    positions: dict[str, int] = {}
    report = {} if report is None else report
    loggers: dict[str, NeemLogger] = {}
    tbox = tbox if tbox is not None else tbox_for(onto)
    where = str(path)
    done = False
    # each user's choice, made once before anything is written: True replaces, False adds,
    # None skips the user's rows
    replacing = {} if session else _choices(store, plans, existing, refused)
    meta: dict[str, object] = {CLOCK_KEY: SEQUENCE_CLOCK} if no_clock else {}
    if not session:
        meta[INCOMPLETE_KEY] = True  # until the user's last row is committed
    syncing = contextlib.ExitStack()
    try:
        # commits are written as they come but reach the disk once per user (``store.sync``
        # below, and when the import ends): a killed import loses none of them
        syncing.enter_context(store.deferred_sync())
        if session:
            wipe_temporary_neems(store)
        for row in checked.rows if checked.rows is not None else read_chains(path):
            if stop is not None and stop():
                raise KeyboardInterrupt
            where = f"{path}:{row.line}"
            logger = loggers.get(row.user)
            if logger is None:
                if replacing.get(row.user, False) is None:
                    continue
                logger = NeemLogger.create(store, onto, user=row.user, replace=bool(replacing.get(row.user, replace)), tbox=tbox,
                                           temporary=session, idle_threshold=idle_threshold, commit_every=commit_every,
                                           hidden=session, meta=meta or None)  # fmt: skip
                loggers[row.user] = logger
                report[logger.neem_id] = 0
                # a new NEEM, its TBox in, written by this logger alone: it knows every subject
                # (so it reads none back), and the indexes are built at its end
                logger.individuals.know_all()
                store.defer_indexes(logger.writes_to)
            action_id = row.extra.get("id")
            # The instants made once, for the logger and the view alike
            if no_clock:
                position = positions[row.user] = positions.get(row.user, -1) + 1
                begin, end = sequence_instant(position), sequence_instant(position + 1)
            else:
                assert row.time is not None  # checked by the first pass
                begin = checked_instant(row.time)
                end = begin if row.end is None else checked_instant(row.end)
            performed_by = str(row.extra.get("performed_by", "robot"))
            logger.action(
                row.action,
                begin,
                end,
                performed_by=performed_by,
                action_id=None if action_id is None else str(action_id),
                available=row.available,
                state=None if row.extra.get("state") is None else str(row.extra["state"]),
                session=None if row.extra.get("session") is None else str(row.extra["session"]),
            )
            if views is not None:
                view = views.get(row.user)
                if view is None:
                    from oracle.writtenview import WrittenView

                    view = views[row.user] = WrittenView(idle_threshold)
                view.logged(row.action, begin, end, performed_by, row.available)
            name = logger.neem_id
            if row.line == plans[row.user].last_line:
                logger.flush()
                store.make_indexes(logger.writes_to)  # before the NEEM is complete or swapped in
                logger.close()  # the user's rows end here: commit (and swap in a replacement) now
                if not session:
                    store.update_meta(logger.neem_id, **{INCOMPLETE_KEY: None})
                store.sync()  # the user's NEEM on disk: it survives a power loss too
                report[name] = logger.committed
                del loggers[row.user]  # done: its caches need not stay in memory (many users)
            else:
                report[name] = logger.committed
        done = True
    except LoggingError as error:
        raise LoggingError(f"{where}: {error}") from None
    finally:
        with syncing:  # whatever is committed below is on disk when this block ends
            for logger in loggers.values():
                if not logger.replacing:
                    report[logger.neem_id] = logger.flush()
                    store.make_indexes(logger.writes_to)  # a NEEM cut short (INCOMPLETE) is read as fast
                elif not done:
                    name = logger.neem_id
                    logger.abandon()  # the old NEEM stays as it was
                    report.pop(name, None)
    return report


def _choices(store: Store, plans: dict[str, _UserPlan], existing: str, refused: list[str]) -> dict[str, bool | None]:
    """For each user of the file with a NEEM in the store: True to replace it, False to add a
    new one, None to skip the user (a line in ``refused`` says why). Users without one: absent."""
    complete: dict[str, str] = {}
    cut: set[str] = set()
    for info in store.neems():
        if info.temporary or info.user not in plans:
            continue
        if info.meta.get(INCOMPLETE_KEY):
            cut.add(info.user)
        else:
            complete.setdefault(info.user, info.id)
    choices: dict[str, bool | None] = {user: True for user in cut}
    for user, neem_id in complete.items():
        if existing == "refuse":
            choices[user] = None
            refused.append(f"user {user!r} already has NEEM {neem_id}: not imported (--replace replaces it,"
                           " --as-new adds another)")
        else:
            choices[user] = existing == "replace"
    return choices
