"""The question forms ``ask`` answers (docs/beyond.md), in English and German, read into a
``Question``; any other text is a ``QuestionError`` listing the forms.

A task is written in the chain syntax (``pick(banana)``), or in words as a person says it in
either language (oracle.past.phrases: "den Kühlschrank geöffnet", "opening the fridge"), or as
the task's name then its objects (``pour the thermos into the green mug``); articles and
prepositions are skipped, and the words of a name may be joined by spaces or underscores.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from oracle.chains import TaskCall, parse_call
from oracle.errors import ChainSyntaxError, NeemOracleError, OntologyError
from oracle.past.phrases import PhraseBook
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology
    from oracle.words import Lexicon


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
_PART_EN = r"(?P<period>today|this morning|this afternoon|at midday|this evening|this week)"
_PART_DE = r"(?P<period>heute|heute morgen|heute früh|heute mittag|heute abend|diese woche|in dieser woche)"
#: Who a question asks about: the person, the robot, both (the NEEM holds the actions of both).
_WHO_EN = r"(?:i|you|we|the robot)"
_HAVE_DE = r"(?:habe ich|hab ich|hast du|haben wir|hat der roboter)"
_DO_DE = r"(?:mache ich|machst du|machen wir|macht der roboter)"
_USUALLY_DE = r"(?:meistens|normalerweise|gewöhnlich|üblicherweise|sonst|meist)"
_DONE_DE = r"(?: gemacht| getan)?"

#: The forms, in the order the unknown-form message lists them. A task is said as a call
#: (pick(apple)) or in words (oracle.past.phrases: "den Kühlschrank geöffnet", "opening the fridge").
FORMS: tuple[Form, ...] = (
    Form("last", "when did I last open the fridge?", "wann habe ich zuletzt den Kühlschrank geöffnet?",
         (("en", rf"when (?:did|have) {_WHO_EN} last (?P<task>.+)"),
          ("en", rf"when was the last time (?:that )?{_WHO_EN} (?P<task>.+)"),
          ("de", rf"wann {_HAVE_DE} (?:zuletzt|das letzte mal|zum letzten mal) (?P<task>.+?){_DONE_DE}"),
          ("de", rf"wann {_HAVE_DE} (?P<task>.+?) (?:zuletzt|das letzte mal|zum letzten mal) (?P<tail>.+)"),
          ("de", r"wann (?:wurde|wurden) (?P<task>.+?) (?:zuletzt|das letzte mal|zum letzten mal) (?P<tail>.+)"))),
    Form("count", "how often did I open the fridge today / this week?",
         "wie oft habe ich heute / diese Woche den Kühlschrank geöffnet?",
         (("en", rf"how (?:often|many times) (?:did|have) {_WHO_EN} (?P<task>.+) " + _PERIOD_EN),
          ("de", rf"wie oft {_HAVE_DE} " + _PERIOD_DE + rf" (?P<task>.+?){_DONE_DE}"),
          ("de", rf"wie oft {_HAVE_DE} (?P<task>.+?) " + _PERIOD_DE + rf"{_DONE_DE}"),
          # the period inside the phrase: "die Schublade diese Woche geschlossen"
          ("de", rf"wie oft {_HAVE_DE} (?P<task>.+?) " + _PERIOD_DE + r" (?P<tail>.+)"))),
    Form("after", "what do I usually do after opening the fridge?",
         "was mache ich meistens, nachdem ich den Kühlschrank geöffnet habe?",
         (("en", r"what (?:do|does) (?:i|you|we|the robot) (?:usually |normally |typically |often )?do after "
                 r"(?:i |you |we )?(?P<task>.+)"),
          ("en", r"what (?:usually )?comes (?:next )?after (?:i |you |we )?(?P<task>.+)"),
          ("de", rf"was {_DO_DE} {_USUALLY_DE},? nachdem (?:ich|du|wir|er) (?P<task>.+?) (?:habe|hast|haben|hat)"),
          ("de", rf"was {_DO_DE} (?:{_USUALLY_DE} )?,? ?nach (?P<task>.+)"),
          ("de", rf"was kommt {_USUALLY_DE} nach (?P<task>.+)"))),
    Form("done", "what did you do this morning / today / this evening?", "was hast du heute morgen / heute / heute abend gemacht?",
         (("en", r"what (?:did|have) (?:you|i|we|the robot) (?:do|done) " + _PART_EN),
          ("de", r"was (?:hast du|habe ich|haben wir|hat der roboter) " + _PART_DE + r" (?:gemacht|getan)"))),
    Form("where", "where is the green mug?", "wo ist der grüne Becher?",
         (("en", r"where (?:is|are) (?P<obj>.+)"),
          ("en", r"where did (?:i|you|we) (?:last )?(?:put|leave|place|see) (?P<obj>.+)"),
          ("de", r"wo (?:ist|steht|liegt|sind) (?P<obj>.+)"),
          ("de", r"wo (?:habe ich|hast du|haben wir) (?P<obj>.+?) (?:zuletzt )?(?:hingestellt|hingelegt|gelassen|gelegt|"
                 r"gestellt|gesehen)"))),
    Form("who", "who usually opens the fridge?", "wer hat meistens den Kühlschrank geöffnet?",
         (("en", r"who (?:usually )?(?:does|did) (?P<task>.+)"),
          ("en", r"who (?:usually |normally )?(?P<task>.+)"),
          ("de", rf"wer (?:macht|machte|hat) {_USUALLY_DE}? ?(?P<task>.+?)(?: gemacht)?"))),
    Form("suggested", "why did you suggest opening the fridge?", "warum hast du vorgeschlagen, den Kühlschrank zu öffnen?",
         (("en", r"why (?:did|do) you suggest (?:that (?:i|we) |to )?(?P<task>.+)"),
          ("de", r"warum hast du vorgeschlagen,? (?:dass ich )?(?P<task>.+)"),
          ("de", r"warum schlägst du (?:mir )?vor,? (?P<task>.+)"),
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


def read_question(text: str, onto: OdbOntology, lexicon: Lexicon | None = None) -> Question:
    """``text`` as a Question; QuestionError naming the forms, the task or the object otherwise.
    ``lexicon``: the tablet's words, when the caller keeps them (default: read here)."""
    if not isinstance(text, str) or not text.strip():
        raise QuestionError(f"ask a question of one of these forms: {forms_line()}")
    said = " ".join(text.strip().rstrip("?!. ").split()).lower()
    book = phrase_book(onto, lexicon)
    problem: QuestionError | None = None
    for form in FORMS:
        for language, pattern in form.patterns:
            found = re.fullmatch(pattern, said)
            if found is None:
                continue
            groups = found.groupdict()
            try:
                task = " ".join(groups[g] for g in ("task", "tail") if groups.get(g))
                calls = resolve_calls(task, onto, book) if task else []
                obj = resolve_object(groups["obj"], onto, book) if groups.get("obj") else None
            except QuestionError as error:  # another pattern may read it (who opens / who does)
                problem = problem or error
                continue
            period = PERIODS[groups["period"]] if groups.get("period") else None
            return Question(form.key, language, calls[0] if calls else None, obj, period, tuple(calls[1:]))
    if problem is not None:
        raise problem
    raise QuestionError(f"{text.strip()!r} is not a question I know; ask one of: {forms_line()}")


