"""A task and its objects as a person says them, read back into a call: "den Kühlschrank
geöffnet", "opening the fridge", "the blue mug" (``ask``, oracle.past.forms).

The words come from the tablet's labels (``ontology/labels.yaml`` and the ontology's tagged
rdfs:labels, oracle.words): each task's templates (the imperative, ``-ing``, German
infinitive and participle), the forms derived from them (English past and third person, German
``zu``-infinitive), and each object's forms (with or without article, dative, content). A noun
is compared with its articles and possessives dropped and German endings cut, so "der blaue
Becher", "den blauen Becher" and "blue mug" name the same object.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

from oracle.chains import TaskCall

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology
    from oracle.words import Lexicon

_SLOT = re.compile(r"\{(\d)(?::(\w+))?\}")
#: Words a noun may start with that name no object: articles, possessives, prepositions.
_LEADING = frozenset(
    "the a an my your our some in into on onto to from at of with off up out "
    "den dem die der das des ein eine einen einem einer mein meine meinen meinem meiner dein deine deinen deinem "
    "unser unsere unseren in im ins auf aufs am an aus mit vom von zum zur etwas".split())
#: The prepositions of a place a thing is put ("in the fridge", "auf die Arbeitsplatte").
_GOAL = r"(?:in|into|inside|on|onto|ins|auf|aufs)\s+"
#: English verbs whose past is not verb + "ed".
_PAST = {"put": "put", "cut": "cut", "eat": "ate", "drink": "drank", "stir": "stirred", "set": "set",
         "take": "took", "make": "made", "get": "got", "pick": "picked", "drop": "dropped"}
#: German separable prefixes: the "zu" of the zu-infinitive goes after them (einzuschalten).
_SEPARABLE = ("aus", "ein", "um", "auf", "ab", "an", "zu", "mit", "weg", "vor", "nach", "zurück")


def stem(word: str) -> str:
    """A word with one German or English ending cut (grünen, grüne -> grün; Kühlschranks ->
    Kühlschrank), so the cases and a plural compare equal."""
    for suffix in ("en", "em", "er", "es", "e", "s", "n"):
        if word.endswith(suffix) and len(word) - len(suffix) >= 4:
            return word[: -len(suffix)]
    return word


def noun_key(text: str) -> str:
    """The comparable core of a noun phrase: lower case, leading articles, possessives and
    prepositions dropped, each word stemmed, underscores as spaces."""
    words = text.lower().replace("_", " ").replace("-", " ").split()
    while words and words[0] in _LEADING:
        words = words[1:]
    return " ".join(stem(w) for w in words)


def english_past(imperative: str) -> str:
    """``open the fridge`` -> ``opened the fridge`` (the first word; ``_PAST`` for the irregular)."""
    verb, _, rest = imperative.partition(" ")
    past = _PAST.get(verb) or (verb + "d" if verb.endswith("e") else verb + "ed")
    return f"{past} {rest}".strip()


def english_third(imperative: str) -> str:
    """``open the fridge`` -> ``opens the fridge``."""
    verb, _, rest = imperative.partition(" ")
    third = verb + ("es" if verb.endswith(("s", "sh", "ch", "x", "z", "o")) else "s")
    return f"{third} {rest}".strip()


def german_zu(infinitive: str) -> str:
    """``{0} einschalten`` -> ``{0} einzuschalten``; ``{0} öffnen`` -> ``{0} zu öffnen``."""
    head, _, verb = infinitive.rpartition(" ")
    prefix = next((p for p in _SEPARABLE if verb.lower().startswith(p) and len(verb) > len(p) + 3), None)
    said = f"{verb[:len(prefix)]}zu{verb[len(prefix):]}" if prefix else f"zu {verb}"
    return f"{head} {said}".strip()


@dataclass(frozen=True)
class Phrase:
    """One way a task is said: the pattern (slots as groups ``a0``, ``a1``) and its task."""

    task: str
    pattern: re.Pattern[str]
    arity: int


class PhraseBook:
    """The task phrases and object nouns of a lexicon, checked against an ontology."""

    def __init__(self, lexicon: Lexicon, onto: OdbOntology) -> None:
        self.onto = onto
        self.nouns: dict[str, str] = {}
        for name, forms in lexicon.objects.items():  # the labels first: "microwave" is not "_microwave"
            if name in onto.objects:
                for said in forms.values():
                    self.nouns.setdefault(noun_key(said), name)
        for name in onto.objects:
            if not name.startswith("_"):  # "_microwave": the class of microwaves, said by no one
                self.nouns.setdefault(noun_key(name), name)
        self.phrases: list[Phrase] = []
        for task, templates in lexicon.tasks.items():
            if task not in onto.tasks:
                continue
            ways = [t for key, t in templates.items() if key in ("en", "en_ing", "de", "de_pp", "en_past", "en_s")]
            if "en" in templates:
                ways += [english_past(templates["en"].lower()), english_third(templates["en"].lower())]
            if "de" in templates:
                ways.append(german_zu(templates["de"]))
            for template in dict.fromkeys(ways):
                self.phrases.append(_phrase(task, template))

    def obj(self, words: str) -> str | None:
        """The object a noun phrase names, or None."""
        return self.nouns.get(noun_key(words))

    def calls(self, words: str) -> list[TaskCall]:
        """Every call the words may say, in the order of the phrases (imperative first)."""
        text = " ".join(words.lower().split())
        found: list[TaskCall] = []
        for phrase in self.phrases:
            match = phrase.pattern.fullmatch(text)
            if match is None:
                continue
            args = [self.obj(match.group(f"a{i}")) for i in range(phrase.arity)]
            if all(args):
                call = TaskCall(phrase.task, tuple(a for a in args if a))
                if call not in found:
                    found.append(call)
        return found


def _phrase(task: str, template: str) -> Phrase:
    """A template ("{0} in {1} gießen") as a pattern: its words literal, each slot any words."""
    parts: list[str] = []
    slots: set[int] = set()
    at = 0
    for found in _SLOT.finditer(template):
        parts.append(_literal(template[at:found.start()]))
        index = int(found.group(1))
        group = f"(?P<a{index}>.+?)" if index not in slots else f"(?P=a{index})"
        # where a thing is put ({1:goal}) is said with its preposition: it ends the thing put
        parts.append(_GOAL + group if found.group(2) == "goal" else group)
        slots.add(index)
        at = found.end()
    parts.append(_literal(template[at:]))
    return Phrase(task, re.compile("".join(parts).strip(), re.IGNORECASE), max(slots, default=-1) + 1)


#: A preposition of a template as it may be said joined with its article ("ins Glas", "into").
_JOINED = {"in": "(?:in|ins|im|into)", "auf": "(?:auf|aufs)", "an": "(?:an|ans|am)", "von": "(?:von|vom)",
           "into": "(?:into|in)", "on": "(?:on|onto)"}


def _literal(text: str) -> str:
    """Template words as a pattern: any run of spaces for a space, a preposition in any of its
    joined forms, case ignored."""
    return r"\s+".join(_JOINED.get(w, re.escape(w)) for w in text.lower().split(" ")) if text else ""
