"""A NEEM's lifecycle (thesis 3.5): keep a session's NEEM under a name, or wipe the temporary ones."""

from __future__ import annotations

from oracle.errors import StoreError
from oracle.store import NeemInfo, Store
from oracle.store.ids import ALIAS_KEY, check_alias, find_neem, resolve_neem
from oracle.store.staging import drop_abandoned


def persist(store: Store, neem: str, name: str) -> NeemInfo:
    """Keep a NEEM (``neem``: its id or alias; thesis 3.5): it keeps its id, is called ``name``
    from now on, and survives the next session start."""
    neem_id = resolve_neem(store, neem)
    check_alias(name)
    other = find_neem(store, name)
    if other is not None and other.id != neem_id:
        raise StoreError(f"{store.location}: the name {name!r} is taken by NEEM {other.id!r}")
    return store.update_meta(neem_id, temporary=False, name=name, **{ALIAS_KEY: name})


def wipe_temporary_neems(store: Store) -> list[str]:
    """Privacy (thesis 3.5): drop every NEEM still marked temporary (a session never persisted),
    and the hidden half-built NEEMs that killed imports and loads left behind."""
    drop_abandoned(store)
    dropped = [info.id for info in store.neems() if info.temporary]
    for neem_id in dropped:
        store.drop_neem(neem_id)
    return dropped
