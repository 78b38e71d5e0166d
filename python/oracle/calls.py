"""Chain calls (``pour(thermos, green_mug)``) as the oracle's records, using the ontology.

The one place where odb names in a chain become task and object class IRIs in role slots; which
argument fills which slot is ``TaskClass.slots`` (the logger's roles follow the same rule).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from datetime import datetime
from typing import Any

from oracle.algorithm.records import Option, Step
from oracle.chains import TaskCall
from oracle.errors import OntologyError
from oracle.namespaces import SOMA_IRI
from oracle.ontology import OdbOntology
from oracle.timeline import clock, is_idle_gap, time_of_day


def option_of(ontology: OdbOntology, call: TaskCall) -> Option:
    """The Option for a call; unknown tasks or objects raise OntologyError naming them."""
    task = ontology.task_iri(call.task)
    classes = [ontology.object_iri(name) for name in call.args]
    filled = dict(zip(ontology.tasks[call.task].slots(len(classes)), classes))
    return Option(task, target=filled.get("target"), reference=filled.get("reference"))


def opening_tasks(ontology: OdbOntology) -> frozenset[str]:
    """Task classes under soma:Opening: their successors are not pruned (thesis Fig. 4.7)."""
    return frozenset(t.iri for t in ontology.tasks.values() if ontology.taxonomy.is_subclass_of(t.iri, SOMA_IRI + "Opening"))


def call_of(ontology: OdbOntology, option: Option) -> TaskCall:
    """The inverse of ``option_of`` for display and for the chain format."""
    args = tuple(ontology.name(c) for c in (option.reference, option.target) if c is not None)
    return TaskCall(ontology.name(option.task), args)


def step_of(
    ontology: OdbOntology,
    call: TaskCall,
    available: Iterable[TaskCall] = (),
    when: datetime | None = None,
    idle: bool = False,
) -> Step:
    option = option_of(ontology, call)
    options = tuple(option_of(ontology, c) for c in available)
    return Step(option.task, option.target, option.reference, options,
                time_of_day(when) if when is not None else None, idle, str(call))


def idle_step(ontology: OdbOntology, when: datetime | None = None) -> Step:
    """An odb:IdleTask step: the delimiter of task chains."""
    return Step(ontology.vocab.idle_task, time_of_day=time_of_day(when) if when is not None else None,
                idle=True, label="idle")


def check_call(ontology: OdbOntology, call: TaskCall, where: str) -> None:
    """Raise OntologyError naming ``where`` when the call uses unknown names."""
    try:
        option_of(ontology, call)
    except OntologyError as error:
        raise OntologyError(f"{where}: {error}") from None


@dataclass
class DoneBefore:
    """What the user did so far, first done first: the offer of an action that had no imagined
    situation before it (docs/algorithm.md, "Steps without an offer"); the history read and the
    live service both keep one, so that they give such steps the same offer."""

    done: dict[Option, None] = field(default_factory=dict)
    _offer: tuple[Option, ...] = ()

    def offer(self) -> tuple[Option, ...]:
        """The options done so far (one tuple, shared until a new option is done)."""
        if len(self._offer) != len(self.done):
            self._offer = tuple(self.done)
        return self._offer

    def add(self, option: Option) -> None:
        """An action done (its option)."""
        self.done.setdefault(option, None)


def steps_from_history(ontology: OdbOntology, rows: Iterable[Mapping[str, Any]], clocked: bool = True) -> list[Step]:
    """The oracle's history from the Prolog bridge's ``situation_history`` rows (begin order);
    each action's step carries its begin as ``time`` when the NEEM has a clock (``clocked``: on
    the sequence clock a begin is a position, not a time)."""
    return history_steps(ontology, rows, clocked)[0]


def history_steps(ontology: OdbOntology, rows: Iterable[Mapping[str, Any]],
                  clocked: bool = True) -> tuple[list[Step], DoneBefore]:
    """``steps_from_history`` and what the user did in them (``DoneBefore`` of every action's
    option, first done first): made in the same pass, so a ranker need not walk the steps again
    (50,000 of them at the first rank after an import)."""
    from oracle.chains import parse_call

    # A long NEEM repeats a few dozen calls and available sets thousands of times: each is
    # read once (Options are immutable, so the steps may share them).
    options_of: dict[str, Option] = {}
    labels: dict[str, str] = {}
    sets: dict[tuple[str, ...], tuple[Option, ...]] = {}

    def option(text: str) -> Option:
        known = options_of.get(text)
        if known is None:
            known = options_of[text] = option_of(ontology, parse_call(text))
        return known

    # Rows read together share one list per distinct available set, and a step repeats often
    # (the same call, set and part of day): each distinct step is made once (Steps are immutable),
    # then given its begin where there is a clock.
    by_list: dict[int, tuple[Any, tuple[Option, ...]]] = {}
    made: dict[tuple[str, int, str | None], Step] = {}
    steps: list[Step] = []
    before = DoneBefore()  # the offer of the actions no imagined situation came before
    added: set[str] = set()  # the calls in ``before`` (a few dozen, each added once, not per row)
    for row in rows:
        part = row.get("part")
        part = part if part not in (None, "none") else None
        if row["call"] == "idle":
            steps.append(Step(ontology.vocab.idle_task, time_of_day=part, idle=True, label="idle"))
            continue
        text = row["call"]
        available = row.get("available")
        if available is None:
            seen = (None, before.offer())
        else:
            found = by_list.get(id(available))
            if found is None or found[0] is not available:
                key = tuple(available)
                options = sets.get(key)
                if options is None:
                    options = sets[key] = tuple(option(c) for c in key)
                found = by_list[id(available)] = (available, options)
            seen = found
        if text not in added:
            added.add(text)
            before.add(option(text))
        same = (text, id(seen[1]), part)
        step = made.get(same)
        if step is None:
            done = option(text)
            label = labels.get(text)
            if label is None:
                label = labels[text] = str(parse_call(text))
            step = made[same] = Step(done.task, done.target, done.reference, seen[1], part, False, label)
        steps.append(step.began(float(row["begin"])) if clocked else step)
    return steps, before


def steps_before(ontology: OdbOntology, rows: Iterable[Mapping[str, Any]], at: float, clocked: bool = True) -> list[Step]:
    """The history a decision at unix seconds ``at`` is ranked with: the ``situation_history``
    rows that began before it and, when the pause since the last action's end is an idle gap,
    the idle step the logger will write before the next action (the replay's rule:
    evaluation.replay observes that idle before ranking the decision after a gap)."""
    earlier = [row for row in rows if float(row["begin"]) < at]
    steps = steps_from_history(ontology, earlier, clocked)
    if earlier and earlier[-1]["call"] != "idle":
        last_end = max(float(row["end"] if row.get("end") is not None else row["begin"]) for row in earlier)
        if is_idle_gap(last_end, at):
            steps.append(idle_step(ontology, clock(last_end)))  # as the logger will date it
    return steps
