"""/explore's first paint and the prior's share: the timeline sent by the explorer's own reader
from the view the store keeps (equal to the engine's read, and answered while the engine thread
is busy), a NEEM nothing was kept for read once with a 202 that says what is being read, and the
shared prior's share of each ranking equal to what the personal predictor scored with."""

from __future__ import annotations

import shutil
import sqlite3
import threading
import time
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from oracle.algorithm.params import preset
from tests.service.test_explore import _decisions, chains, store  # noqa: F401 - the module's fixtures
from tests.service.test_server import axe_source, browser  # noqa: F401 - fixtures

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")


def _client(path: Path, prior=None) -> Iterator:
    from fastapi.testclient import TestClient

    from oracle.evaluation.neem_replay import replay_neem
    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    ctx = build_context(str(path), build_ontology(), preset("recommended"), prior="none")
    ctx.engine.prior = prior
    app = create_app(ctx)
    app.state.explore_replay = replay_neem
    with TestClient(app, base_url="http://127.0.0.1") as test_client:
        yield test_client, ctx
    ctx.thread.close()


@pytest.fixture()
def served(store, tmp_path) -> Iterator:  # noqa: F811
    """The service over a copy of the store whose history was read once (and so is kept)."""
    from oracle.historycache import HistoryCache

    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    for client, ctx in _client(copy):
        ctx.thread.call(_read_once, ctx.engine, HistoryCache.default())
        yield client, ctx


def _read_once(engine, cache) -> None:
    cache.view(engine.bridge(engine.newest()))


def _prior_of(chains_path: Path):  # noqa: F811
    """A prior counted from the NEEM's own chains (orders 0 and 1): enough to take part in every
    ranking, which is all these tests need of it."""
    import json

    from oracle.algorithm.prior import Prior, option_key
    from oracle.calls import option_of
    from oracle.chains import parse_call
    from oracle.ontology import build_ontology

    onto = build_ontology()
    keys = [option_key(option_of(onto, parse_call(json.loads(line)["action"]))) for line in chains_path.read_text().splitlines()]
    tables: dict[tuple[str, ...], Counter[str]] = {(): Counter(keys)}
    for before, after in zip(keys, keys[1:]):
        tables.setdefault((before,), Counter())[after] += 1
    return Prior({context: {k: float(n) for k, n in counts.items()} for context, counts in tables.items()})


def test_the_timeline_comes_from_the_kept_view_as_the_engine_reads_it(served):
    from oracle.historycache import HistoryCache, compact

    client, ctx = served
    neem = client.get("/explore/api/neems").json()[0]["id"]
    sent = client.get(f"/explore/api/neems/{neem}/timeline")
    assert sent.status_code == 200
    rows = ctx.thread.call(lambda: HistoryCache.default().view(ctx.engine.bridge(neem)).rows)
    assert sent.json() == {"neem": neem, "user": ctx.thread.call(lambda: ctx.engine.store.neem(neem).user), **compact(rows)}


def test_a_logged_action_is_on_the_next_timeline(served):
    """The reader keeps a timeline by the store's mark: an action logged since is on the next one."""
    client, ctx = served
    neem = client.get("/explore/api/neems").json()[0]["id"]
    before = client.get(f"/explore/api/neems/{neem}/timeline").json()
    last = max(before["rows"][1::6])
    logged = client.post(f"/api/neems/{neem}/actions", json={"call": "pick(banana)", "begin": last + 3600, "end": last + 3605})
    assert logged.status_code == 200, logged.text
    deadline = time.monotonic() + 30
    while True:
        after = client.get(f"/explore/api/neems/{neem}/timeline")
        rows = after.json()["rows"] if after.status_code == 200 else []
        if rows and rows[-6] == last + 3600:
            break
        assert time.monotonic() < deadline, "the logged action never reached the timeline"
        time.sleep(0.2)
    assert after.json()["calls"][rows[-4]] == "pick(banana)" and len(rows) > len(before["rows"])


