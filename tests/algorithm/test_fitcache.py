"""The fitted-model cache (oracle.fitcache) and the routine predictor's ``extend``: a model
extended from a fit of a prefix is the model a fresh fit gives, bit for bit; the cache uses an
entry only for a history that begins with the entry's steps, and never one another user could
have written."""

from __future__ import annotations

import json
import os
import pickle

import numpy as np
import pytest

from algoworld import random_matrix, synthetic_history
from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.routine import RoutineOracle
from oracle.errors import SettingsError
from oracle.fitcache import FitCache


def _same(a: RoutineOracle, b: RoutineOracle, queries) -> None:
    wa, wb = a.weights_, b.weights_
    assert wa.steps == wb.steps
    for name in ("scores", "hits", "spread"):
        assert np.array_equal(getattr(wa, name), getattr(wb, name)), name
    assert a.options_ == b.options_ and a.n_steps_ == b.n_steps_ == b.fitted_steps_
    for step in queries:
        ra, rb = a.rank(step), b.rank(step)
        assert [(t.option, t.probability, t.order, t.n_similar, t.situations) for t in ra] == \
               [(t.option, t.probability, t.order, t.n_similar, t.situations) for t in rb]


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("window", [0, 5, 40, 1000])
def test_extend_equals_a_fresh_fit(seed, window):
    matrix = random_matrix(seed)
    steps = synthetic_history(160, seed)
    queries = steps[-12:]
    fresh = RoutineOracle(matrix, tuning_window=window).fit(steps)
    for cut in (0, 1, 37, 120, 159, 160):
        grown = RoutineOracle(matrix, tuning_window=window).fit(steps[:cut])
        grown = pickle.loads(pickle.dumps(grown))  # as the cache keeps it
        _same(fresh, grown.extend(steps), queries)
    # in two hops, as a user's NEEM grows between ranks
    hop = RoutineOracle(matrix, tuning_window=window).fit(steps[:50]).extend(steps[:90]).extend(steps)
    _same(fresh, hop, queries)


def test_a_decision_drops_repeated_options_with_or_without_the_offer_set():
    from oracle.algorithm.focus import decision

    assert decision([3, 1, 3, 2], 2) == decision([3, 1, 3, 2], 2, frozenset({1, 2, 3})) == ([3, 1, 2], 2)
    assert decision([3, 1, 2], 2, frozenset({1, 2, 3})) == ([3, 1, 2], 2)
    assert decision([3, 1, 2], 7, frozenset({1, 2, 3})) is None


@pytest.mark.parametrize("seed", [0, 4])
def test_a_fit_over_shared_offers_equals_one_over_copies(seed):
    """``fit`` interns each offer its steps share once (``OptionTable.offer``, by identity); steps
    whose offers are equal copies, or repeat an option, count the same."""
    from dataclasses import replace

    matrix = random_matrix(seed)
    steps = synthetic_history(300, seed)
    assert len({id(step.options) for step in steps}) < 60   # the offers really are shared
    copies = [replace(step, options=tuple(list(step.options))) for step in steps]
    assert all(a.options is not b.options for a, b in zip(steps, copies))
    queries = steps[-10:]
    _same(RoutineOracle(matrix).fit(steps), RoutineOracle(matrix).fit(copies), queries)
    doubled = [replace(step, options=step.options + step.options[:2]) if i % 3 else step for i, step in enumerate(steps)]
    partial = RoutineOracle(matrix).fit([])
    for step in doubled:
        partial.partial_fit(step)
    grown = RoutineOracle(matrix).fit(doubled)
    assert (grown.fresh_.lift.hits, grown.fresh_.lift.share, grown.fresh_.lift.steps) == \
           (partial.fresh_.lift.hits, partial.fresh_.lift.share, partial.fresh_.lift.steps)
    assert (grown.hand_.hits, grown.hand_.share, grown.hand_.steps) == \
           (partial.hand_.hits, partial.hand_.share, partial.hand_.steps)


def test_the_window_changes_what_tunes():
    """The scores really are cut to the window (else the test above would prove little)."""
    matrix = random_matrix(3)
    steps = synthetic_history(200, 3)
    assert RoutineOracle(matrix, tuning_window=10).fit(steps).weights_.steps <= 10
    assert RoutineOracle(matrix, tuning_window=1000).fit(steps).weights_.steps > 150


def test_extend_refuses_what_it_cannot_continue():
    matrix = random_matrix(4)
    steps = synthetic_history(30, 4)
    with pytest.raises(SettingsError, match="fewer than"):
        RoutineOracle(matrix).fit(steps).extend(steps[:10])
    changed = RoutineOracle(matrix).fit(steps[:20]).partial_fit(steps[20])
    with pytest.raises(SettingsError, match="partial_fit"):
        changed.extend(steps)
    with pytest.raises(SettingsError, match="tuning_window"):
        RoutineOracle(matrix, tuning_window=-1).fit(steps)


class _Counting(RoutineOracle):
    """Counts the steps it is given to add (fresh fits and extensions)."""

    added = 0

    def _add(self, step, score, offers=None):
        type(self).added += 1
        super()._add(step, score, offers)


