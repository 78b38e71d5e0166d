"""Memory given back between the steps of a long command: ``import`` writes (SQLite's page cache
and the C heap grow to ~180 MiB at 50,000 actions) and then fits (another ~90 MiB); what the
writes freed is returned to the system first, so the two peaks do not add up."""

from __future__ import annotations

import ctypes
import ctypes.util
import gc
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from oracle.store import Store


def give_back(store: Store) -> None:
    """The store's caches freed, Python's garbage collected, and the C heap's free pages
    returned (glibc's malloc_trim; elsewhere nothing: memory then stays as it was)."""
    store.shrink_memory()
    gc.collect()
    name = ctypes.util.find_library("c")
    if name is None:
        return
    try:
        trim = ctypes.CDLL(name).malloc_trim
    except (OSError, AttributeError):
        return  # not glibc
    trim(0)