def test_the_list_says_which_neems_are_shared(served):
    from oracle.neem.sharing import set_shared

    client, ctx = served
    neem = client.get("/explore/api/neems").json()[0]
    assert neem["consent"] == "not shared"
    ctx.thread.call(set_shared, ctx.engine.store, neem["id"], True)
    assert client.get("/explore/api/neems").json()[0]["consent"] == "shared: its counts may enter a prior"


def test_the_timeline_and_the_page_do_not_wait_for_the_engine_thread(served):
    """A page opened while the engine thread is held (another page's routines, a robot's call)
    gets its shell and its timeline all the same."""
    client, ctx = served
    neem = client.get("/explore/api/neems").json()[0]["id"]
    held, release = threading.Event(), threading.Event()

    def hold() -> None:
        held.set()
        release.wait(30)

    ctx.thread.submit(hold)
    assert held.wait(10)
    try:
        began = time.monotonic()
        page = client.get("/explore")
        timeline = client.get(f"/explore/api/neems/{neem}/timeline")
        took = time.monotonic() - began
        assert page.status_code == 200 and neem in page.text
        assert timeline.status_code == 200 and timeline.json()["rows"]
        assert not release.is_set() and took < 25  # answered while the engine thread was still held
    finally:
        release.set()


def test_a_neem_nothing_was_kept_for_is_read_once_and_says_so(served, monkeypatch):
    from oracle.historycache import kept_history
    from oracle.service import explore_routes

    client, ctx = served
    monkeypatch.setattr(explore_routes, "QUICK_READ_S", 0.0)  # the page is told at once, however quick the read
    with sqlite3.connect(ctx.engine.store.location) as conn:  # as a loaded dump or a NEEM of an older version
        assert conn.execute("DELETE FROM kept WHERE kind='history'").rowcount == 1
    neem = client.get("/explore/api/neems").json()[0]
    assert ctx.thread.call(lambda: kept_history(ctx.engine.store, ctx.engine.ontology, neem["id"])) is None
    first = client.get(f"/explore/api/neems/{neem['id']}/timeline")
    assert first.status_code == 202
    said = first.json()
    assert said["reading"] is True and said["actions"] == neem["actions"] and said["user"] == neem["user"]
    deadline = time.monotonic() + 120
    while (answer := client.get(f"/explore/api/neems/{neem['id']}/timeline")).status_code == 202:
        assert time.monotonic() < deadline, "the first read did not finish"
        time.sleep(0.1)
    assert answer.status_code == 200 and answer.json()["rows"]
    kept = ctx.thread.call(lambda: kept_history(ctx.engine.store, ctx.engine.ontology, neem["id"]))
    assert kept is not None and answer.json()["rows"] == kept["rows"]  # kept now: the next open is the reader's


def test_a_store_that_keeps_nothing_is_read_once_per_open_not_per_poll(store, tmp_path, monkeypatch):  # noqa: F811
    """Where the store cannot keep a view (a MongoDB server: no append mark), an open reads the
    history once and the replay's polls take that read, not one whole read each second."""
    from oracle.service import explore_routes

    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    reads = []
    view = explore_routes._view_in_slices

    async def counted(ctx, neem):
        reads.append(neem)
        return await view(ctx, neem)

    monkeypatch.setattr(explore_routes, "_view_in_slices", counted)
    monkeypatch.setattr(explore_routes, "QUICK_READ_S", 0.0)
    for client, ctx in _client(copy):
        monkeypatch.setattr(ctx.engine.store, "append_mark", lambda neem: None)  # as a server's store answers
        neem = client.get("/explore/api/neems").json()[0]["id"]
        first = client.get(f"/explore/api/neems/{neem}/timeline")
        assert first.status_code == 202 and first.json()["kept_after"] is False
        deadline = time.monotonic() + 120
        while client.get(f"/explore/api/neems/{neem}/timeline").status_code == 202:
            assert time.monotonic() < deadline
            time.sleep(0.1)
        found = _decisions(client, neem)
        assert found["n_predictions"] > 0 and reads == [neem]  # the polls read nothing again
        while client.get(f"/explore/api/neems/{neem}/timeline").status_code == 202:  # a new open reads it again:
            time.sleep(0.1)                                                           # nothing tells it is unchanged
        assert len(reads) == 2