def test_cache_fits_once_then_extends_only_the_new_steps(tmp_path):
    cache = FitCache(tmp_path / "fits")
    matrix = random_matrix(5)
    steps = synthetic_history(120, 5)
    _Counting.added = 0
    first = cache.fitted(_Counting(matrix), steps[:100], "s", "n")
    assert _Counting.added == 100
    entry, = (tmp_path / "fits").glob("*.fit")
    assert entry.stat().st_mode & 0o777 == 0o600 and (tmp_path / "fits").stat().st_mode & 0o777 == 0o700
    again = cache.fitted(_Counting(matrix), steps[:100], "s", "n")
    assert _Counting.added == 100  # the same history: nothing fitted
    grown = cache.fitted(_Counting(matrix), steps, "s", "n")
    assert _Counting.added == 120  # only the 20 new steps
    _same(_Counting(matrix).fit(steps), grown, steps[-5:])
    _same(first, again, steps[-5:])
    assert again.distances is matrix  # the caller's matrix, not a copy


def test_a_fit_not_to_keep_is_fitted_and_not_written(tmp_path):
    # a temporary NEEM's fit (thesis 3.5: wiped with the NEEM) never reaches the cache
    cache = FitCache(tmp_path / "fits")
    matrix = random_matrix(5)
    steps = synthetic_history(60, 5)
    _Counting.added = 0
    model = cache.fitted(_Counting(matrix), steps, "s", "n", keep=False)
    cache.fitted(_Counting(matrix), steps, "s", "n", keep=False)
    assert _Counting.added == 120 and not (tmp_path / "fits").exists()
    _same(_Counting(matrix).fit(steps), model, steps[-5:])


def test_cache_fits_afresh_when_the_history_is_not_a_continuation(tmp_path):
    cache = FitCache(tmp_path)
    matrix = random_matrix(6)
    steps = synthetic_history(80, 6)
    cache.fitted(_Counting(matrix), steps, "s", "n")
    other = synthetic_history(90, 7)  # another history of the same NEEM (e.g. re-imported)
    _Counting.added = 0
    model = cache.fitted(_Counting(matrix), other, "s", "n")
    assert _Counting.added == 90
    _same(RoutineOracle(matrix).fit(other), model, other[-5:])
    shorter = cache.fitted(_Counting(matrix), other[:40], "s", "n")  # a rank at an earlier moment
    assert _Counting.added == 130 and shorter.n_steps_ == 40


def test_cache_keys_on_parameters_and_neem(tmp_path):
    cache = FitCache(tmp_path)
    matrix = random_matrix(8)
    steps = synthetic_history(60, 8)
    cache.fitted(RoutineOracle(matrix), steps, "s", "a")
    cache.fitted(RoutineOracle(matrix, tuning="mixture"), steps, "s", "a")
    cache.fitted(RoutineOracle(matrix), steps, "s", "b")
    cache.fitted(RoutineOracle(random_matrix(9)), steps, "s", "a")
    assert len(list(tmp_path.glob("*.fit"))) == 4


def test_damaged_or_foreign_entries_are_never_used(tmp_path):
    cache = FitCache(tmp_path)
    matrix = random_matrix(10)
    steps = synthetic_history(50, 10)
    cache.fitted(_Counting(matrix), steps, "s", "n")
    entry, = tmp_path.glob("*.fit")
    entry.write_bytes(b"not a pickle")
    _Counting.added = 0
    cache.fitted(_Counting(matrix), steps, "s", "n")
    assert _Counting.added == 50 and entry.read_bytes() != b"not a pickle"  # refitted and replaced
    _Counting.added = 0
    cache.fitted(_Counting(matrix), steps, "s", "n")
    assert _Counting.added == 0  # the replaced entry is used
    os.chmod(entry, 0o620)  # another user of the group could have written it
    cache.fitted(_Counting(matrix), steps, "s", "n")
    assert _Counting.added == 50


