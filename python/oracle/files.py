"""Files that hold a person's data (chains, dumps): private, complete, never written through a link.

A file is written beside its place as ``.NAME.XXXX.part`` (0600, created exclusively, never
through a symlink) and moved onto its place only when complete, so a full disk or a kill leaves
an earlier file as it was; folders the writer creates are 0700 whatever the umask.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import hmac
import os
import secrets
import shutil
import stat
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any, ClassVar, TextIO, TypeVar

from oracle.errors import NeemOracleError

_Cache = TypeVar("_Cache", bound="CacheFolder")
_Value = TypeVar("_Value")


def written_by_user_alone(info: os.stat_result) -> bool:
    """Whether a file (its ``stat``) is a regular file of this user that nobody else may write:
    the only kind a cache reads back."""
    return stat.S_ISREG(info.st_mode) and info.st_uid == os.getuid() and not info.st_mode & 0o022


def private_folder(path: Path) -> Path:
    """``path`` and the missing folders above it, each created 0700 (existing ones are left as they are)."""
    missing = [folder for folder in [path, *path.parents] if not folder.exists()]
    for folder in reversed(missing):
        folder.mkdir(mode=0o700)
        os.chmod(folder, 0o700)  # the umask may have taken bits away; it never adds any
    return path


@contextlib.contextmanager
def private_file(path: Path | str) -> Iterator[TextIO]:
    """Write ``path`` privately and atomically (see the module's docstring); OSError on failure,
    with the place untouched."""
    with _private(Path(path), "w") as handle:
        yield handle


def write_private_bytes(path: Path | str, data: bytes) -> None:
    """``data`` as the file ``path``, privately and atomically (as ``private_file``)."""
    with _private(Path(path), "wb") as handle:
        handle.write(data)


@contextlib.contextmanager
def _private(path: Path, mode: str) -> Iterator[Any]:
    if path.is_symlink():
        raise OSError(errno.ELOOP, "is a symbolic link; refusing to write through it", str(path))
    private_folder(path.parent)
    temporary = path.with_name(f".{path.name}.{os.urandom(4).hex()}.part")
    fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
    try:
        os.fchmod(fd, 0o600)
        handle: IO[Any]
        with (os.fdopen(fd, "wb") if mode == "wb" else os.fdopen(fd, "w", encoding="utf-8")) as handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(temporary, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)


#: Entries kept per kind in the user's cache (ontologies, distance matrices, compiled modules,
#: fits, histories); the least recently used go first.
MAX_CACHE_ENTRIES = 32


def used(path: Path) -> None:
    """Mark a cache entry as just used (its modification time), so pruning keeps it."""
    with contextlib.suppress(OSError):
        os.utime(path)


def prune_cache(directory: Path, pattern: str, keep: int = MAX_CACHE_ENTRIES) -> None:
    """Remove all but the ``keep`` most recently used entries (files or folders) of ``directory``
    matching ``pattern``: a cache keyed by content would otherwise keep every odb, mapping and
    source version it ever saw."""
    try:
        entries = sorted(((entry.stat().st_mtime, entry) for entry in directory.glob(pattern)), reverse=True)
    except OSError:
        return
    for _, old in entries[keep:]:
        with contextlib.suppress(OSError):
            if old.is_dir() and not old.is_symlink():
                shutil.rmtree(old)
            else:
                old.unlink()


#: The user's own key for what this package keeps (kept fits, cache entries): 32 random bytes
#: in ``key`` of a private cache folder (0700, the file 0600), never written into a store, a dump
#: or a request. An entry is read only when its tag verifies under it, so one from another account,
#: another machine or a file someone handed over is made afresh before a byte of it is decoded.
KEY_FILE = "key"
_SIZE = 32
TAG_BYTES = hashlib.sha256().digest_size


def user_key(folder: Path) -> bytes | None:
    """The key kept in ``folder`` (made on first use); None where the folder cannot hold one
    privately (another user's, writable by others, read-only)."""
    try:
        private_folder(folder)
        info = os.stat(folder, follow_symlinks=False)
        if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid() or info.st_mode & 0o077:
            return None
        path = folder / KEY_FILE
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
    if key is None or len(blob) < TAG_BYTES:
        return None
    tag, data = blob[:TAG_BYTES], blob[TAG_BYTES:]
    return data if hmac.compare_digest(tag, hmac.new(key, data, hashlib.sha256).digest()) else None


def cached_plain(path: Path, key: str, make: Callable[[], _Value], encode: Callable[[_Value], Any],
                 decode: Callable[[Any], _Value], pattern: str, former: str | None = None) -> _Value:
    """The value kept at ``path`` for ``key``, or else ``make()``, then kept there. An entry is
    JSON (``{"key": ..., "value": encode(value)}``): reading it makes lists, dicts, strings and
    numbers, which ``decode`` turns back into the value, checking each part as it goes; nothing in
    the bytes names code, and nothing is unpickled. It is read only when it is a regular file of
    this user that nobody else may write and its HMAC tag verifies under the key kept in the same
    private folder (``user_key``), so a file put there by anyone else, or copied from another
    account, is made again before a byte of it is decoded; one ``decode`` refuses (any error) is
    made again too. The entries of the folder matching ``pattern`` are pruned (``prune_cache``),
    and those matching ``former`` (an earlier format's, never read now) removed when an entry is
    written; a folder that cannot be written only makes every call make the value."""
    import json

    secret = user_key(path.parent)
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
        with os.fdopen(fd, "rb") as handle:
            data = verified(secret, handle.read()) if written_by_user_alone(os.fstat(handle.fileno())) else None
        if data is not None:
            entry = json.loads(data)
            if isinstance(entry, dict) and entry.get("key") == key:
                value = decode(entry["value"])
                used(path)
                return value
    except Exception:  # noqa: BLE001 - missing, damaged or refused by decode: made again below
        pass
    value = make()
    if secret is None:
        return value  # nothing kept that could not be verified
    try:
        text = json.dumps({"key": key, "value": encode(value)}, separators=(",", ":"), ensure_ascii=False)
        write_private_bytes(path, signed(secret, text.encode("utf-8")))
        prune_cache(path.parent, pattern)
        if former is not None:
            prune_cache(path.parent, former, keep=0)
    except (OSError, TypeError, ValueError, NeemOracleError):
        pass  # caching is an optimisation
    return value


def default_key_dir() -> Path:
    """Where the user's own key of kept fits lives (``user_key``): ``$NEEM_ORACLE_KEY_DIR``, else
    the platform's configuration folder (``~/.config/neem-oracle`` on Linux). Not the cache:
    a fit kept in a store outlives a cleared or moved cache."""
    override = os.environ.get("NEEM_ORACLE_KEY_DIR")
    if override:
        return Path(override)
    import platformdirs

    return Path(platformdirs.user_config_dir("neem-oracle"))


def default_cache_dir() -> Path:
    """The user's private cache of this package: ``$NEEM_ORACLE_CACHE``, else the platform's
    (``~/.cache/neem-oracle`` on Linux)."""
    override = os.environ.get("NEEM_ORACLE_CACHE")
    if override:
        return Path(override)
    import platformdirs

    return Path(platformdirs.user_cache_dir("neem-oracle"))


@dataclass(frozen=True)
class CacheFolder:
    """A folder of the user's private cache (``FOLDER`` of ``default_cache_dir``) with one
    ``*SUFFIX`` file per entry, the least recently written pruned."""

    root: Path
    FOLDER: ClassVar[str] = ""
    SUFFIX: ClassVar[str] = ""
    #: Entries kept; the least recently written go first.
    MAX_ENTRIES: ClassVar[int] = MAX_CACHE_ENTRIES

    @classmethod
    def default(cls: type[_Cache]) -> _Cache:
        return cls(default_cache_dir() / cls.FOLDER)

    def _prune(self) -> None:
        prune_cache(self.root, f"*{self.SUFFIX}", self.MAX_ENTRIES)

    def _store(self, path: Path, data: bytes) -> None:
        """Keep ``data`` at ``path`` (private) and prune; a folder that is read-only or full only
        means the next call makes the entry afresh."""
        try:
            write_private_bytes(path, data)
            self._prune()
        except OSError:
            return
