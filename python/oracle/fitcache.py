"""The fitted predictor of a NEEM's history, kept between calls: a rank after one more action
adds that action to the model fitted before instead of fitting the whole history again.

One entry per NEEM and predictor, kept in the store beside the NEEM where the store can keep
it (oracle.store.kept; one fit per NEEM there, so the first rank after an import finds the fit
the import made), else a file in the user's private cache (``fits/`` beside the compiled Prolog
modules; folder 0700, file 0600). Its key is a digest of everything a fit depends on besides
the history: the predictor's class and parameters, the distance matrix's content, the source of
``oracle.algorithm`` and the Python and numpy versions.

An entry is never unpickled. It is plain data (oracle.plainstate: JSON and raw arrays, only the
predictors' own classes), behind a tag under the user's own key (oracle.files.user_key, kept in the
user's configuration folder, never in the store): the key, the number of steps fitted, the digest of those
steps and the model without its distance matrix (the caller's, of the same content, is put
back). A store may come from someone else: an entry whose tag does not verify (written on
another account or machine, damaged, planted) is dropped before any of it is decoded, the model
is fitted afresh, and one line in the log says so.

A predictor takes part when it has ``extend(history)`` (the routine predictor: the model
``fit(history)`` gives, from the one fitted on a prefix of it, bit for bit). An entry is used
only when its steps are exactly the first steps of the history; otherwise, and when it is
missing, damaged, or not the user's own, the model is fitted afresh and the entry replaced. The
cache is an optimisation: a folder that cannot be written only makes every call fit afresh.
"""

from __future__ import annotations

import hashlib
import importlib
import json
import logging
import os
import pickle
import pkgutil
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

import oracle.algorithm
from oracle import plainstate
from oracle.algorithm.records import Step
from oracle.files import CacheFolder, default_key_dir, signed, user_key, verified, written_by_user_alone

if TYPE_CHECKING:
    from oracle.store.base import Store

LOG = logging.getLogger("oracle.fitcache")
_FORMAT = b"neem-oracle fit 3\n"
#: The kind of entry the store keeps (oracle.store.kept).
KIND = "fit"
#: The largest kept entry read (a fit of 50,000 actions is about 4 MB).
MAX_ENTRY_BYTES = 256 << 20


@dataclass(frozen=True)
class FitCache(CacheFolder):
    """Fitted models under ``root`` (one file each), tagged under the key kept in ``root``."""

    FOLDER: ClassVar[str] = "fits"
    SUFFIX: ClassVar[str] = ".fit"
    #: The folder of the key entries are tagged under (None: the user's, ``default_key_dir``).
    keys: Path | None = None

    def fitted(self, model: Any, steps: Sequence[Step], store: str, neem: str, *, keep: bool = True,
               kept: Store | None = None) -> Any:
        """``model.fit(steps)``, extended from the entry of NEEM ``neem`` of the store at
        ``store`` (its location; ``kept``: the store itself, which may keep the entry) when the
        entry's steps are the first steps of ``steps``; the entry then holds the new fit.
        ``keep`` False (a temporary NEEM, wiped when its session ends: nothing made from it may
        outlive it) fits afresh and keeps nothing."""
        if not keep or not callable(getattr(model, "extend", None)):
            return model.fit(steps)
        key = _entry_key(model, neem)
        secret = user_key(self.keys or default_key_dir())
        path = self.root / f"{_file_name(key, store)}{self.SUFFIX}"
        entries = [raw for raw in (None if kept is None else kept.read_kept(neem, KIND), self._load(path)) if raw]
        cached = _best(entries, secret, key, model, steps, neem)
        if cached is not None and callable(getattr(model, "use_prior", None)):
            cached.use_prior(model.prior)  # a prior is never kept with a fit: the steps to add learn with it
        if cached is not None and cached.fitted_steps_ == len(steps):
            return cached
        fitted = cached.extend(steps) if cached is not None else model.fit(steps)
        data = None if secret is None else _dumps(secret, key, fitted, steps)
        if data is not None and (kept is None or not kept.write_kept(neem, KIND, data)):
            self._store(path, data)
        return fitted

    def _load(self, path: Path) -> bytes | None:
        try:
            fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
        except OSError:
            return None
        with os.fdopen(fd, "rb") as handle:
            info = os.fstat(handle.fileno())
            if not written_by_user_alone(info) or info.st_size > MAX_ENTRY_BYTES:
                return None
            return handle.read(MAX_ENTRY_BYTES)


def model_classes(model: Any) -> dict[str, type]:
    """The classes a kept model may hold: ``model``'s own and those defined in the modules of
    ``oracle.algorithm`` (by exact name; nothing named in an entry is looked up anywhere else)."""
    modules = [importlib.import_module(f"oracle.algorithm.{info.name}")
               for info in pkgutil.iter_modules(oracle.algorithm.__path__)]
    return {**plainstate.classes_of(modules), plainstate.class_name(type(model)): type(model)}


