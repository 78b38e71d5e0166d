"""Which NEEM a question names when its asker names none: the service's (``serve --neem``), else
the store's only one. KnowRob's clients (rosprolog, openEASE's console) have no NEEM argument, so
a store of one NEEM needs no choosing; with several, guessing (the newest, say) would answer
about the wrong user without a word, so the asker is told how to choose."""

from __future__ import annotations

from oracle.errors import StoreError
from oracle.store import Store
from oracle.store.ids import alias_of


def store_neem(store: Store, how: str) -> str:
    """The id of the store's only NEEM; a one-line StoreError naming ``how`` to choose when the
    store holds none or several."""
    infos = store.neems()
    if not infos:
        raise StoreError("the store holds no NEEM yet: log one first (POST /api/neems)")
    if len(infos) > 1:
        names = [alias_of(info) or info.id for info in infos]
        shown = ", ".join(names[:6]) + (", ..." if len(names) > 6 else "")
        raise StoreError(f"the store holds {len(infos)} NEEMs ({shown}): choose one with {how}")
    return infos[0].id
