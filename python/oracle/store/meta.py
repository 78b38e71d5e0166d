"""A NEEM's registry entry (the ``meta`` document): the fields openEASE's NEEM list and the
NEEM handbook read, with this tool's defaults."""

from __future__ import annotations

from collections.abc import Mapping
from datetime import datetime, timezone
from typing import Any

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
        "url": "",  # openEASE links the NEEM's repository; a private store has none
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
