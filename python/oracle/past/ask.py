"""``ask``: a question about the past answered from the NEEM, with its evidence.

The question is read into a form (oracle.past.forms), the evidence asked of Prolog
(oracle.past.evidence), the sentences made in both languages (oracle.past.sentences). "Now" is
the time given (``--at``) or the NEEM's latest event, so a recorded NEEM is asked about as if
the question came right after it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from oracle.past.evidence import call_words, request, window
from oracle.past.forms import Question, QuestionError, read_question
from oracle.past.kept import KeptPast
from oracle.past.routines import Done, follows
from oracle.past.sentences import Namer, ObjectNamer, sentences

if TYPE_CHECKING:
    from oracle.bridge import Bridge
    from oracle.ontology import OdbOntology
    from oracle.words import Lexicon

@dataclass(frozen=True)
class Answer:
    """An answer: the form it was read as, the question's language, the sentence in English and
    in German, and the evidence (times in unix seconds, tasks in the chain syntax)."""

    question: str
    form: str
    language: str
    english: str
    german: str
    evidence: dict[str, Any] = field(default_factory=dict)

    @property
    def text(self) -> str:
        """The sentence in the question's language."""
        return self.german if self.language == "de" else self.english

    def to_json(self) -> dict[str, Any]:
        return {"question": self.question, "form": self.form, "language": self.language, "text": self.text,
                "english": self.english, "german": self.german, "evidence": self.evidence}


def ask(bridge: Bridge, onto: OdbOntology, text: str, at: float | None = None, clocked: bool = True,
        kept: KeptPast | None = None) -> Answer:
    """Answer ``text`` (one of oracle.past.forms.FORMS) about the NEEM the bridge reads, as of
    ``at`` (default: the NEEM's latest event). QuestionError for a question of no known form.
    ``kept``: what earlier answers read of the NEEM (oracle.past.kept; default: nothing)."""
    kept = KeptPast() if kept is None else kept
    lexicon = kept.lexicon(onto)
    question = _done_reading(bridge, read_question(text, onto, lexicon))
    now = at if at is not None else kept.now(bridge)
    if question.period is not None and not clocked:
        raise QuestionError("this NEEM was logged without a clock (a time-less log): it has no today or morning")
    evidence = {"now": now, **_evidence(bridge, question, now, kept)}
    name, obj = namers(onto, lexicon)
    english, german = sentences(question.form, evidence, name, obj)
    return Answer(text.strip(), question.form, question.language, english, german, evidence)


def namers(onto: OdbOntology, lexicon: Lexicon | None = None) -> tuple[Namer, ObjectNamer]:
    """Tasks and objects in the tablet's words (oracle.words; ``lexicon`` when the caller
    keeps them), a call its words lack in its syntax: what the sentences say instead of code names."""
    from datetime import timezone

    from oracle.past.phrases import english_third
    from oracle.words import Words, load_lexicon

    lexicon = load_lexicon(ontology=onto) if lexicon is None else lexicon
    words = {lang: Words(lexicon, lang, timezone.utc) for lang in ("en", "de")}

    def name(call: str, language: str, way: str) -> str:
        said = words[language]
        if way in ("do", "does"):
            text = said.said(call)
            first = text.split(" ", 1)[0].lower()
            if language == "en" or first in ("der", "die", "das", "den", "dem", "aus", "ein", "eine", "einen"):
                text = text[:1].lower() + text[1:]  # mid-sentence; a German noun keeps its capital
            return english_third(text) if way == "does" else text
        return said.said(call, "after")

    def obj(thing: str, language: str) -> str:
        return words[language].obj(thing)

    return name, obj


def _done_reading(bridge: Bridge, q: Question) -> Question:
    """Of several readings of the task's words, the first the NEEM has an action of (else the
    first): "open fridge" is open(fridge) for a user who never did open_fridge."""
    if q.call is None or not q.readings:
        return q
    for call in (q.call, *q.readings):
        if request(bridge, ["last", *call_words(call), None])["begin"] is not None:
            return replace(q, call=call, readings=())
    return q


