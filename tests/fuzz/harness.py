"""Run fuzz targets (targets.TARGETS) under atheris: ``python -m tests.fuzz.harness NAME [NAME...]
[-- libFuzzer options]``, e.g. ``-- -max_total_time=60 -rss_limit_mb=1024``. Several names run one
after another (each in its own process: libFuzzer exits when it stops). A crash leaves its input
as ``crash-*`` in the working directory: save it under ``regressions/NAME/`` and test_fuzz.py
replays it from then on.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

#: The repository (``tests`` is a package there): each target's process starts from it.
ROOT = Path(__file__).resolve().parents[2]


def main(argv: list[str]) -> int:
    cut = argv.index("--") if "--" in argv else len(argv)
    names, options = argv[:cut], argv[cut + 1:]
    if len(names) == 1:
        return _fuzz(names[0], options)
    worst = 0
    for name in names:  # one process each: libFuzzer ends the process it runs in
        worst = max(worst, subprocess.call([sys.executable, "-m", "tests.fuzz.harness", name, "--", *options], cwd=ROOT))
    return worst


def _fuzz(name: str, options: list[str]) -> int:
    import atheris

    with atheris.instrument_imports(include=["oracle"]):
        from tests.fuzz.targets import TARGETS
    if name not in TARGETS:
        print(f"error: no fuzz target {name!r}; known: {', '.join(sorted(TARGETS))}", file=sys.stderr)
        return 2
    atheris.Setup([sys.argv[0], *options], TARGETS[name])
    atheris.Fuzz()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
