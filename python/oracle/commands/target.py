"""The NEEM a command works on: its store (never created), its id, its ontology, its bridge."""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from typing import TYPE_CHECKING

from oracle.commands.common import ontology_from
from oracle.errors import StoreError

if TYPE_CHECKING:
    from oracle.bridge import Bridge
    from oracle.ontology import OdbOntology
    from oracle.store import Store

#: The options that name an ontology; when none is given, the NEEM's own ontology is used.
ONTOLOGY_DESTS = ("odb", "mapping", "soma", "ontology")


@dataclass(frozen=True)
class Target:
    store: Store
    neem_id: str
    onto: OdbOntology


def open_target(args: argparse.Namespace, *, write: bool = False) -> Target:
    """Open ``--store`` (read-only unless ``write``: a reader never waits for a writer; a writer's
    whole-file check runs beside its reads), pick
    ``--neem`` and the ontology the NEEM was logged with."""
    from oracle.ontology.reopen import ontology_for
    from oracle.store import open_store
    from oracle.store.ids import alias_of, resolve_neem

    store = open_store(args.store, create=False, read_only=not write, check_while_reading=write)
    try:
        neem_id = resolve_neem(store, args.neem) if args.neem is not None else default_neem(store)
        info = store.neem(neem_id)
        given = ontology_from(args) if any(getattr(args, name, None) is not None for name in ONTOLOGY_DESTS) else None
        name = alias_of(info) or neem_id  # messages name the NEEM as the user knows it
        onto = ontology_for(name, info.meta, given, lambda: ontology_from(args))
    except BaseException:
        store.close()
        raise
    return Target(store, neem_id, onto)


def default_neem(store: Store) -> str:
    """The store's only NEEM. With several, guessing (say, the newest) would answer about the
    wrong user without a word, so the user is asked to choose."""
    from oracle.store.ids import alias_of

    infos = store.neems()
    ids = [info.id for info in infos]
    if not ids:
        raise StoreError(f"{store.location}: the store holds no NEEM; log one first")
    if len(ids) > 1:
        names = [alias_of(info) or info.id for info in infos]
        shown = ", ".join(names[:6]) + (", ..." if len(names) > 6 else "")
        raise StoreError(f"{store.location} holds {len(ids)} NEEMs ({shown}); choose one with --neem")
    return ids[0]


def connect(args: argparse.Namespace, *, write: bool = False) -> tuple[Bridge, OdbOntology]:
    """The Prolog bridge over the NEEM ``--store``/``--neem`` name, with the NEEM's ontology
    (``open_target``: the store is never created, several NEEMs need ``--neem``; it is
    opened read-only unless ``write``)."""
    from oracle.bridge import Bridge

    target = open_target(args, write=write)
    return Bridge(target.store, target.neem_id, target.onto), target.onto