def _evidence(bridge: Bridge, q: Question, now: float | None, kept: KeptPast) -> dict[str, Any]:
    if q.form == "where":
        return request(bridge, ["where", q.obj, now])
    if q.form == "done":
        assert q.period is not None
        start, end = window(q.period, now) if now is not None else (0.0, 0.0)
        reply = request(bridge, ["done", start, end])
        return {**reply, "period": q.period, "from": start, "to": end}
    assert q.call is not None
    if q.form == "last":
        return request(bridge, ["last", *call_words(q.call), now])
    if q.form == "after":
        return usual_after(str(q.call), kept.done(bridge))
    if q.form == "who":
        return _who(bridge, q, now)
    if q.form == "count":
        assert q.period is not None
        start, end = window(q.period, now) if now is not None else (0.0, 0.0)
        return {**request(bridge, ["count", *call_words(q.call), start, end]), "period": q.period,
                "from": start, "to": end}
    return _suggested(bridge, q, now, kept)


def _suggested(bridge: Bridge, q: Question, now: float | None, kept: KeptPast) -> dict[str, Any]:
    """The latest preference that ranked the call, and what preceded it: the last action before
    it and how often the call followed that action."""
    assert q.call is not None
    reply = request(bridge, ["suggested", *call_words(q.call), now])
    if reply["time"] is None:
        return reply
    at = float(reply["time"])
    reply = {**reply, "routine": _routine_step(bridge, kept, at, reply["task"])}
    found = request(bridge, ["before", at, 1])["actions"]
    if not found:
        return {**reply, "before": None}
    last = found[-1]
    previous = last["task"]
    after = usual_after(previous, kept.done(bridge))
    followed = next((n["count"] for n in after["next"] if n["task"] == reply["task"]), 0)
    return {**reply, "before": {"task": previous, "time": last["begin"], "occurrences": after["occurrences"],
                                "followed": followed}}


def _routine_step(bridge: Bridge, kept: KeptPast, at: float, task: str) -> dict[str, Any] | None:
    """The routine in progress at ``at`` when ``task`` is its next step (oracle.past.mine)."""
    from oracle.past.mine import neem_routines

    current = neem_routines(bridge, at, kept=kept).current
    if current is None or current.remaining[:1] != (task,):
        return None
    return {"key": current.routine.key, "name": current.routine.name, "left": len(current.remaining)}


def usual_after(call: str, done: list[Done]) -> dict[str, Any]:
    """What followed ``call`` (oracle.past.routines.follows) in the NEEM's actions ``done``
    (oracle.past.kept: its kept history), in the shape of odb_past's `after` answer."""
    n, counts = follows(done, call)
    return {"task": call, "occurrences": n, "next": [{"task": t, "count": k} for t, k in counts]}


def _who(bridge: Bridge, q: Question, now: float | None) -> dict[str, Any]:
    """Who performed the call's actions (odb_past:performers/2) and who usually does it in the
    part of the day of now (oracle.past.autonomy, from the call's own actions)."""
    from oracle.chains import MODES
    from oracle.past.autonomy import ModeCounts, Performed
    from oracle.timeline import part_of_day_at

    reply = request(bridge, ["who", *call_words(q.call)])  # type: ignore[arg-type]
    model = ModeCounts()
    for row in reply["modes"]:
        if row["mode"] != "unknown":
            model.add(Performed(reply["task"], part_of_day_at(row["time"]), row["mode"]))
    part = part_of_day_at(now) if now is not None else "Midday"
    usual, source = model.predict(reply["task"], part)
    counts = {mode: sum(1 for r in reply["modes"] if r["mode"] == mode) for mode in (*MODES, "unknown")}
    return {**reply, "usual": usual if source != "none" else None, "part": part, "counts": counts}
