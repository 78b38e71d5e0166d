"""The service ranks with the shared prior it is given, or the store's own (``serve --prior``)."""

from __future__ import annotations

import json

import pytest

from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.prior import Prior, PriorError, store_prior_path
from oracle.ontology.provenance import fingerprint


def _prior(onto) -> Prior:
    return Prior({(): {"pick(red_mug)": 10.0}}, fingerprint(onto), 5, None, 3, 6)


def test_the_store_s_own_prior_is_found_and_reaches_every_session(tmp_path, onto):
    from oracle.service import build_context

    spec = str(tmp_path / "s.sqlite")
    _prior(onto).save(store_prior_path(spec))
    ctx = build_context(spec, onto, Hyperparameters())
    try:
        engine = ctx.thread.call(lambda: ctx.engine)
        assert engine.prior is not None and engine.prior.tables == _prior(onto).tables
        made = ctx.thread.call(lambda: engine.create("ann", None))
        session = ctx.thread.call(lambda: engine.session(made["id"]))
        assert session.ranker.predictor.prior is engine.prior
    finally:
        ctx.thread.close()
    ctx = build_context(spec, onto, Hyperparameters(), prior="none")
    try:
        assert ctx.thread.call(lambda: ctx.engine.prior) is None
    finally:
        ctx.thread.close()


def test_a_prior_of_another_ontology_is_refused(tmp_path, onto):
    from oracle.service import build_context

    path = tmp_path / "other.json"
    data = _prior(onto).to_json()
    data["fingerprint"] = "0123456789abcdef"
    path.write_text(json.dumps(data))
    with pytest.raises(PriorError, match="another ontology"):
        build_context(str(tmp_path / "s.sqlite"), onto, Hyperparameters(), prior=str(path))
