"""The routine predictor's settings checked before a fit: every parameter's domain, one line each
error (docs/algorithm.md, "Parameters")."""

from __future__ import annotations

import math
from typing import Any

from oracle.errors import SettingsError

#: token streams: idle steps as tokens / contexts that run across idle steps
STREAMS = ("idle", "through")
TUNINGS = ("leader", "mixture", "fixed")


def check_settings(model: Any) -> None:
    """Raise SettingsError, naming the parameter, for any setting of ``model`` (a
    ``RoutineOracle``) outside its domain (docs/algorithm.md, "Parameters")."""
    name = type(model).__name__
    if not model.orders or any(isinstance(n, bool) or not isinstance(n, int) or n < 0 for n in model.orders):
        raise SettingsError(f"{name}: orders must be whole numbers >= 0, got {model.orders!r}")
    if not model.lowest_orders or any(isinstance(n, bool) or not isinstance(n, int) or n not in (0, 1)
                                     for n in model.lowest_orders):
        raise SettingsError(f"{name}: lowest_orders must be 0 or 1, got {model.lowest_orders!r}")
    if not model.timed or any(not isinstance(t, bool) for t in model.timed):
        raise SettingsError(f"{name}: timed must be True or False values, got {model.timed!r}")
    if not model.discounts or any(not isinstance(t, bool) for t in model.discounts):
        raise SettingsError(f"{name}: discounts must be True or False values, got {model.discounts!r}")
    if isinstance(model.discount_from, bool) or not isinstance(model.discount_from, int) or model.discount_from < 0:
        raise SettingsError(f"{name}: discount_from must be a whole number >= 0, got {model.discount_from!r}")
    if (isinstance(model.discount_evidence, bool) or not isinstance(model.discount_evidence, int)
            or model.discount_evidence < 0):
        raise SettingsError(f"{name}: discount_evidence must be a whole number >= 0, got {model.discount_evidence!r}")
    if model.timed_discount_from is not None and (isinstance(model.timed_discount_from, bool)
                                                 or not isinstance(model.timed_discount_from, int)
                                                 or model.timed_discount_from < 0):
        raise SettingsError(f"{name}: timed_discount_from must be None or a whole number >= 0, "
                            f"got {model.timed_discount_from!r}")
    if model.timed_to is not None and (isinstance(model.timed_to, bool) or not isinstance(model.timed_to, int)
                                      or model.timed_to < 0):
        raise SettingsError(f"{name}: timed_to must be None or a whole number >= 0, got {model.timed_to!r}")
    if model.timed_blend is not None and (isinstance(model.timed_blend, bool)
                                         or not isinstance(model.timed_blend, (int, float))
                                         or not 0 <= model.timed_blend <= 1):
        raise SettingsError(f"{name}: timed_blend must be None or a number from 0 to 1, got {model.timed_blend!r}")
    if isinstance(model.focus, bool) or not isinstance(model.focus, int) or model.focus < 0:
        raise SettingsError(f"{name}: focus must be a whole number >= 0, got {model.focus!r}")
    if not isinstance(model.resume, bool):
        raise SettingsError(f"{name}: resume must be True or False, got {model.resume!r}")
    if not isinstance(model.fresh, bool):
        raise SettingsError(f"{name}: fresh must be True or False, got {model.fresh!r}")
    if model.fresh_level not in ("base", "top"):
        raise SettingsError(f"{name}: fresh_level must be base or top, got {model.fresh_level!r}")
    if not isinstance(model.focus_odds, bool):
        raise SettingsError(f"{name}: focus_odds must be True or False, got {model.focus_odds!r}")
    if model.focus_level not in ("base", "top"):
        raise SettingsError(f"{name}: focus_level must be base or top, got {model.focus_level!r}")
    if not isinstance(model.timed_shrink, bool):
        raise SettingsError(f"{name}: timed_shrink must be True or False, got {model.timed_shrink!r}")
    if isinstance(model.timed_from, bool) or not isinstance(model.timed_from, int) or model.timed_from < 0:
        raise SettingsError(f"{name}: timed_from must be a whole number >= 0, got {model.timed_from!r}")
    if not model.temperatures or any(not (isinstance(t, (int, float)) and math.isfinite(t) and t > 0)
                                    for t in model.temperatures):
        raise SettingsError(f"{name}: temperatures must be positive numbers, got {model.temperatures!r}")
    if not model.streams or any(s not in STREAMS for s in model.streams):
        raise SettingsError(f"{name}: streams must be among {', '.join(STREAMS)}, got {model.streams!r}")
    if model.timed_gate is not None and (isinstance(model.timed_gate, bool) or not isinstance(model.timed_gate, (int, float))
                                        or not math.isfinite(model.timed_gate)):
        raise SettingsError(f"{name}: timed_gate must be a number (a standard normal quantile) or None, "
                            f"got {model.timed_gate!r}")
    if not isinstance(model.exclusion, bool):
        raise SettingsError(f"{name}: exclusion must be True or False, got {model.exclusion!r}")
    if not isinstance(model.novelty, (tuple, list)) or not model.novelty or any(not isinstance(t, bool) for t in model.novelty):
        raise SettingsError(f"{name}: novelty must be True or False values, got {model.novelty!r}")
    if model.tuning not in TUNINGS:
        raise SettingsError(f"{name}: tuning must be one of {', '.join(TUNINGS)}, got {model.tuning!r}")
    if isinstance(model.tuning_window, bool) or not isinstance(model.tuning_window, int) or model.tuning_window < 0:
        raise SettingsError(f"{name}: tuning_window must be a whole number >= 0, got {model.tuning_window!r}")
    if not isinstance(model.context_depth, int) or model.context_depth < 0:
        raise SettingsError(f"{name}: context_depth must be a whole number >= 0, got {model.context_depth!r}")
    edges = model.recency
    if (not isinstance(edges, (tuple, list))
            or any(isinstance(e, bool) or not isinstance(e, (int, float)) or not math.isfinite(e) or e <= 0 for e in edges)
            or any(b <= a for a, b in zip(edges, edges[1:]))):
        raise SettingsError(f"{name}: recency must be increasing positive seconds (empty: off), got {edges!r}")
    for value, what in ((model.context_decay, "context_decay"), (model.switch_margin, "switch_margin"),
                        (model.recency_gate, "recency_gate"),
                        (model.task_factor, "task_factor"), (model.object_factor, "object_factor"), (model.penalty, "penalty"),
                        (model.time_of_day_penalty, "time_of_day_penalty")):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
            raise SettingsError(f"{name}: {what} must be a number >= 0, got {value!r}")
