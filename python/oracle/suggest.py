"""Did-you-mean: the names closest to a misspelt one (commands, options, NEEMs, tasks, objects)."""

from __future__ import annotations

import difflib
from collections.abc import Iterable


def closest(word: str, candidates: Iterable[str], n: int = 3) -> list[str]:
    """The candidates most like ``word`` (difflib's ratio, at least 0.6), best first; a word that
    differs only in case or ``-``/``_`` comes first."""
    pool = sorted(set(candidates))
    folded = {c.lower().replace("-", "_"): c for c in pool}
    key = word.lower().replace("-", "_")
    exact = [folded[key]] if key in folded and folded[key] != word else []
    found = difflib.get_close_matches(key, list(folded), n=n, cutoff=0.6)
    return exact + [folded[f] for f in found if folded[f] not in exact and folded[f] != word][: n - len(exact)]


def did_you_mean(word: str, candidates: Iterable[str]) -> str:
    """`` Did you mean 'x'?`` (or ``'x' or 'y'``), empty when nothing is close: to end a message."""
    found = closest(word, candidates)
    if not found:
        return ""
    return " Did you mean " + " or ".join(repr(f) for f in found) + "?"
