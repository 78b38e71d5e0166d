"""A kept fit is data, never code: what a store, a cache file or a handed-over file holds in the
kept-fit place runs nothing, is dropped, and the model is fitted afresh (oracle.fitcache,
oracle.plainstate, oracle.files.user_key; docs/security.md, "Files a user is handed").

"Runs nothing" is watched with Python's audit hooks: while an entry is read, no pickle global
is resolved, no process, shell, library or code object is made and no file is opened for
writing."""

from __future__ import annotations

import os
import random
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "algorithm"))

from algoworld import random_matrix, synthetic_history  # noqa: E402
from oracle import fitcache, plainstate  # noqa: E402
from oracle.algorithm.predictors import PREDICTORS, make_predictor  # noqa: E402
from oracle.algorithm.params import Hyperparameters  # noqa: E402
from oracle.algorithm.routine import RoutineOracle  # noqa: E402
from oracle.files import default_key_dir, signed, user_key  # noqa: E402
from oracle.fitcache import FitCache  # noqa: E402
from test_fitcache import _KeptStore  # noqa: E402  (a store that keeps entries)

#: Audit events that would mean an entry ran something.
_RAN = ("pickle.find_class", "os.system", "subprocess.Popen", "os.exec", "os.posix_spawn", "os.fork",
        "ctypes.dlopen", "ctypes.call_function", "exec", "compile", "builtins.input", "socket.connect", "shutil.rmtree")


class _Watch:
    """Records the audit events of ``_RAN`` (and writes opened) while switched on."""

    def __init__(self) -> None:
        self.on = False
        self.seen: list[str] = []
        sys.addaudithook(self)

    def __call__(self, event: str, args: tuple) -> None:
        if not self.on:
            return
        if event in _RAN or event == "open" and len(args) > 1 and isinstance(args[1], str) and any(m in args[1] for m in "wax+"):
            self.seen.append(event)


_WATCH = _Watch()


def _gadget(planted: str) -> bytes:
    """The round-3 payload: pickle GLOBALs whose dotted names start in the predictors' package and
    end at types (ctypes.CDLL, operator.methodcaller), which the old "untrusted" unpickler
    admitted: ``methodcaller("system", b"touch PLANTED")(CDLL(None))`` runs a shell command."""
    command = f"touch {planted}".encode()
    return (b"\x80\x04"
            + b"c" + b"oracle.algorithm.fast\nnp._core.shape_base.operator.methodcaller\n"
            + b"X" + len(b"system").to_bytes(4, "little") + b"system"
            + b"C" + bytes([len(command)]) + command + b"\x86R"                # methodcaller("system", cmd)
            + b"c" + b"oracle.algorithm.fast\nnp.ctypeslib.ctypes.CDLL\n" + b"N\x85R"  # CDLL(None): the C library
            + b"\x85R" + b".")                                                 # (...)(libc)


def _entries(planted: str, key: bytes | None) -> list[bytes]:
    gadget = _gadget(planted)
    forged_head = b'{"key":"x","steps":0,"digest":"x"}'
    entries = [gadget, fitcache._FORMAT + gadget, fitcache._FORMAT + bytes(32) + gadget,
               plainstate.MAGIC + gadget, fitcache._FORMAT + bytes(32) + len(forged_head).to_bytes(4, "little") + forged_head + gadget]
    if key is not None:  # even an entry tagged under the right key is never unpickled
        body = len(forged_head).to_bytes(4, "little") + forged_head + gadget
        entries.append(fitcache._FORMAT + signed(key, body))
    return entries


def test_the_dotted_name_gadget_runs_nothing_anywhere_a_fit_is_read(tmp_path):
    matrix, steps = random_matrix(5), synthetic_history(40, 5)
    planted = tmp_path / "planted"
    cache = FitCache(tmp_path / "fits")
    key = fitcache._entry_key(RoutineOracle(matrix), "n")
    user_file = tmp_path / "fits" / f"{fitcache._file_name(key, 's')}{FitCache.SUFFIX}"
    fresh = RoutineOracle(matrix).fit(steps)
    user_file.parent.mkdir(mode=0o700)
    for entry in _entries(str(planted), user_key(default_key_dir())):
        store = _KeptStore()
        store.kept[("n", fitcache.KIND)] = entry
        user_file.write_bytes(entry)
        os.chmod(user_file, 0o600)
        _WATCH.seen.clear()
        _WATCH.on = True
        try:
            model = cache.fitted(RoutineOracle(matrix), steps, "s", "n", kept=store)
        finally:
            _WATCH.on = False
        assert not planted.exists() and "pickle.find_class" not in _WATCH.seen and "os.system" not in _WATCH.seen
        assert store.kept[("n", fitcache.KIND)] != entry  # dropped and replaced by a fresh fit
        assert [(t.option, t.probability) for t in model.rank(steps[-1])] == \
               [(t.option, t.probability) for t in fresh.rank(steps[-1])]
    with pytest.raises(plainstate.PlainStateError):
        plainstate.loads(_gadget(str(planted)), fitcache.model_classes(fresh))
    assert not planted.exists()


