"""A NEEM's lifecycle (thesis 3.5): keep a session's NEEM under a name, or wipe the temporary ones."""

from __future__ import annotations

from oracle.store import NeemInfo, Store
from oracle.store.staging import drop_abandoned


def persist(store: Store, neem_id: str, name: str) -> NeemInfo:
    """Keep a NEEM (thesis 3.5): it gets the id ``name`` and survives the next session start."""
    store.rename_neem(neem_id, name)
    return store.update_meta(name, temporary=False, name=name)


def wipe_temporary_neems(store: Store) -> list[str]:
    """Privacy (thesis 3.5): drop every NEEM still marked temporary (a session never persisted),
    and the hidden half-built NEEMs that killed imports and loads left behind."""
    drop_abandoned(store)
    dropped = [info.id for info in store.neems() if info.temporary]
    for neem_id in dropped:
        store.drop_neem(neem_id)
    return dropped
