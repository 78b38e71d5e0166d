"""The fitted predictor of a NEEM's history, kept between calls: a rank after one more action
adds that action to the model fitted before instead of fitting the whole history again.

One entry per NEEM and predictor, kept in the store beside the NEEM where the store can keep
it (oracle.store.kept; one fit per NEEM there, so the first rank after an import finds the fit
the import made), else a file in the user's private cache (``fits/`` beside the compiled Prolog
modules; folder 0700, file 0600). Its key is a digest of everything a fit depends on besides
the history: the predictor's class and parameters, the distance matrix's content, the source of
``oracle.algorithm`` and the Python and numpy versions. Inside: the key, the number of steps
fitted, the digest of those steps (their pickle) and the model, pickled without its distance
matrix (the caller's, of the same content, is put back). A store's file may come from someone
else: its entries are unpickled by ``_Unpickler`` with ``trusted`` False, which makes nothing
but the predictors' own classes, numpy arrays and builtin containers.

A predictor takes part when it has ``extend(history)`` (the routine predictor: the model
``fit(history)`` gives, from the one fitted on a prefix of it, bit for bit). An entry is used
only when its steps are exactly the first steps of the history; otherwise, and when it is
missing, damaged, or not the user's own, the model is fitted afresh and the entry replaced. The
cache is an optimisation: a folder that cannot be written only makes every call fit afresh.
"""

from __future__ import annotations

import hashlib
import io
import os
import pickle
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from oracle.algorithm.records import Step
from oracle.files import CacheFolder, written_by_user_alone

if TYPE_CHECKING:
    from oracle.store.base import Store

_FORMAT = b"neem-oracle fit 2"
#: The kind of entry the store keeps (oracle.store.kept).
KIND = "fit"
_DISTANCES = "distances"


@dataclass(frozen=True)
class FitCache(CacheFolder):
    """Fitted models under ``root`` (one file each)."""

    FOLDER: ClassVar[str] = "fits"
    SUFFIX: ClassVar[str] = ".fit"

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
        path = self.root / f"{_file_name(key, store)}{self.SUFFIX}"
        entries = [(raw, trusted) for raw, trusted in ((None if kept is None else kept.read_kept(neem, KIND), False),
                                                       (self._load(path), True)) if raw is not None]
        cached = _best(entries, key, model, steps)
        if cached is not None and cached.fitted_steps_ == len(steps):
            return cached
        fitted = cached.extend(steps) if cached is not None else model.fit(steps)
        data = self._dumps(key, fitted, steps)
        if data is not None and (kept is None or not kept.write_kept(neem, KIND, data)):
            self._store(path, data)
        return fitted

    def _load(self, path: Path) -> bytes | None:
        try:
            with path.open("rb") as handle:
                info = os.fstat(handle.fileno())
                if not written_by_user_alone(info):
                    return None  # never unpickled
                return handle.read()
        except OSError:
            return None

    def _dumps(self, key: str, model: Any, steps: Sequence[Step]) -> bytes | None:
        try:
            body = io.BytesIO()
            _Pickler(body, model.distances).dump(model)
            return pickle.dumps((_FORMAT, key, len(steps), _steps_digest(steps), body.getvalue()), protocol=5)
        except pickle.PicklingError:
            return None


def _best(entries: Sequence[tuple[bytes, bool]], key: str, model: Any, steps: Sequence[Step]) -> Any | None:
    """The model of the kept entry (raw bytes, whether trusted: the store's is not) that fitted
    the most of ``steps``. Each entry's head (its key, its number of steps and their digest) is
    read first; only the chosen one's model is unpickled (4 MB at 50,000 actions), and a damaged
    one gives way to the next."""
    digests: dict[int, str] = {}
    heads = []
    for raw, trusted in entries:
        try:
            head, entry_key, count, digest, body = _Unpickler(io.BytesIO(raw), None, trusted).load()
            if head != _FORMAT or entry_key != key or type(count) is not int or not 0 <= count <= len(steps):
                continue
            if count not in digests:
                digests[count] = _steps_digest(steps[:count])
            if digest == digests[count] and isinstance(body, bytes):
                heads.append((count, body, trusted))
        except Exception:
            continue
    for count, body, trusted in sorted(heads, key=lambda h: h[0], reverse=True):
        cached = _parse(body, count, model, trusted=trusted)
        if cached is not None:
            return cached
    return None


def _parse(body: bytes, count: int, model: Any, *, trusted: bool) -> Any | None:
    """The model pickled in an entry's ``body``, fitted on ``count`` steps; None when it is not
    one (a damaged or foreign entry is fitted afresh and replaced)."""
    try:
        cached = _Unpickler(io.BytesIO(body), model.distances, trusted).load()
    except Exception:
        return None
    if type(cached) is not type(model) or getattr(cached, "fitted_steps_", None) != count:
        return None
    return cached


class _Pickler(pickle.Pickler):
    """Pickles a model with its distance matrix as a reference (the caller supplies it)."""

    def __init__(self, out: io.BytesIO, distances: Any) -> None:
        super().__init__(out, protocol=5)
        self._distances = distances

    def persistent_id(self, obj: Any) -> str | None:
        return _DISTANCES if obj is self._distances else None


#: What an entry from a store may make (``trusted`` False): the predictors' own classes, numpy's
#: arrays, builtin containers.
_SAFE_MODULES = ("oracle.algorithm.",)
_SAFE_GLOBALS = {("numpy", "dtype"), ("numpy", "ndarray"), ("numpy._core.numeric", "_frombuffer"),
                 ("numpy.core.numeric", "_frombuffer"), ("numpy._core.multiarray", "_reconstruct"),
                 ("numpy.core.multiarray", "_reconstruct"), ("numpy._core.multiarray", "scalar"),
                 ("numpy.core.multiarray", "scalar"), ("copyreg", "_reconstructor"), ("builtins", "set"),
                 ("builtins", "frozenset"), ("builtins", "slice"), ("builtins", "complex"), ("builtins", "object"),
                 ("collections", "OrderedDict"), ("collections", "defaultdict"), ("collections", "Counter"),
                 ("collections", "deque")}


class _Unpickler(pickle.Unpickler):
    def __init__(self, data: io.BytesIO, distances: Any, trusted: bool = True) -> None:
        super().__init__(data)
        self._distances = distances
        self._trusted = trusted

    def find_class(self, module: str, name: str) -> Any:
        if not self._trusted and (module, name) not in _SAFE_GLOBALS:
            found = super().find_class(module, name) if module.startswith(_SAFE_MODULES) else None
            if not isinstance(found, type):
                raise pickle.UnpicklingError(f"{module}.{name} is not made from a kept fit")
            return found
        return super().find_class(module, name)

    def persistent_load(self, pid: Any) -> Any:
        if pid != _DISTANCES:
            raise pickle.UnpicklingError(f"unknown reference {pid!r}")
        return self._distances


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