def _dumps(secret: bytes, key: str, model: Any, steps: Sequence[Step]) -> bytes | None:
    try:
        body = plainstate.dumps(model, model_classes(model), shared=model.distances)
    except plainstate.PlainStateError as error:
        LOG.debug("a fit of %s is not kept: %s", type(model).__name__, error)
        return None
    head = json.dumps({"key": key, "steps": len(steps), "digest": _steps_digest(steps)}).encode()
    return _FORMAT + signed(secret, len(head).to_bytes(4, "little") + head + body)


def _opened(raw: bytes, secret: bytes | None) -> tuple[Mapping[str, Any], bytes] | None:
    """An entry's head and model bytes, when its tag verifies under ``secret``."""
    if not raw.startswith(_FORMAT):
        return None
    data = verified(secret, raw[len(_FORMAT):])
    if data is None or len(data) < 4:
        return None
    size = int.from_bytes(data[:4], "little")
    try:
        head = json.loads(data[4:4 + size])
    except ValueError:
        return None
    return (head, data[4 + size:]) if isinstance(head, dict) else None


def _best(entries: Sequence[bytes], secret: bytes | None, key: str, model: Any, steps: Sequence[Step],
          neem: str) -> Any | None:
    """The model of the kept entry that fitted the most of ``steps``. Each entry's tag is checked
    first, then its head (its key, its number of steps and their digest); only the chosen one's
    model is decoded (4 MB at 50,000 actions), and a damaged one gives way to the next."""
    digests: dict[int, str] = {}
    heads = []
    for raw in entries:
        opened = _opened(raw, secret)
        if opened is None:
            LOG.warning("a kept fit of NEEM %r was not written by this account here, or is damaged: "
                        "fitted afresh and replaced", neem)
            continue
        head, body = opened
        count = head.get("steps")
        if head.get("key") != key or type(count) is not int or not 0 <= count <= len(steps):
            continue
        if count not in digests:
            digests[count] = _steps_digest(steps[:count])
        if head.get("digest") == digests[count]:
            heads.append((count, body))
    for count, body in sorted(heads, key=lambda h: h[0], reverse=True):
        cached = _parse(body, count, model)
        if cached is not None:
            return cached
    return None


def _parse(body: bytes, count: int, model: Any) -> Any | None:
    """The model kept in an entry's ``body``, fitted on ``count`` steps; None when it is not
    one (a damaged or foreign entry is fitted afresh and replaced)."""
    try:
        cached = plainstate.loads(body, model_classes(model), shared=model.distances)
    except plainstate.PlainStateError:
        return None
    if type(cached) is not type(model) or getattr(cached, "fitted_steps_", None) != count:
        return None
    return cached


def _steps_digest(steps: Sequence[Step]) -> str:
    """Equal digests are equal steps (pickle writes every field)."""
    return hashlib.sha256(pickle.dumps(list(steps), protocol=5)).hexdigest()


def _file_name(key: str, store: str) -> str:
    """The user-cache file of an entry: its key, for the store at ``store``."""
    return hashlib.sha256(f"{key}\0{store}".encode()).hexdigest()[:32]


def _entry_key(model: Any, neem: str) -> str:
    digest = hashlib.sha256()
    for part in (_FORMAT.decode(), type(model).__module__, type(model).__qualname__, neem, sys.version,
                 np.__version__, _code_digest()):
        digest.update(part.encode() + b"\0")
    prior = getattr(model, "prior", None)
    if prior is not None:  # weights learnt with a prior are kept for that prior only
        digest.update(b"prior=" + prior.digest().encode() + b"\0")
    for name, value in model.get_params().items():
        digest.update(name.encode() + b"=")
        if value is model.distances:
            digest.update(repr(value.classes).encode())
            digest.update(np.ascontiguousarray(value.values).tobytes())
        else:
            digest.update(_canonical(value).encode())
        digest.update(b"\0")
    return digest.hexdigest()[:32]


def _canonical(value: Any) -> str:
    """A text of a parameter value that does not depend on the order sets iterate in."""
    if isinstance(value, (set, frozenset)):
        return "{" + ",".join(sorted(_canonical(v) for v in value)) + "}"
    if isinstance(value, (tuple, list)):
        return "(" + ",".join(_canonical(v) for v in value) + ")"
    return repr(value)


def _code_digest() -> str:
    """The source of the predictors: a changed file is a different model."""
    folder = Path(__file__).resolve().parent / "algorithm"
    digest = hashlib.sha256()
    for path in sorted(folder.glob("*.py")):
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()
