"""Words of names, labels and comments, for matching odb entries to SOMA/DUL classes by text.

A name is split at ``_``, ``-``, digits and CamelCase; each word is lower-cased and cut to a
stem by a few English inflection rules (no word list, no WordNet), so ``PickingUp`` and
``pick_up``, ``Pouring`` and ``pour``, ``Containers`` and ``container`` meet.
"""

from __future__ import annotations

import re

_CAMEL = re.compile(r"[A-Z]+(?=[A-Z][a-z])|[A-Z]?[a-z]+|[A-Z]+|[0-9]+")
_WORD = re.compile(r"[A-Za-z]+")
#: Words too common in SOMA's comments to say anything about a class.
STOP_WORDS = frozenset(
    "a an the of to and or in on at by for from with without as is are be been being it its this that these those "
    "which who whom whose some any such other than then there their them they can may might must should would "
    "could will not no only also into onto out up down over under e g i ie eg etc one two used use using".split()
)


def stem(word: str) -> str:
    """A crude English stem: plural and verb endings off, a doubled final consonant undone."""
    w = word.lower()
    for suffix, keep in (("ies", "y"), ("sses", "ss"), ("ing", ""), ("ed", ""), ("es", ""), ("s", "")):
        if w.endswith(suffix) and len(w) - len(suffix) >= 3 and not (suffix == "s" and w.endswith("ss")):
            w = w[: len(w) - len(suffix)] + keep
            break
    if len(w) >= 4 and w[-1] == w[-2] and w[-1] not in "lsz":
        w = w[:-1]  # cutting -> cutt -> cut
    if len(w) >= 4 and w.endswith("e"):
        w = w[:-1]  # release / releasing meet at "releas"
    return w


def name_words(name: str) -> tuple[str, ...]:
    """``edans_ikea_kitchen_door`` -> (edan, ikea, kitchen, door); ``PickingUp`` -> (pick, up)."""
    words: list[str] = []
    for part in re.split(r"[_\-\s.]+", name):
        for token in _CAMEL.findall(part):
            if token.isdigit():
                continue
            words.append(stem(token))
    return tuple(w for w in words if w)


def text_words(text: str) -> tuple[str, ...]:
    """The stems of a comment's words, stop words left out."""
    return tuple(stem(w) for w in _WORD.findall(text) if w.lower() not in STOP_WORDS and len(w) > 1)


def joined(name: str) -> str:
    """``dish_washer`` and ``Dishwasher`` -> ``dishwasher``: compounds written apart or together."""
    return re.sub(r"[^a-z]", "", name.lower())