def phrase_book(onto: OdbOntology, lexicon: Lexicon | None = None) -> PhraseBook:
    """The words of the ontology's tasks and objects (the tablet's labels, ``lexicon`` when the
    caller keeps them) to read questions with."""
    from oracle.words import load_lexicon

    return PhraseBook(load_lexicon(ontology=onto) if lexicon is None else lexicon, onto)


def resolve_calls(words: str, onto: OdbOntology, book: PhraseBook | None = None) -> list[TaskCall]:
    """The readings of a task in the chain syntax (one) or as words: as a person says it
    (oracle.past.phrases: "den Kühlschrank geöffnet", "opening the fridge"), else the task's
    name then its objects (the longest task name first), checked against the ontology;
    QuestionError naming what is unknown when there is none."""
    words = words.strip().strip(",")
    if "(" not in words:
        said = (book or phrase_book(onto)).calls(words)
        if said:
            return said
        return _calls_from_words(words.replace("_", " ").split(), onto)
    try:
        call = parse_call(words)
        onto.task_iri(call.task)
        for arg in call.args:
            onto.object_iri(arg)
    except (ChainSyntaxError, OntologyError) as error:
        raise QuestionError(str(error)) from None
    return [call]


def resolve_object(words: str, onto: OdbOntology, book: PhraseBook | None = None) -> str:
    """An odb object name from words (``green mug``, ``green_mug``, ``der grüne Becher``);
    QuestionError if unknown."""
    from oracle.suggest import did_you_mean

    name = "_".join(w for w in words.replace("_", " ").split() if w not in _FILLERS)
    if name in onto.objects:
        return name
    said = (book or phrase_book(onto)).obj(words)
    if said is not None:
        return said
    raise QuestionError(f"unknown object {words.strip()!r}.{did_you_mean(name, onto.objects)} Known objects include "
                        f"{', '.join(sorted(onto.objects)[:8])}, ...")


def _calls_from_words(tokens: list[str], onto: OdbOntology) -> list[TaskCall]:
    calls: list[TaskCall] = []
    from oracle.suggest import did_you_mean

    hint = did_you_mean(tokens[0], onto.tasks) if tokens else ""
    problem = f"{' '.join(tokens)!r} does not start with a task name.{hint} Known tasks: {', '.join(sorted(onto.tasks))}" \
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
