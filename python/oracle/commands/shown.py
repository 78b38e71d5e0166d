"""How a ranking is shown on the terminal: by ``rank`` and by ``demo`` (so neither command imports
the other)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from oracle.algorithm.records import RankedTask
    from oracle.ranking import NeemRanking


def describe(task: RankedTask) -> str:
    """One line of why a task stands where it does; scores are lower-is-better for every method."""
    from oracle.algorithm.records import RoutineTask, local_name
    from oracle.answers import lifts

    if isinstance(task, RoutineTask):
        if task.order > 0:
            why = f"followed [{', '.join(task.context)}] {task.n_similar}x"
        elif task.order == 0:
            why = f"done {task.n_similar}x, not after this context"
        else:
            why = "no past context: by similarity"
        if task.order <= 0:  # where no counted context backs it, as the tablet's reason
            why += "".join(f"; {note}" for note in lifts([local_name(obj) for obj in task.focus], task.new, task.resumed,
                                                         task.since))
        return f"{percent(task.probability):>7s} ({why})"
    if math.isinf(task.score):
        return "no similar history"
    return f"thesis score {task.score:.3g} (lower ranks higher) from {task.n_similar} similar"


def percent(probability: float) -> str:
    """A probability as a person reads it: ``87%``, ``4.2%``, ``0.031%``; below a thousandth of
    a percent ``<0.001%`` (three decimals of a probability made 0.000 of tasks still ranked)."""
    value = 100.0 * probability
    if value >= 10:
        return f"{value:.0f}%"
    if value >= 0.001:
        return f"{value:.2g}%"
    return "<0.001%"


def history_words(history: int, breaks: int, pause: bool) -> str:
    """The actions a ranking learnt from, counted as ``neems`` counts the NEEM's actions (the
    breaks logged as idle actions among them), and the break since the last action apart."""
    logged, logged_breaks = history - int(pause), breaks - int(pause)
    text = f"{logged} action{'s' if logged != 1 else ''} before the decision"
    if logged_breaks:
        text += f" ({logged_breaks} of them breaks, logged as idle actions)"
    return text + (" and the break since the last one" if pause else "")


def print_ranking(result: NeemRanking, limit: int | None = None, modes: bool = False) -> None:
    """The ranking, best first; with ``modes`` who usually does each task (the result's
    ``usual``), in the tablet's English words, and each step of the chain."""
    from oracle.algorithm.records import RoutineTask
    from oracle.words import mode_sentence
    from oracle.timeline import format_clock

    when = f"{format_clock(result.at)} ({result.time_of_day})" if result.time_of_day else f"position {result.at:g} (no clock)"
    print(f"NEEM {result.neem}: {history_words(result.history, result.breaks, result.pause)}; decision at {when}; "
          f"{result.method} ranked {len(result.calls)} options in {result.milliseconds:.2f} ms"
          + ("; % = how likely it is next" if result.ranking and isinstance(result.ranking[0], RoutineTask) else ""))
    shown = list(zip(result.ranking, result.calls))[:limit]
    usual, chain_modes = (result.usual, result.chain_modes) if modes else ((), ())
    for index, (t, call) in enumerate(shown):
        said = mode_sentence("en", usual[index].mode, usual[index].counts, usual[index].context) if index < len(usual) else ""
        people = result.people[index] if index < len(result.people) else None
        print(f"  {t.rank:2d}. {str(call):32s} {describe(t)}" + (f" {said}" if said else "")
              + (f" {people[0].upper()}{people[1:]}." if people else ""))
    if limit is not None and len(result.calls) > limit:
        print(f"  ... and {len(result.calls) - limit} more")
    steps = [f"{c} [{chain_modes[i] or '?'}]" if i < len(chain_modes) else str(c) for i, c in enumerate(result.chain)]
    print("predicted chain: " + " -> ".join(steps))
    if result.written is not None:
        print(f"ranking written back as {result.written}")
    if result.note is not None:
        print(result.note)
