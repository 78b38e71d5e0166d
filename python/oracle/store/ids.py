"""NEEM ids as openEASE lists them (24-hex ObjectIds) and the human aliases beside them: the one
place a name a user types (an alias or an id) becomes the id a store keys its NEEM by."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from bson import ObjectId

from oracle.errors import StoreError

if TYPE_CHECKING:
    from oracle.store.base import NeemInfo, Store

#: Registry field holding a NEEM's human name (what ``--neem`` and the service accept besides
#: the id); openEASE shows ``name``, which a new NEEM also gets.
ALIAS_KEY = "alias"

_OBJECT_ID = re.compile(r"^[0-9a-f]{24}$")
_ALIAS = re.compile(r"^[A-Za-z0-9][A-Za-z0-9.\-]{0,63}$")


def new_neem_id() -> str:
    """A fresh ObjectId in hex, openEASE's NEEM id (time first, so ids sort by creation)."""
    return str(ObjectId())


def is_object_id(text: str) -> bool:
    return isinstance(text, str) and _OBJECT_ID.match(text) is not None


def check_alias(alias: str) -> str:
    """An alias is typed on command lines and in URLs: 1-64 letters, digits, '.' and '-'; a
    24-hex alias would read as an id, so it is refused."""
    if not isinstance(alias, str) or not _ALIAS.match(alias) or is_object_id(alias):
        raise StoreError(
            f"invalid NEEM name {alias!r}: use 1-64 letters, digits, '.' and '-' (not 24 hex digits, that is an id)"
        )
    return alias


def alias_of(info: NeemInfo) -> str | None:
    alias = info.meta.get(ALIAS_KEY)
    return alias if isinstance(alias, str) else None


def find_neem(store: Store, name: str) -> NeemInfo | None:
    """The NEEM ``name`` names (its id, else its alias), None when none does; StoreError when
    several NEEMs share the alias (loaded from two stores): the id tells them apart."""
    if not isinstance(name, str) or not name:
        raise StoreError(f"a NEEM name must be a non-empty string, got {name!r}")
    infos = store.neems()
    for info in infos:
        if info.id == name:
            return info
    named = [info for info in infos if alias_of(info) == name]
    if len(named) > 1:
        ids = ", ".join(info.id for info in named)
        raise StoreError(f"{store.location}: NEEM name {name!r} is ambiguous ({ids}); give the id")
    return named[0] if named else None


def resolve_neem(store: Store, name: str) -> str:
    """The id of the NEEM ``name`` names (an id or an alias); a one-line StoreError otherwise."""
    info = find_neem(store, name)
    if info is None:
        from oracle.suggest import did_you_mean

        known = [str(n) for info in store.neems() for n in (info.id, alias_of(info)) if n]
        raise StoreError(f"{store.location}: no NEEM {name!r} (neither an id nor a name; see 'neems')."
                         f"{did_you_mean(name, known)}")
    return info.id


def check_alias_free(store: Store, staging: str, target: str) -> None:
    """The alias of the NEEM being swapped in as ``target`` names no other NEEM (StoreError)."""
    alias = store.neem(staging).meta.get(ALIAS_KEY)
    if not isinstance(alias, str):
        return
    other = next((info for info in store.neems() if info.id != target and alias in (info.id, alias_of(info))), None)
    if other is not None:
        raise StoreError(f"{store.location}: the name {alias!r} is taken by NEEM {other.id!r} (choose another name)")


def unique_alias(store: Store, base: str) -> str:
    """``base``, or ``base-2``, ``base-3``... : the first that names no NEEM yet."""
    infos = store.neems()
    taken = {info.id for info in infos} | {alias for alias in map(alias_of, infos) if alias is not None}
    alias, n = base, 1
    while alias in taken:
        n += 1
        alias = f"{base}-{n}"
    return alias


__all__ = ["ALIAS_KEY", "alias_of", "check_alias", "find_neem", "is_object_id", "new_neem_id", "resolve_neem",
           "unique_alias"]
