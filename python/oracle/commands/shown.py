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
        return f"p {task.probability:.3f} ({why})"
    return "no similar history" if math.isinf(task.score) else f"score {task.score:.4f} from {task.n_similar} similar"


def print_ranking(result: NeemRanking, limit: int | None = None) -> None:
    from oracle.timeline import format_clock

    when = f"{format_clock(result.at)} ({result.time_of_day})" if result.time_of_day else f"position {result.at:g} (no clock)"
    print(f"NEEM {result.neem}: {result.history} past actions, decision at {when}; "
          f"{result.method} ranked {len(result.calls)} options in {result.milliseconds:.2f} ms")
    shown = list(zip(result.ranking, result.calls))[:limit]
    for t, call in shown:
        print(f"  {t.rank:2d}. {str(call):32s} {describe(t)}")
    if limit is not None and len(result.calls) > limit:
        print(f"  ... and {len(result.calls) - limit} more")
    print("predicted chain: " + " -> ".join(str(c) for c in result.chain))
    if result.written is not None:
        print(f"ranking written back as {result.written}")
    if result.note is not None:
        print(result.note)
