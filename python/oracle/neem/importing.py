"""Bulk import: a chains JSONL file logged into one NEEM per user."""

from __future__ import annotations

from pathlib import Path

from oracle.chains import read_chains
from oracle.errors import LoggingError
from oracle.neem.lifecycle import wipe_temporary_neems
from oracle.neem.writer import NeemLogger
from oracle.ontology.model import OdbOntology
from oracle.store import Store
from oracle.store.tbox import TBox, tbox_from_graph
from oracle.timeline import IDLE_THRESHOLD_S


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
) -> dict[str, int]:
    """Log a chains JSONL file, one NEEM per user; return {NEEM id: actions committed}.

    With ``session`` the NEEMs are temporary (thesis 3.5): earlier temporary NEEMs are wiped
    first, and these are wiped by the next session unless ``persist`` keeps them.

    Rows may carry ``id`` and ``performed_by`` besides the chain fields (``end``/``duration``
    are chain fields, see oracle.chains). Rows are committed as they are logged (in groups of
    ``commit_every``); an error on line n commits every good line before it, then raises an
    error naming the file and line.
    """
    report = {} if report is None else report
    loggers: dict[str, NeemLogger] = {}
    tbox = tbox if tbox is not None else tbox_from_graph(onto.graph)
    where = str(path)
    try:
        for row in read_chains(path):
            where = f"{path}:{row.line}"
            if row.time is None:
                raise LoggingError("'time' is required to log an action")
            end = row.end
            logger = loggers.get(row.user)
            if logger is None:
                if session and not loggers:
                    wipe_temporary_neems(store)
                logger = NeemLogger.create(store, onto, user=row.user, replace=replace, tbox=tbox, temporary=session,
                                           idle_threshold=idle_threshold, commit_every=commit_every)  # fmt: skip
                loggers[row.user] = logger
                report[logger.neem_id] = 0
            action_id = row.extra.get("id")
            logger.action(
                row.action,
                row.time,
                end,
                performed_by=str(row.extra.get("performed_by", "robot")),
                action_id=None if action_id is None else str(action_id),
                available=row.available,
            )
            report[logger.neem_id] = logger.committed
    except LoggingError as error:
        raise LoggingError(f"{where}: {error}") from None
    finally:
        for logger in loggers.values():
            report[logger.neem_id] = logger.flush()
    return report