def test_ten_thousand_random_or_mutated_entries_run_nothing_and_are_refitted(tmp_path):
    matrix, steps = random_matrix(7), synthetic_history(30, 7)
    store = _KeptStore()
    cache = FitCache(tmp_path / "fits")
    cache.fitted(RoutineOracle(matrix), steps, "s", "n", kept=store)
    good = store.kept[("n", fitcache.KIND)]
    key = fitcache._entry_key(RoutineOracle(matrix), "n")
    secret = user_key(default_key_dir())
    rng = random.Random(0)
    model = RoutineOracle(matrix)
    _WATCH.seen.clear()
    _WATCH.on = True
    try:
        for i in range(10_000):
            entry = _mutated(good, rng) if i % 2 else rng.randbytes(rng.randrange(0, 4096))
            assert fitcache._best([entry], secret, key, model, steps, "n") is None or entry == good
    finally:
        _WATCH.on = False
    assert not _WATCH.seen
    # and through the whole path, as rank meets them: each dropped, fitted afresh, replaced
    for _ in range(20):
        entry = _mutated(good, rng)
        store.kept[("n", fitcache.KIND)] = entry
        cache.fitted(RoutineOracle(matrix), steps, "s", "n", kept=store)
        assert fitcache._opened(store.kept[("n", fitcache.KIND)], secret) is not None  # ours again


def _mutated(data: bytes, rng: random.Random) -> bytes:
    raw = bytearray(data)
    for _ in range(rng.randrange(1, 8)):
        kind = rng.randrange(3)
        at = rng.randrange(len(raw))
        if kind == 0:
            raw[at] = rng.randrange(256)
        elif kind == 1:
            del raw[at:at + rng.randrange(1, 64)]
        else:
            raw[at:at] = rng.randbytes(rng.randrange(1, 64))
    return bytes(raw)


def test_the_decoder_itself_makes_only_data_from_mutated_models():
    """Behind the tag, the plain decoder alone: 2,000 mutations of a real model's bytes either
    decode or fail with PlainStateError; nothing runs."""
    matrix, steps = random_matrix(3), synthetic_history(20, 3)
    model = RoutineOracle(matrix).fit(steps)
    classes = fitcache.model_classes(model)
    data = plainstate.dumps(model, classes, shared=matrix)
    rng = random.Random(1)
    _WATCH.seen.clear()
    _WATCH.on = True
    try:
        for _ in range(2_000):
            try:
                plainstate.loads(_mutated(data, rng), classes, shared=matrix)
            except plainstate.PlainStateError:
                pass
    finally:
        _WATCH.on = False
    assert not _WATCH.seen


@pytest.mark.parametrize("name", [name for name in PREDICTORS if name not in ("thesis", "thesis-normalized")])
def test_every_kept_predictor_round_trips_as_plain_data(name):
    """The plain format keeps each predictor that is kept (those with ``extend``) exactly: the
    same ranking, and the same model after extending both."""
    matrix, steps = random_matrix(4), synthetic_history(200, 4)
    model = make_predictor(name, matrix, frozenset(), Hyperparameters())
    if not callable(getattr(model, "extend", None)):
        pytest.skip(f"{name} is never kept (no extend)")
    model = model.fit(steps[:150])
    classes = fitcache.model_classes(model)
    copy = plainstate.loads(plainstate.dumps(model, classes, shared=matrix), classes, shared=matrix)
    assert type(copy) is type(model) and copy.distances is matrix
    ranked = lambda m, s: [(t.option, t.probability) for t in m.rank(s)]  # noqa: E731
    assert ranked(copy, steps[150]) == ranked(model, steps[150])
    grown, copy_grown = model.extend(steps), copy.extend(steps)
    for step in steps[-5:]:
        assert ranked(copy_grown, step) == ranked(grown, step)
