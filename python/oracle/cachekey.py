"""The user's own key for what this package keeps (kept fits, cached ontologies): an entry is
used only when its tag verifies under the key, so an entry from another account, another machine
or a file someone handed over is dropped and made afresh before a byte of it is decoded.

The key is 32 random bytes in ``key`` of a cache folder that only this user may write (0700,
the file 0600); it is never written into a store, a dump or a request. Without a usable folder
there is no key: nothing kept can be verified, and nothing is kept.
"""

from __future__ import annotations

import contextlib
import hashlib
import hmac
import os
import secrets
import stat
from pathlib import Path

from oracle.files import private_folder, written_by_user_alone

FILE = "key"
_SIZE = 32
TAG = hashlib.sha256().digest_size


def user_key(folder: Path) -> bytes | None:
    """The key kept in ``folder`` (made on first use); None where the folder cannot hold one
    privately (another user's, writable by others, read-only)."""
    try:
        private_folder(folder)
        info = os.stat(folder, follow_symlinks=False)
        if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid() or info.st_mode & 0o077:
            return None
        path = folder / FILE
        for _ in range(2):
            found = _read(path)
            if found is not None:
                return found
            with contextlib.suppress(FileExistsError):
                fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
                with os.fdopen(fd, "wb") as handle:
                    os.fchmod(handle.fileno(), 0o600)
                    handle.write(secrets.token_bytes(_SIZE))
        return _read(path)
    except OSError:
        return None


def _read(path: Path) -> bytes | None:
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except FileNotFoundError:
        return None
    with os.fdopen(fd, "rb") as handle:
        if not written_by_user_alone(os.fstat(handle.fileno())) or os.fstat(handle.fileno()).st_mode & 0o077:
            return None
        data = handle.read(_SIZE + 1)
    return data if len(data) == _SIZE else None


def signed(key: bytes, data: bytes) -> bytes:
    """``data`` behind its tag under ``key``."""
    return hmac.new(key, data, hashlib.sha256).digest() + data


def verified(key: bytes | None, blob: bytes) -> bytes | None:
    """The data ``signed`` put behind a tag that verifies under ``key``; None otherwise."""
    if key is None or len(blob) < TAG:
        return None
    tag, data = blob[:TAG], blob[TAG:]
    return data if hmac.compare_digest(tag, hmac.new(key, data, hashlib.sha256).digest()) else None