def test_the_prior_shares_are_what_the_predictor_scored_with(store, chains, monkeypatch):  # noqa: F811
    """Every share shown is the prior's part of the very scores the personal predictor ranked
    with: the scores those parts sum to order the offer as the ranking shown, and no ranking
    differs from evaluate's replay with the same prior."""
    from oracle.algorithm.personal import PRIOR_COLUMNS, PersonalOracle
    from oracle.evaluation.neem_replay import neem_chains, replay_neem
    from oracle.evaluation.replay import OracleMethod, ReplayRules, replay, summarize
    from oracle.historycache import HistoryCache
    from oracle.ontology import build_ontology
    from oracle.service import build_context

    onto, settings, prior = build_ontology(), preset("recommended"), _prior_of(chains)
    ctx = build_context(str(store), onto, settings, prior="none")
    try:
        neem = ctx.thread.call(ctx.engine.newest)
        rows = ctx.thread.call(lambda: HistoryCache.default().view(ctx.engine.bridge(neem)).rows)
        user = ctx.thread.call(lambda: ctx.engine.store.neem(neem).user)
    finally:
        ctx.thread.close()
    scored: list[tuple[float, float | None]] = []  # each _combined call: how far the parts' sum is from its scores, the share
    combined = PersonalOracle._combined

    def noted(self, log_p, x, w):
        a = self.served_weight() or 0.0
        k = len(PRIOR_COLUMNS)
        prior_part = (1 - a) * (x[:, -k:] @ w[-k:])
        own_part = a * log_p + (1 - a) * (x[:, :-k] @ w[:-k])
        spreads = [np.abs(v - v.mean()).sum() for v in (prior_part, own_part)]
        served = combined(self, log_p, x, w)
        # the two parts sum to the scores served, up to the one constant a softmax ignores
        scored.append((float(np.ptp(served - (prior_part + own_part))), spreads[0] / sum(spreads) if sum(spreads) else None))
        return served

    monkeypatch.setattr(PersonalOracle, "_combined", noted)
    shown = replay_neem(onto, settings, "personal", rows, user, keep=10, prior=prior)
    assert shown.prior and len(scored) > 10
    shares = [d.prior_share for d in shown.decisions if d.candidates]
    assert [s for s in shares if s is not None] == pytest.approx([s for _, s in scored if s is not None], abs=1e-12)
    assert shares[0] == pytest.approx(1.0)  # nothing learnt yet: the others' habits alone rank
    assert 0.0 < min(s for s in shares if s is not None) < max(s for s in shares if s is not None) <= 1.0
    assert max(off for off, _ in scored) < 1e-9  # the parts are the very scores the ranking was made with
    # and no ranking differs from evaluate's replay with the same prior
    monkeypatch.setattr(PersonalOracle, "_combined", combined)
    plain = replay(onto, {user: neem_chains(rows, user)}, [OracleMethod(onto, settings, method="personal",
                                                                        served=ReplayRules().served)],
                   protocol=ReplayRules(), priors=lambda _: prior)
    assert [o.ranks["personal"] for o in plain.outcomes] == [d.rank for d in shown.decisions]
    assert summarize(plain)["methods"]["personal"]["top1"] == shown.summary["methods"]["personal"]["top1"]


