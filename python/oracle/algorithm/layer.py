"""A fork's view of a dict it shares with the dict's owner (``contexts._Level.fork``): the fork's
own entries over the shared dict, which the owner promises to hand down entry by entry before it
changes one (``Layer.keep``), so the fork reads the dict as it was when it was forked without
copying it."""

from __future__ import annotations

from collections.abc import Iterator, MutableMapping
from typing import Any

_GONE = object()  # a context a fork's layer knows was not there when it was made


class Layer(MutableMapping[Any, Any]):
    """A fork's view of a level's dict (``_Level.fork``): its own entries over the dict it was
    forked from (the base). The base is read as it was at the fork: the level that owns it hands
    down a context's entry before changing it (``keep``). Iterates over the same keys as a copy
    of the base with the fork's entries added would."""

    __slots__ = ("own", "base")

    def __init__(self, base: dict[Any, Any]) -> None:
        self.own: dict[Any, Any] = {}
        self.base = base

    def keep(self, key: Any) -> None:
        """The base is about to change ``key``: keep its entry (or its absence) as it is now."""
        if key not in self.own:
            self.own[key] = self.base.get(key, _GONE)

    def get(self, key: Any, default: Any = None) -> Any:
        found = self.own.get(key, _GONE)
        if found is _GONE:
            if key in self.own:
                return default
            return self.base.get(key, default)
        return found

    def __getitem__(self, key: Any) -> Any:
        found = self.get(key, _GONE)
        if found is _GONE:
            raise KeyError(key)
        return found

    def __contains__(self, key: object) -> bool:
        return self.get(key, _GONE) is not _GONE

    def __setitem__(self, key: Any, value: Any) -> None:
        self.own[key] = value

    def __delitem__(self, key: Any) -> None:
        raise TypeError("a level's contexts are never deleted")

    def __iter__(self) -> Iterator[Any]:
        own, base = self.own, self.base
        for key in base:
            if own.get(key) is not _GONE:
                yield key
        for key, value in own.items():
            if value is not _GONE and key not in base:
                yield key

    def __len__(self) -> int:
        return sum(1 for _ in self)