def test_unwritable_cache_still_ranks_and_predictors_without_extend_just_fit(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    matrix = random_matrix(11)
    steps = synthetic_history(40, 11)
    model = FitCache(blocker / "fits").fitted(RoutineOracle(matrix), steps, "s", "n")
    _same(RoutineOracle(matrix).fit(steps), model, steps[-3:])
    thesis = FitCache(tmp_path / "fits").fitted(PreferenceOracle(matrix), steps, "s", "n")
    assert thesis.n_steps_ == 40 and not (tmp_path / "fits").exists()


class _KeptStore:
    """A store that keeps entries (oracle.store.kept's interface)."""

    def __init__(self) -> None:
        self.kept: dict[tuple[str, str], bytes] = {}

    def read_kept(self, neem: str, kind: str) -> bytes | None:
        return self.kept.get((neem, kind))

    def write_kept(self, neem: str, kind: str, data: bytes) -> bool:
        self.kept[(neem, kind)] = data
        return True


def test_a_fit_kept_in_the_store_serves_the_next_process(tmp_path, monkeypatch):
    store = _KeptStore()
    matrix = random_matrix(5)
    steps = synthetic_history(80, 5)
    first = FitCache(tmp_path / "a").fitted(RoutineOracle(matrix), steps[:60], "s", "n", kept=store)
    assert store.kept and not list((tmp_path / "a").glob("*.fit"))  # the store kept it, not the user's cache
    monkeypatch.setattr(RoutineOracle, "fit", lambda self, history: pytest.fail("fitted afresh"))
    again = FitCache(tmp_path / "a").fitted(RoutineOracle(matrix), steps[:60], "s", "n", kept=store)
    _same(first, again, steps[-5:])
    grown = FitCache(tmp_path / "a").fitted(RoutineOracle(matrix), steps, "s", "n", kept=store)  # extended
    monkeypatch.undo()
    _same(RoutineOracle(matrix).fit(steps), grown, steps[-5:])


def test_a_fit_another_account_kept_is_fitted_afresh_and_said_once(tmp_path, caplog):
    # another user's cache folder has another key: their entry in a store they hand over is not used
    store, matrix, steps = _KeptStore(), random_matrix(5), synthetic_history(40, 5)
    FitCache(tmp_path / "theirs", keys=tmp_path / "their-key").fitted(RoutineOracle(matrix), steps, "s", "n", kept=store)
    theirs = store.kept[("n", "fit")]
    _Counting.added = 0
    with caplog.at_level("WARNING", logger="oracle.fitcache"):
        FitCache(tmp_path / "mine").fitted(_Counting(matrix), steps, "s", "n", kept=store)
    assert _Counting.added == 40 and store.kept[("n", "fit")] != theirs  # fitted afresh, replaced
    assert len([r for r in caplog.records if "was not written by this account" in r.getMessage()]) == 1
    _Counting.added = 0
    caplog.clear()
    with caplog.at_level("WARNING", logger="oracle.fitcache"):
        FitCache(tmp_path / "mine").fitted(_Counting(matrix), steps, "s", "n", kept=store)
    assert _Counting.added == 0 and not caplog.records  # our own entry now: used, nothing said


def test_a_damaged_further_entry_gives_way_to_the_other(tmp_path, monkeypatch):
    # the user's file is read first by its head; a model that will not decode makes the cache
    # extend the store's shorter fit, not fit afresh
    import oracle.fitcache as fitcache
    from oracle.files import default_key_dir, signed, user_key

    store, matrix, steps = _KeptStore(), random_matrix(6), synthetic_history(90, 6)
    cache = FitCache(tmp_path / "fits")
    cache.fitted(RoutineOracle(matrix), steps[:70], "s", "n", kept=store)
    key = fitcache._entry_key(RoutineOracle(matrix), "n")
    head = json.dumps({"key": key, "steps": 80, "digest": fitcache._steps_digest(steps[:80])}).encode()
    damaged = fitcache._FORMAT + signed(user_key(default_key_dir()), len(head).to_bytes(4, "little") + head + b"not a model")
    path = tmp_path / "fits" / f"{fitcache._file_name(key, 's')}{FitCache.SUFFIX}"
    path.parent.mkdir(mode=0o700, exist_ok=True)
    path.write_bytes(damaged)
    os.chmod(path, 0o600)
    monkeypatch.setattr(RoutineOracle, "fit", lambda self, history: pytest.fail("fitted afresh"))
    grown = cache.fitted(RoutineOracle(matrix), steps, "s", "n", kept=store)  # the store's 70, extended
    monkeypatch.undo()
    _same(RoutineOracle(matrix).fit(steps), grown, steps[-4:])


def test_a_kept_fit_learns_its_new_steps_with_the_prior_and_is_kept_per_prior(tmp_path):
    """The prior is never kept with a fit: the cache gives the kept model the caller's prior
    before it adds the steps since, so the grown fit equals a fresh one with that prior; a fit
    learnt under another prior is not used."""
    from oracle.algorithm.personal import PersonalOracle
    from oracle.algorithm.prior import Prior, option_key

    matrix = random_matrix(8)
    steps = synthetic_history(140, 8)
    prior = Prior({(): {option_key(steps[0].options[-1]): 40.0, option_key(steps[3].options[0]): 10.0}})
    other = Prior({(): {option_key(steps[0].options[0]): 40.0}})
    cache = FitCache(tmp_path / "fits")
    cache.fitted(PersonalOracle(matrix).use_prior(prior), steps[:90], "s", "n")
    grown = cache.fitted(PersonalOracle(matrix).use_prior(prior), steps, "s", "n")
    fresh = PersonalOracle(matrix).use_prior(prior).fit(steps)
    assert grown.prior is prior
    for step in steps[-6:]:
        assert [(t.option, t.probability) for t in grown.rank(step)] == [(t.option, t.probability) for t in fresh.rank(step)]
    assert fitcache_key(PersonalOracle(matrix).use_prior(prior)) != fitcache_key(PersonalOracle(matrix).use_prior(other))


def fitcache_key(model):
    import oracle.fitcache as fitcache

    return fitcache._entry_key(model, "n")
