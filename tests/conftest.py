"""Session-wide test set-up: the suite's caches stay out of the user's own."""

from __future__ import annotations

import os
from collections.abc import Iterator

import pytest


@pytest.fixture(scope="session", autouse=True)
def _private_cache(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """Built ontologies, distance matrices, compiled modules, fits and histories of the suite go
    to a folder of its own (child processes inherit it), not to ~/.cache/neem-oracle; a
    NEEM_ORACLE_CACHE set by the caller is kept."""
    set_here = [name for name in ("NEEM_ORACLE_CACHE", "NEEM_ORACLE_KEY_DIR") if not os.environ.get(name)]
    for name in set_here:  # the key of kept fits too (oracle.files.default_key_dir), not ~/.config's
        os.environ[name] = str(tmp_path_factory.mktemp(name.lower()))
    try:
        yield
    finally:
        for name in set_here:
            os.environ.pop(name, None)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Three kinds of test run with the slow ones (in CI, or `make test SLOW=1`), whatever their
    own marks say: those that drive the page in chromium, the mongomock-ng copies of tests
    parametrized over backends (their SQLite copy runs every time), and those that wait out one
    of the service's real deadlines."""
    slow = pytest.mark.slow
    for item in items:
        params = getattr(getattr(item, "callspec", None), "params", {})
        if (
            "browser" in getattr(item, "fixturenames", ())
            or "mongomock" in params.values()
            or item.get_closest_marker("deadline") is not None
        ):
            item.add_marker(slow)
