"""Plain words for the tablet page, in English or German: tasks and objects as a person says them
("Open the fridge", "Pour the beer into the glass"), a ranked task's reason as one short
sentence, the answers in one or two sentences, a time on the person's clock.

Where a name comes from: an ``rdfs:label`` with the language's tag in the ontology, else
``ontology/labels.yaml``, else the name itself with spaces ("the oven knob"). The robot's API
keeps the call syntax; only the page (``GET .../tablet``, ``lang``) is worded here.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from datetime import tzinfo
from pathlib import Path
from typing import Any

from oracle.chains import TaskCall, parse_call
from oracle.errors import ChainSyntaxError, OntologyError
from oracle.timeline import shown_clock

#: The page's languages; the first is the default.
LANGS = ("en", "de")
_SLOT = re.compile(r"\{(\d)(?::(dat|content|goal))?\}")


@dataclass(frozen=True)
class Lexicon:
    """Object forms (``en``, ``de``, ``de_dat``, ``en_content``, ``de_content``) and task
    templates (``en``, ``en_ing``, ``de``, ``de_pp``) by odb name."""

    objects: Mapping[str, Mapping[str, str]]
    tasks: Mapping[str, Mapping[str, str]]


def load_lexicon(path: Path | None = None, ontology: Any = None) -> Lexicon:
    """``ontology/labels.yaml`` (or ``path``), overridden by the ontology's language-tagged
    rdfs:labels of its object classes (``ontology``: an OdbOntology, optional)."""
    from oracle.paths import data_dir
    from oracle.yamlfile import read_yaml

    source = path or data_dir() / "labels.yaml"
    data = read_yaml(source, OntologyError, "labels") if source.exists() else {}
    if not isinstance(data, dict):
        raise OntologyError(f"{source}: expected a mapping with 'objects' and 'tasks'")
    objects = {str(k): dict(v) for k, v in (data.get("objects") or {}).items()}
    tasks = {str(k): dict(v) for k, v in (data.get("tasks") or {}).items()}
    if ontology is not None:
        for name, forms in _tagged_labels(ontology).items():
            objects[name] = {**objects.get(name, {}), **forms}
    return Lexicon(objects, tasks)


def _tagged_labels(ontology: Any) -> dict[str, dict[str, str]]:
    """{object name: {lang: label}} from rdfs:label literals with a language tag (the generated
    labels carry none: they are the odb names; ``OdbOntology.labels``)."""
    labels = ontology.labels
    found: dict[str, dict[str, str]] = {}
    for name, cls in ontology.objects.items():
        for lang, label in labels.get(cls.iri, {}).items():
            if lang in LANGS:
                found.setdefault(name, {})[lang] = label
    return found


def pick_lang(asked: str | None, accept_language: str | None = None) -> str:
    """The page's language: ``asked`` (``?lang=``) when it is one of LANGS, else the first of the
    browser's Accept-Language that is, else English."""
    if asked and asked.lower()[:2] in LANGS:
        return asked.lower()[:2]
    for part in (accept_language or "").split(","):
        code = part.split(";")[0].strip().lower()[:2]
        if code in LANGS:
            return code
    return LANGS[0]


