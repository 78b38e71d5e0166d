"""The question forms ``ask`` answers (docs/beyond.md), in English and German, read into a
``Question``; any other text is a ``QuestionError`` listing the forms.

A task is written in the chain syntax (``pick(banana)``) in either language, or, in English, as
words: the task's name then its objects (``pour the thermos into the green mug``); articles and
prepositions are skipped, and the words of a name may be joined by spaces or underscores.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from oracle.chains import TaskCall, parse_call
from oracle.errors import ChainSyntaxError, NeemOracleError, OntologyError
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology


class QuestionError(NeemOracleError):
    """A question that is none of the forms, or names a task or object the ontology lacks."""


@dataclass(frozen=True)
class Form:
    """One question form: its key, an English and a German example, and the patterns that read it
    (the named groups ``task``, ``obj``, ``period``)."""

    key: str
    english: str
    german: str
    patterns: tuple[tuple[str, str], ...]  # (language, regular expression)


_PERIOD_EN = r"(?P<period>today|this week)"
_PERIOD_DE = r"(?P<period>heute|diese woche|in dieser woche)"
_PART_EN = r"(?P<period>today|this morning|this afternoon|at midday|this evening)"
_PART_DE = r"(?P<period>heute|heute morgen|heute früh|heute mittag|heute abend)"

#: The forms, in the order the unknown-form message lists them.
FORMS: tuple[Form, ...] = (
    Form("last", "when did I last pick(apple)?", "wann habe ich zuletzt pick(apple) gemacht?",
         (("en", r"when did (?:i|you|we) last (?P<task>.+)"),
          ("de", r"wann (?:habe ich|hast du|haben wir) zuletzt (?P<task>.+?)(?: gemacht| getan)?"))),
    Form("count", "how often did I pick(apple) today / this week?", "wie oft habe ich heute / diese Woche pick(apple) gemacht?",
         (("en", r"how (?:often|many times) did (?:i|you|we) (?P<task>.+) " + _PERIOD_EN),
          ("de", r"wie oft (?:habe ich|hast du|haben wir) " + _PERIOD_DE + r" (?P<task>.+?)(?: gemacht| getan)?"))),
    Form("after", "what do I usually do after pick(apple)?", "was mache ich meistens nach pick(apple)?",
         (("en", r"what do (?:i|you|we) usually do after (?P<task>.+)"),
          ("de", r"was (?:mache ich|machst du|machen wir) (?:meistens|normalerweise|gewöhnlich) nach (?P<task>.+)"))),
    Form("done", "what did you do this morning / today / this evening?", "was hast du heute morgen / heute / heute abend gemacht?",
         (("en", r"what did (?:you|i|we) do " + _PART_EN),
          ("de", r"was (?:hast du|habe ich|haben wir) " + _PART_DE + r" gemacht"))),
    Form("where", "where is the green_mug?", "wo ist der green_mug?",
         (("en", r"where is (?:the |my )?(?P<obj>.+)"),
          ("de", r"wo (?:ist|steht|liegt) (?:der |die |das |mein |meine )?(?P<obj>.+)"))),
    Form("suggested", "why did you suggest open(fridge)?", "warum hast du open(fridge) vorgeschlagen?",
         (("en", r"why did you suggest (?P<task>.+)"),
          ("de", r"warum hast du (?P<task>.+) vorgeschlagen"))),
)

#: The periods of the questions, by the words that name them (both languages).
PERIODS = {"today": "today", "heute": "today", "this week": "week", "diese woche": "week", "in dieser woche": "week",
           "this morning": "Morning", "heute morgen": "Morning", "heute früh": "Morning",
           "this afternoon": "Midday", "at midday": "Midday", "heute mittag": "Midday",
           "this evening": "Evening", "heute abend": "Evening"}

_FILLERS = frozenset({"the", "a", "an", "my", "into", "in", "from", "onto", "on", "with", "to", "of", "off", "up", "out"})


@dataclass(frozen=True)
class Question:
    """A question read: its form's key, its language (``en``/``de``), the task, object or period
    it names (None when the form has none)."""

    form: str
    language: str
    call: TaskCall | None = None
    obj: str | None = None
    period: str | None = None
    #: Other readings of the task's words, in order (``open fridge``: open_fridge, then open(fridge)).
    readings: tuple[TaskCall, ...] = ()


def forms_line() -> str:
    """The one line that lists the forms (the answer to a question of no known form)."""
    return "; ".join(f.english for f in FORMS) + " (German: " + "; ".join(f.german for f in FORMS) + ")"


def read_question(text: str, onto: OdbOntology) -> Question:
    """``text`` as a Question; QuestionError naming the forms, the task or the object otherwise."""
    if not isinstance(text, str) or not text.strip():
        raise QuestionError(f"ask a question of one of these forms: {forms_line()}")
    said = " ".join(text.strip().rstrip("?!. ").split()).lower()
    for form in FORMS:
        for language, pattern in form.patterns:
            found = re.fullmatch(pattern, said)
            if found is None:
                continue
            groups = found.groupdict()
            calls = resolve_calls(groups["task"], onto) if groups.get("task") else []
            obj = resolve_object(groups["obj"], onto) if groups.get("obj") else None
            period = PERIODS[groups["period"]] if groups.get("period") else None
            return Question(form.key, language, calls[0] if calls else None, obj, period, tuple(calls[1:]))
    raise QuestionError(f"{text.strip()!r} is not a question I know; ask one of: {forms_line()}")


def resolve_calls(words: str, onto: OdbOntology) -> list[TaskCall]:
    """The readings of a task in the chain syntax (one) or as words (the task's name, then its
    objects; the longest task name first), checked against the ontology; QuestionError naming
    what is unknown when there is none."""
    words = words.strip()
    if "(" not in words:
        return _calls_from_words(words.replace("_", " ").split(), onto)
    try:
        call = parse_call(words)
        onto.task_iri(call.task)
        for arg in call.args:
            onto.object_iri(arg)
    except (ChainSyntaxError, OntologyError) as error:
        raise QuestionError(str(error)) from None
    return [call]


def resolve_object(words: str, onto: OdbOntology) -> str:
    """An odb object name from words (``green mug``, ``green_mug``); QuestionError if unknown."""
    name = "_".join(w for w in words.replace("_", " ").split() if w not in _FILLERS)
    if name not in onto.objects:
        raise QuestionError(f"unknown object {words.strip()!r}; known objects include "
                            f"{', '.join(sorted(onto.objects)[:8])}, ...")
    return name


def _calls_from_words(tokens: list[str], onto: OdbOntology) -> list[TaskCall]:
    calls: list[TaskCall] = []
    problem = f"{' '.join(tokens)!r} does not start with a task name; known tasks: {', '.join(sorted(onto.tasks))}" \
              " (or write the call, e.g. pick(apple))"
    for size in (3, 2, 1):  # the longest task name first: drink from, turn on
        name = "_".join(tokens[:size])
        if len(tokens) >= size and name in onto.tasks:
            objects = _objects([t for t in tokens[size:] if t not in _FILLERS], onto)
            if isinstance(objects, str):
                problem = objects
            else:
                calls.append(TaskCall(name, tuple(objects)))
    if not calls:
        raise QuestionError(problem)
    return calls


def _objects(tokens: list[str], onto: OdbOntology) -> list[str] | str:
    """The object names the words spell (the longest first), or the problem as text."""
    names: list[str] = []
    at = 0
    while at < len(tokens):
        for size in range(len(tokens) - at, 0, -1):
            name = "_".join(tokens[at:at + size])
            if name in onto.objects:
                names.append(name)
                at += size
                break
        else:
            return f"{tokens[at]!r} is no object I know (known objects include {', '.join(sorted(onto.objects)[:8])}, ...)"
    return names
