"""The fitted predictor of a NEEM's history, kept between calls: a rank after one more action
adds that action to the model fitted before instead of fitting the whole history again.

One entry per NEEM and predictor, a file in the user's private cache (``fits/`` beside the
compiled Prolog modules; folder 0700, file 0600). Its name is a digest of everything a fit
depends on besides the history: the predictor's class and parameters, the distance matrix's
content, the source of ``oracle.algorithm`` and the Python and numpy versions. Inside: the
number of steps fitted, the digest of those steps (their pickle) and the model, pickled without
its distance matrix (the caller's, of the same content, is put back).

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
from typing import Any, ClassVar

import numpy as np

from oracle.algorithm.records import Step
from oracle.files import CacheFolder, write_private_bytes, written_by_user_alone

_FORMAT = b"neem-oracle fit 1"
_DISTANCES = "distances"


@dataclass(frozen=True)
class FitCache(CacheFolder):
    """Fitted models under ``root`` (one file each)."""

    FOLDER: ClassVar[str] = "fits"
    SUFFIX: ClassVar[str] = ".fit"

    def fitted(self, model: Any, steps: Sequence[Step], store: str, neem: str, *, keep: bool = True) -> Any:
        """``model.fit(steps)``, extended from the entry of NEEM ``neem`` of the store at
        ``store`` (its location) when the entry's steps are the first steps of ``steps``; the
        entry then holds the new fit. ``keep`` False (a temporary NEEM, wiped when its session
        ends: nothing made from it may outlive it) fits afresh and keeps nothing."""
        if not keep or not callable(getattr(model, "extend", None)):
            return model.fit(steps)
        path = self.root / f"{_entry_key(model, store, neem)}{self.SUFFIX}"
        cached = self._load(path, model, steps)
        if cached is not None and cached.fitted_steps_ == len(steps):
            return cached
        fitted = cached.extend(steps) if cached is not None else model.fit(steps)
        self._store(path, fitted, steps)
        return fitted

    def _load(self, path: Path, model: Any, steps: Sequence[Step]) -> Any | None:
        try:
            with path.open("rb") as handle:
                info = os.fstat(handle.fileno())
                if not written_by_user_alone(info):
                    return None  # never unpickled
                data = handle.read()
        except OSError:
            return None
        try:
            head, count, digest, body = pickle.loads(data)
            if head != _FORMAT or count > len(steps) or digest != _steps_digest(steps[:count]):
                return None
            cached = _Unpickler(io.BytesIO(body), model.distances).load()
        except Exception:  # a damaged or foreign entry: fit afresh (it is replaced)
            return None
        if type(cached) is not type(model) or getattr(cached, "fitted_steps_", None) != count:
            return None
        return cached

    def _store(self, path: Path, model: Any, steps: Sequence[Step]) -> None:
        try:
            body = io.BytesIO()
            _Pickler(body, model.distances).dump(model)
            data = pickle.dumps((_FORMAT, len(steps), _steps_digest(steps), body.getvalue()), protocol=5)
            write_private_bytes(path, data)
            self._prune()
        except (OSError, pickle.PicklingError):
            return  # read-only or full: the next call fits afresh


class _Pickler(pickle.Pickler):
    """Pickles a model with its distance matrix as a reference (the caller supplies it)."""

    def __init__(self, out: io.BytesIO, distances: Any) -> None:
        super().__init__(out, protocol=5)
        self._distances = distances

    def persistent_id(self, obj: Any) -> str | None:
        return _DISTANCES if obj is self._distances else None


class _Unpickler(pickle.Unpickler):
    def __init__(self, data: io.BytesIO, distances: Any) -> None:
        super().__init__(data)
        self._distances = distances

    def persistent_load(self, pid: Any) -> Any:
        if pid != _DISTANCES:
            raise pickle.UnpicklingError(f"unknown reference {pid!r}")
        return self._distances


def _steps_digest(steps: Sequence[Step]) -> str:
    """Equal digests are equal steps (pickle writes every field)."""
    return hashlib.sha256(pickle.dumps(list(steps), protocol=5)).hexdigest()


def _entry_key(model: Any, store: str, neem: str) -> str:
    digest = hashlib.sha256()
    for part in (_FORMAT.decode(), type(model).__module__, type(model).__qualname__, store, neem, sys.version,
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