@dataclass(frozen=True)
class Words:
    lexicon: Lexicon
    lang: str
    zone: tzinfo

    @property
    def text(self) -> Mapping[str, str]:
        return TEXT[self.lang]

    # -- names ----------------------------------------------------------------------------------
    def obj(self, name: str, form: str = "") -> str:
        forms = self.lexicon.objects.get(name, {})
        if form == "goal":  # where a thing is put: "in the fridge", else "on the counter"
            found = forms.get(f"{self.lang}_goal")
            return found or f"{self.text['on']} {self.obj(name)}"
        if form == "content":
            found = forms.get(f"{self.lang}_content")
            if found:
                return found
        elif form == "dat" and self.lang == "de":
            found = forms.get("de_dat")
            if found:
                return found
        found = forms.get(self.lang)
        if found:
            return found
        plain = name.replace("_", " ")
        return f"the {plain}" if self.lang == "en" else plain

    def said(self, call: TaskCall | str, form: str = "") -> str:
        """The call as a person says it (``form``: "" the request, "after" what follows "after")."""
        parsed = _parsed(call)
        if parsed is None:
            return str(call)
        key = {"": self.lang, "after": f"{self.lang}_ing" if self.lang == "en" else "de_pp"}[form]
        template = self.lexicon.tasks.get(parsed.task, {}).get(key)
        if template is None:
            args = " ".join(self.obj(a) for a in parsed.args)
            words = parsed.task.replace("_", " ")
            template_text = f"{words} {args}".strip() if self.lang == "en" else f"{args} {words}".strip()
            return _capital(template_text) if not form else template_text
        text = _SLOT.sub(lambda m: self._slot(parsed.args, int(m.group(1)), m.group(2) or ""), template)
        return _capital(text) if not form else text

    def _slot(self, args: Sequence[str], index: int, form: str) -> str:
        return self.obj(args[index], form) if index < len(args) else "?"

    # -- reasons --------------------------------------------------------------------------------
    def reason(self, entry: Mapping[str, Any]) -> str:
        """Why a ranked task stands where it does, as one short sentence (the API's entry)."""
        t = self.text
        n = int(entry.get("support") or 0)
        order = entry.get("context_order")
        if order is None:  # the thesis oracle: the similar past situations
            return t["like_past"].format(n=n) if n else t["new_to_me"]
        times = self.times(n)
        if order > 0:
            context = entry.get("context") or []
            last = context[-1] if context else "idle"
            situations = entry.get("situations") or []
            lately = t["last_at"].format(at=self.clock(float(situations[-1]))) if situations else ""
            if last == "idle":
                return t["after_break"].format(times=times, last=lately)
            return t["after_task"].format(times=times, after=self.said(last, "after"), last=lately)
        held = entry.get("focus") or []
        if entry.get("resumed"):
            return t["resumed"]
        if held:
            return t["in_hand"].format(objects=self.join([self.obj(o) for o in held]))
        if entry.get("new"):
            return t["newly"]
        since = entry.get("since")
        if since is not None:
            return t["since"].format(ago=self.ago(float(since)))
        people = entry.get("people")  # a shared prior's share of what others did next (oracle.algorithm.personal)
        if people is not None and not n:
            return t["people"].format(chance=self.chance(float(people)))
        if order == 0 or entry.get("done"):
            return t["done_elsewhere"].format(times=times) if n else t["done_before"]
        likely = entry.get("probability")
        return t["never"] if likely is None else t["never_likely"].format(chance=self.chance(float(likely)))

    def chance(self, probability: float) -> str:
        """A probability as a natural frequency: "about 4 in 100", "less than 1 in 100"."""
        per_100 = round(100 * probability)
        return self.text["chance_low"] if per_100 < 1 else self.text["chance"].format(n=per_100)

    def times(self, n: int) -> str:
        return self.text["once"] if n == 1 else self.text["n_times"].format(n=n)

    def join(self, items: Sequence[str]) -> str:
        if len(items) <= 1:
            return "".join(items)
        return ", ".join(items[:-1]) + self.text["and"] + items[-1]

    def ago(self, seconds: float) -> str:
        t = self.text
        if seconds < 90:
            return t["ago_s"].format(n=max(0, round(seconds)))
        if seconds < 90 * 60:
            return t["ago_min"].format(n=round(seconds / 60))
        if seconds < 36 * 3600:
            return t["ago_h"].format(n=round(seconds / 3600))
        return t["ago_d"].format(n=round(seconds / 86400))

    # -- times ----------------------------------------------------------------------------------
    def clock(self, seconds: float | None) -> str:
        """A time on the person's clock: ``08:05``, or with the day when it is not today's."""
        if seconds is None:
            return ""
        return shown_clock(float(seconds), self.zone).strftime("%H:%M")

    def routine(self, name: str, left: int) -> str:
        """The page's control for a routine in progress: "Finish “Coffee in the red mug” (3 steps left)"."""
        return (self.text["routine_one"] if left == 1 else self.text["routine_n"]).format(name=name, n=left)

    def part_of_day(self, part: str | None) -> str:
        """The part of the day as said before a clock time: "Morning, 08:04", "morgens, 08:04"."""
        return self.text.get(f"part_{part}", part or "")

    def person(self, user: str | None, meta: Mapping[str, Any] | None = None) -> str:
        """The person's name for the page's header: the NEEM's ``person`` entry, else the user
        when it reads as a name ("ada" -> "Ada"); nothing for an id ("p003-none-blue-yogurt")."""
        named = (meta or {}).get("person")
        if isinstance(named, str) and named.strip():
            return named.strip()
        if user and re.fullmatch(r"[^\W\d_]+(?:[ '][^\W\d_]+)*", user):
            return " ".join(w[:1].upper() + w[1:] for w in user.split(" "))
        return ""

    # -- who does it (thesis 6.3, the autonomy mode) ---------------------------------------------
    def mode(self, mode: str | None, counts: Mapping[str, int], context: str = "call") -> str:
        """Who usually does a task, with how often: "You usually do this yourself (5 of 6 times)."
        ("" when no action of it is known; ``context``: what the counts are of, UsualMode's)."""
        return mode_sentence(self.lang, mode, counts, context)

    def who(self, mode: str) -> str:
        """Who does a step, as the workflow sheet's toggle says it: "You", "The robot", "Together"."""
        return self.text[f"who_{mode}"]


def mode_sentence(lang: str, mode: str | None, counts: Mapping[str, int], context: str = "call") -> str:
    """The usual mode of a task with its support, in ``lang`` (``rank`` prints the English one):
    how often it was done so in the most specific context known (oracle.past.autonomy). Where the
    predictor (oracle.past.modelogit) says another mode than those counts' most frequent, the
    sentence says what is likely, not what is usual, and gives no figure that would contradict it.
    Counts of the task with any objects (``context`` ``task`` or ``task and part``, UsualMode's)
    are said to be of "this kind of task": they are not of this call, which may never have been done."""
    if mode is None:
        return ""
    t = TEXT[lang]
    total = sum(counts.values())
    n = counts.get(mode, 0)
    if not total or n < max(counts.values()):
        return t[f"guess_{mode}"]
    key = f"kind_{mode}" if context.startswith("task") else f"mode_{mode}"
    return t[key].format(of=(t["of_one"] if total == 1 else t["of_n"]).format(n=n, total=total))


def _parsed(call: TaskCall | str) -> TaskCall | None:
    if isinstance(call, TaskCall):
        return call
    try:
        return parse_call(call)
    except ChainSyntaxError:
        return None


def _capital(text: str) -> str:
    return text[:1].upper() + text[1:]


def _read_text(path: Path) -> dict[str, dict[str, str]]:
    """The page's sentences by language, read from the package's own file (JSON: read without
    importing YAML, which the CLI's start would pay for)."""
    import json

    data = json.loads(path.read_text(encoding="utf-8"))
    return {lang: {str(k): str(v) for k, v in data[lang].items()} for lang in LANGS}


#: Every sentence and label the page shows, by language (``words.json`` beside this file: data a
#: translator edits, not code). ``{...}`` are filled in by this module or by the page's script.
TEXT: dict[str, dict[str, str]] = _read_text(Path(__file__).with_name("words.json"))
