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
