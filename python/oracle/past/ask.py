"""``ask``: a question about the past answered from the NEEM, with its evidence.

The question is read into a form (oracle.past.forms), the evidence asked of Prolog
(oracle.past.evidence), the sentences made in both languages (oracle.past.sentences). "Now" is
the time given (``--at``) or the NEEM's latest event, so a recorded NEEM is asked about as if
the question came right after it.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from oracle.past.evidence import call_words, now_of, request, window
from oracle.past.forms import Question, QuestionError, read_question
from oracle.past.sentences import sentences

if TYPE_CHECKING:
    from oracle.bridge import Bridge
    from oracle.ontology import OdbOntology

#: How far back "why did you suggest" looks for the action before the suggestion (seconds).
BEFORE_WINDOW_S = 24 * 3600.0


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


def ask(bridge: Bridge, onto: OdbOntology, text: str, at: float | None = None, clocked: bool = True) -> Answer:
    """Answer ``text`` (one of oracle.past.forms.FORMS) about the NEEM the bridge reads, as of
    ``at`` (default: the NEEM's latest event). QuestionError for a question of no known form."""
    question = _done_reading(bridge, read_question(text, onto))
    now = at if at is not None else now_of(bridge)
    if question.period is not None and not clocked:
        raise QuestionError("this NEEM was logged without a clock (a time-less log): it has no today or morning")
    evidence = {"now": now, **_evidence(bridge, question, now)}
    english, german = sentences(question.form, evidence)
    return Answer(text.strip(), question.form, question.language, english, german, evidence)


def _done_reading(bridge: Bridge, q: Question) -> Question:
    """Of several readings of the task's words, the first the NEEM has an action of (else the
    first): "open fridge" is open(fridge) for a user who never did open_fridge."""
    if q.call is None or not q.readings:
        return q
    for call in (q.call, *q.readings):
        if request(bridge, ["last", *call_words(call), None])["begin"] is not None:
            return replace(q, call=call, readings=())
    return q


def _evidence(bridge: Bridge, q: Question, now: float | None) -> dict[str, Any]:
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
        return request(bridge, ["after", *call_words(q.call)])
    if q.form == "count":
        assert q.period is not None
        start, end = window(q.period, now) if now is not None else (0.0, 0.0)
        return {**request(bridge, ["count", *call_words(q.call), start, end]), "period": q.period,
                "from": start, "to": end}
    return _suggested(bridge, q, now)


def _suggested(bridge: Bridge, q: Question, now: float | None) -> dict[str, Any]:
    """The latest preference that ranked the call, and what preceded it: the last action before
    it and how often the call followed that action."""
    assert q.call is not None
    reply = request(bridge, ["suggested", *call_words(q.call), now])
    if reply["time"] is None:
        return reply
    at = float(reply["time"])
    done = request(bridge, ["done", at - BEFORE_WINDOW_S, at])["actions"]
    if not done:
        return {**reply, "before": None}
    previous = done[-1]["task"]
    from oracle.chains import parse_call

    after = request(bridge, ["after", *call_words(parse_call(previous))])
    followed = next((n["count"] for n in after["next"] if n["task"] == reply["task"]), 0)
    return {**reply, "before": {"task": previous, "time": done[-1]["begin"], "occurrences": after["occurrences"],
                                "followed": followed}}
