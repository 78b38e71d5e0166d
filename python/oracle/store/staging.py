"""Hidden staging NEEMs that outlived their builder: dropped, or swapped in when they were ready.

A staging NEEM (``Store.create_staging``) records the process building it. A killed or failed
import or load leaves it behind, never listed nor read; it holds personal data nobody could see,
list or wipe, so the next writer drops it once that process is gone (one made on another host
after a day). One that was ready to replace a NEEM already dropped (a kill inside ``swap_in`` on
MongoDB, which has no transactions, also one between the renames of its collections) is swapped
in instead.
"""

from __future__ import annotations

import os
import socket
from datetime import datetime, timezone
from typing import TYPE_CHECKING

from oracle.timeline import TimeValueError, parse_iso

if TYPE_CHECKING:
    from oracle.store.base import Store

#: Registry field marking a NEEM under construction (value: the NEEM it will replace).
STAGING = "staging_for"

#: Registry field of a staging NEEM: the process building it ({"host": ..., "pid": ...}).
STAGED_BY = "staged_by"
#: Registry field of a complete staging NEEM about to replace its target: if its builder dies
#: once the old NEEM is dropped (MongoDB has no transaction), the next writer finishes the swap.
READY = "ready_to_swap"

#: A staging NEEM whose builder cannot be checked (another host) is abandoned after this long.
ABANDONED_AFTER_S = 24 * 3600


def builder() -> dict[str, object]:
    """What a staging NEEM records of the process building it."""
    return {"host": socket.gethostname(), "pid": os.getpid()}


def drop_abandoned(store: Store) -> list[str]:
    """Repair or drop every staging NEEM of a dead builder; return the ids dropped."""
    here, now = socket.gethostname(), datetime.now(timezone.utc)
    dropped = []
    for info in store.staging_neems():
        owner = info.meta.get(STAGED_BY)
        if isinstance(owner, dict) and owner.get("host") == here and isinstance(owner.get("pid"), int):
            abandoned = not _process_alive(owner["pid"])
        else:
            abandoned = _age_s(info.created_at, now) > ABANDONED_AFTER_S
        if not abandoned:
            continue
        target = info.meta.get(STAGING)
        if info.meta.get(READY) and isinstance(target, str):
            # Killed between dropping the old NEEM and renaming the new one, or in the middle
            # of renaming its collections: finish the swap.
            if not store.has_neem(target):
                store.rename_neem(info.id, target)
            elif store.interrupted_rename(info.id, target):
                store.finish_rename(info.id, target)
            else:  # the old NEEM is still there: the half-done replacement goes
                store.drop_neem(info.id)
                dropped.append(info.id)
                continue
            store.update_meta(target, **{STAGING: None, STAGED_BY: None, READY: None})
            continue
        store.drop_neem(info.id)
        dropped.append(info.id)
    return dropped


def _process_alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, ValueError):
        return True  # another user's process (or an id that cannot be checked): keep its NEEM
    return True


def _age_s(created_at: object, now: datetime) -> float:
    try:
        made = parse_iso(str(created_at))
    except TimeValueError:
        return float("inf")  # no readable creation time: nobody can be building it still
    if made.tzinfo is None:
        made = made.replace(tzinfo=timezone.utc)
    return (now - made).total_seconds()
