"""A NEEM's registry entry (the ``meta`` document): the fields openEASE's NEEM list and the
NEEM handbook read, with this tool's defaults."""

from __future__ import annotations

import hashlib
from collections.abc import Mapping
from datetime import datetime, timezone
from typing import Any
from urllib.parse import quote

from bson.objectid import ObjectId

from oracle.store.validate import check_meta

#: The fields openEASE's NEEM list reads from a ``meta`` document without a default (a
#: document missing one breaks the listing); the others are optional there. docs/store.md.
OPENEASE_FIELDS: tuple[str, ...] = ("name", "description", "created_by", "created_at", "url")


def new_meta(
    user: str | None, temporary: bool, extra: Mapping[str, Any] | None = None, *, name: str | None = None
) -> dict[str, Any]:
    """A registry document with every field openEASE reads; ``extra`` overrides the defaults."""
    meta: dict[str, Any] = {
        "name": name,
        "description": f"Episodes of {user or 'a user'} with an assistive robot, logged by neem-oracle",
        "created_by": user,
        "created_at": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "url": "",  # openEASE links the NEEM's repository; a private store has none (hub_document)
        "model_version": "SOMA/DUL, the neem-oracle core extract",  # the NEEM handbook's fields
        "keywords": ["neem-oracle", "assistive robot", "activities of daily living"],
        "activity": {"name": "activities of daily living", "url": ""}, "environment": "home",
        "agent": "assistive robot arm",
        "visibility": False,  # privacy (thesis 3.5): a NEEM is the user's until they publish it
        "temporary": temporary,
    }
    meta.update(extra or {})
    check_meta(meta, "registry entry")
    return meta


#: The fields openEASE's NEEM hub searches (its ``meta`` collection's ``$text`` index), with
#: their weights: the name first, then what the NEEM is about, then who and where.
HUB_TEXT_FIELDS: dict[str, int] = {"name": 10, "description": 5, "keywords": 5, "activity.name": 3,
                                   "environment": 2, "agent": 2, "created_by": 1}  # fmt: skip
HUB_TEXT_INDEX = "neem_hub_text"
#: Internal fields of our registry that a hub document leaves out.
_PRIVATE = ("temporary", "alias", "summary", "documents", "ontology", "clock", "id")


def hub_text_index() -> dict[str, Any]:
    """The text index of the hub's ``meta`` collection, as mongodump's ``.metadata.json`` and
    ``create_index`` state it."""
    return {"v": 2, "key": {"_fts": "text", "_ftsx": 1}, "name": HUB_TEXT_INDEX, "weights": dict(HUB_TEXT_FIELDS),
            "default_language": "english", "language_override": "language", "textIndexVersion": 3}  # fmt: skip


def hub_id(neem_id: str) -> ObjectId:
    """The hub's ObjectId of a NEEM: its id when that is one (24 hex digits), else one derived
    from it (the first 12 bytes of its SHA-1), so that exporting a NEEM twice gives one id."""
    if ObjectId.is_valid(neem_id) and len(neem_id) == 24:
        return ObjectId(neem_id)
    return ObjectId(hashlib.sha1(neem_id.encode("utf-8")).digest()[:12])


#: Where openEASE looks for a NEEM's repository (its ``NEEM_DOWNLOAD_URL_PREFIX``; the hub's
#: repositories live in its ``neems`` group, which its last-updated look-up reads).
NEEMGIT = "https://neemgit.informatik.uni-bremen.de/"


def hub_url(name: str) -> str:
    """The repository URL openEASE's hub gives a NEEM of this name: ``<neemgit>/neems/<name>``."""
    return f"{NEEMGIT}neems/{quote(name, safe='')}"


def hub_document(meta: Mapping[str, Any], neem_id: str, *, visibility: bool, url: str | None = None) -> dict[str, Any]:
    """The registry entry as a document of openEASE's ``meta`` collection: ``_id`` the NEEM's
    ObjectId (``hub_id``; the collections' prefix of a hub export), every field the hub shows
    (missing ones empty, claiming nothing), and ``visibility`` as chosen.

    ``url``: the NEEM's repository (``export --url``); without one, the entry's own, else the
    URL the hub would give it (``hub_url`` of its name). openEASE keys a NEEM's overview page by
    the last part of ``url`` (or ``repo``) and reads its README.md there: an empty ``url`` gives
    it no page. ``repo`` is that last part, unless the entry names its own."""
    doc: dict[str, Any] = {"_id": hub_id(neem_id)}
    doc.update({k: v for k, v in meta.items() if k not in _PRIVATE and not k.startswith("_")})
    for field in OPENEASE_FIELDS:
        doc.setdefault(field, "")
    if url:
        doc["url"] = url
    elif not doc["url"]:
        doc["url"] = hub_url(str(doc["name"] or neem_id))
    if not doc.get("repo"):
        doc["repo"] = str(doc["url"]).rstrip("/").rsplit("/", 1)[-1]
    doc.setdefault("keywords", [])
    doc["visibility"] = bool(visibility)
    return doc


def loaded_meta(meta: Mapping[str, Any], source: str) -> dict[str, Any]:
    """Registry fields of a NEEM someone else recorded, loaded from ``source`` (a dump folder's
    name): what its dump says, and where it says nothing, no claim that this tool logged it."""
    honest: dict[str, Any] = {
        "description": f"A NEEM loaded from the dump {source!r}",
        "created_by": None,
        "keywords": [],
        "model_version": "",
        "activity": {"name": "", "url": ""},
        "environment": "",
        "agent": "",
    }
    honest.update(meta)
    return honest