def test_the_decisions_route_shows_the_prior_share(store, chains, tmp_path):  # noqa: F811
    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    for client, ctx in _client(copy, _prior_of(chains)):
        if ctx.engine.method != "personal":
            pytest.skip(f"the service's predictor is {ctx.engine.method}, not personal: no prior is blended")
        neem = client.get("/explore/api/neems").json()[0]["id"]
        found = _decisions(client, neem)
        prior = found["prior"]
        assert prior["given"] is True and len(prior["shares"]) == len(found["rank"])
        used = [s for s in prior["shares"] if s is not None]
        assert prior["decisions"] == len(used) > 0 and prior["mean"] == pytest.approx(sum(used) / len(used), abs=1e-3)
    for client, _ in _client(copy):  # without a prior: said so, no shares
        neem = client.get("/explore/api/neems").json()[0]["id"]
        prior = _decisions(client, neem)["prior"]
        assert prior["given"] is False and prior["decisions"] == 0 and prior["mean"] is None


# -- the page in chromium ------------------------------------------------------------------------
def test_the_page_says_what_it_reads_and_shows_the_prior_share(store, chains, browser, axe_source, tmp_path):  # noqa: F811
    """A first read through Prolog is said on the page (no blank page) and the timeline follows;
    with ``serve --prior`` each decision says the prior's share, the figures its mean, and the page
    stays keyboard usable and axe-clean with them."""
    import json
    import urllib.request

    from tests.service.test_server import free_port, serious, start_server, stop_server

    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    prior = tmp_path / "prior.json"
    _prior_of(chains).save(prior)
    port = free_port()
    process = start_server(copy, port, "--prior", str(prior))
    try:
        url = f"http://127.0.0.1:{port}"
        page = browser.new_page(viewport={"width": 1280, "height": 1000}, bypass_csp=True)
        errors: list[str] = []
        page.on("pageerror", lambda error: errors.append(str(error)))
        told = []

        def reading_once(route):  # the service's answer while it reads a NEEM nothing was kept for
            if told:
                route.continue_()
                return
            told.append(True)
            route.fulfill(status=202, content_type="application/json",
                          body=json.dumps({"reading": True, "neem": "n", "user": "someone", "actions": 1234, "seconds": 2.5}))

        page.route("**/timeline", reading_once)
        page.goto(url + "/explore")
        page.wait_for_function("document.getElementById('timeline-status').textContent.startsWith('Reading')")
        said = page.locator("#timeline-status").text_content()
        assert "someone (1234 actions) through Prolog" in said and "2.5 s so far" in said
        for button in ("#zoom-in", "#zoom-out", "#zoom-reset"):  # before any timeline: nothing to zoom, no error
            page.locator(button).click()
        page.wait_for_function("performance.getEntriesByName('timeline-painted').length > 0", timeout=60_000)
        assert page.evaluate("performance.getEntriesByName('timeline-reading').length") == 1
        page.wait_for_function("window.neemExplorer.state.decisions !== null", timeout=300_000)
        neem = json.loads(urllib.request.urlopen(url + "/explore/api/neems", timeout=30).read())[0]["id"]
        found = json.loads(urllib.request.urlopen(f"{url}/explore/api/neems/{neem}/decisions", timeout=60).read())
        shares = found["prior"]["shares"]
        page.locator("#timeline").focus()
        page.keyboard.press("Home")
        page.keyboard.press("ArrowRight")
        shown = page.locator("#decision .share").text_content()
        if shares[1] is None:
            assert "took no part" in shown
        else:
            percent = int(shares[1] * 100 + 0.5)  # as Math.round: half up
            assert shown.startswith(f"Where the ranking came from: {percent} % the shared prior")
        figures = page.locator("#figures").text_content()
        assert f"The shared prior took part in {found['prior']['decisions']} of {len(found['rank'])} rankings" in figures
        assert f"on average {found['prior']['mean'] * 100:.1f} %" in figures
        assert serious(page, axe_source) == []
        assert errors == []
        page.close()
    finally:
        stop_server(process)
