"""The fuzz targets (targets.py): every saved input replays clean, and a bounded atheris run of
each finds no crash (``make fuzz`` runs them longer)."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

from oracle.service import bodyshape
from tests.fuzz.targets import TARGETS, reference_shape

HERE = Path(__file__).parent
ROOT = HERE.parent.parent
#: Seconds of atheris per target: 30 in CI (where CI is set: .ci/run sets it), 10 in a
#: developer's make test, which is kept within 3 minutes; make fuzz: FUZZ_SECONDS, 600 by default.
SECONDS = int(os.environ.get("NEEM_FUZZ_SECONDS") or (30 if os.environ.get("CI") else 10))
SAVED = sorted((p.parent.name, p) for p in (HERE / "regressions").glob("*/*") if p.is_file())


@pytest.mark.parametrize(("target", "path"), SAVED, ids=[f"{t}/{p.name}" for t, p in SAVED])
def test_every_saved_input_replays_clean(target, path):
    TARGETS[target](path.read_bytes())


def test_a_utf16_body_is_refused_rather_than_miscounted():
    """json.loads reads UTF-16 too, where half of U+2200 is a quote byte: the scan would see a
    string where the parser sees 40 brackets."""
    body = '["\u2200'.encode("utf-16-le") + b"[\x00" * 40 + "\"]".encode("utf-16-le")
    shape = bodyshape.measure(body)
    assert not shape.utf8 and bodyshape.refusal(shape, 32, 50_000, 100, 65536) == "the request body is not UTF-8 JSON"


def test_the_reference_agrees_on_the_worst_bodies():
    from oracle.benchmarks.flood import worst_bodies

    for name, body in worst_bodies(4096).items():
        expected = reference_shape(body)
        if expected is not None:
            assert bodyshape.measure(body) == expected, name


@pytest.mark.skipif(importlib.util.find_spec("atheris") is None,
                    reason="atheris is not installed (make setup installs the dev extra; it has wheels for CPython 3.11-3.13)")
@pytest.mark.parametrize("target", sorted(TARGETS))
def test_atheris_finds_no_crash(target, tmp_path):
    run = subprocess.run([sys.executable, "-m", "tests.fuzz.harness", target, "--", f"-max_total_time={SECONDS}", "-timeout=20",
                          "-rss_limit_mb=2048", f"-artifact_prefix={tmp_path}/"],
                         cwd=ROOT, capture_output=True, text=True, timeout=SECONDS + 120)  # fmt: skip
    crashes = sorted(tmp_path.glob("crash-*")) + sorted(tmp_path.glob("oom-*")) + sorted(tmp_path.glob("timeout-*"))
    assert run.returncode == 0 and not crashes, (
        f"atheris found a crash in {target}: {[str(p) for p in crashes]} (save it under tests/fuzz/regressions/{target}/)\n"
        + run.stderr[-3000:])
