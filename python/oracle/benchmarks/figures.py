"""How the benchmarks summarise repeated runs: min/median/max, and growth between sizes."""

from __future__ import annotations

import math


def spread(samples: list[float]) -> dict[str, float]:
    """Min, median and max of repeated runs, and how many runs there were."""
    ordered = sorted(samples)
    return {"min": ordered[0], "median": ordered[len(ordered) // 2], "max": ordered[-1], "runs": len(ordered)}


def spread_text(figure: dict[str, float], unit: float = 1.0, digits: int = 2) -> str:
    """``min/median/max`` of a spread, scaled by ``unit``."""
    return "/".join(f"{figure[k] * unit:.{digits}f}" for k in ("min", "median", "max"))


def growth_exponent(sizes: list[int], values: list[float]) -> float | None:
    """The growth exponent k of value ~ size^k between the two largest sizes."""
    if len(sizes) < 2 or values[-2] <= 0 or values[-1] <= 0:
        return None
    return math.log(values[-1] / values[-2]) / math.log(sizes[-1] / sizes[-2])


def installed_env(**extra: str) -> dict[str, str]:
    """The environment for timing ``python -m oracle`` as an installed package runs: the
    package's ``.pyc`` written first (an install writes them) and PYTHONDONTWRITEBYTECODE
    unset, so a call never compiles a module it imports."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    env = {**os.environ, **extra}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(Path(__file__).resolve().parents[1])],
                   check=True, env=env)
    return env


#: Runs argv[2:] and writes its CPU seconds and peak RSS (KiB) to argv[1]. A child started
#: from the bench itself reports the bench's own RSS as its peak: Linux keeps the high-water
#: mark of the image a process had before exec (subprocess forks the bench, ~250 MiB after
#: the floors read the rows of a 50,000-action NEEM). From this small launcher it is ~10 MiB.
_MEASURED = """
import os, sys
pid = os.fork()
if pid == 0:
    os.execv(sys.argv[2], sys.argv[2:])
_, status, usage = os.wait4(pid, 0)
with open(sys.argv[1], "w") as out:
    out.write(f"{usage.ru_utime + usage.ru_stime} {usage.ru_maxrss}")
sys.exit(os.waitstatus_to_exitcode(status))
"""


def run_measured(argv: list[str], env: dict[str, str]) -> tuple[float, float, int]:
    """Wall seconds of ``argv`` run through ``_MEASURED``, and the CPU seconds and peak RSS
    (KiB) of that command alone."""
    import sys
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as tmp:
        report = Path(tmp) / "usage"
        wall, _, _ = run_child([sys.executable, "-c", _MEASURED, str(report), *argv], env)
        cpu, peak = report.read_text().split()
    return wall, float(cpu), int(peak)


def run_child(argv: list[str], env: dict[str, str]) -> tuple[float, float, int]:
    """Wall seconds, CPU seconds and peak RSS (KiB) of one child process run to exit."""
    import os
    import subprocess
    import time

    start = time.perf_counter()
    child = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    err = child.stderr.read().decode() if child.stderr else ""
    if child.stderr:
        child.stderr.close()
    if child.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)} failed: {err.strip()[-400:]}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss
