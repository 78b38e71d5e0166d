"""The ten hyperparameters of the PreferenceOracle (thesis Table 4.2), their presets and YAML files.

``Hyperparameters`` is the validated record; ``PRESETS`` holds the Fig. 5.5 settings A-N;
``OracleParams`` gives the estimators their scikit-learn ``get_params``/``set_params``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace
from pathlib import Path
from typing import Any, Self

import yaml

from oracle.errors import SettingsError
from oracle.yamlfile import read_yaml


@dataclass(frozen=True)
class Hyperparameters:
    """Thesis Table 4.2 ("recommended") as defaults; ``event_horizon_forward`` was not trained: 3 as in Fig. 4.6."""

    object_factor: float = 1.0
    task_factor: float = 2.0
    knockout: float = 1.16
    penalty: float = 3.7
    event_horizon_backwards: int = 16
    decreasing_importance_factor: float = 0.81
    compare_situations: float = 1.0
    time_of_day_penalty: float = 1.18
    event_horizon_forward: int = 3
    multiple_occurrences_factor: float = 0.25

    def __post_init__(self) -> None:
        validate(asdict(self))

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


NAMES: tuple[str, ...] = tuple(f.name for f in fields(Hyperparameters))
_INTS = {"event_horizon_backwards", "event_horizon_forward"}


#: The valid range of every hyperparameter: (lowest, highest), both included except a lowest of
#: ``decreasing_importance_factor`` (0 would erase every predecessor level, eq. 4.11). The
#: thesis values and the Fig. 5.5 presets lie well inside; the upper ends bound the work (the
#: horizons are loop counts) and keep scores finite, and are documented in docs/algorithm.md.
RANGES: dict[str, tuple[float, float]] = {
    "object_factor": (0.0, 100.0),
    "task_factor": (0.0, 100.0),
    "knockout": (0.0, 1000.0),
    "penalty": (0.0, 1000.0),
    "event_horizon_backwards": (0, 1000),
    "decreasing_importance_factor": (0.0, 1.0),
    "compare_situations": (0.0, 100.0),
    "time_of_day_penalty": (0.0, 1000.0),
    "event_horizon_forward": (0, 100),
    "multiple_occurrences_factor": (0.0, 100.0),
}


def validate(values: dict[str, Any], where: str = "settings") -> None:
    """Raise SettingsError naming ``where`` and the entry when a value is missing, mistyped or out of range."""
    for name in NAMES:
        if name not in values:
            raise SettingsError(f"{where}: missing {name!r}")
        value = values[name]
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SettingsError(f"{where}: {name!r} must be a number, got {_short(value)}")
        low, high = RANGES[name]
        if isinstance(value, int) and not low <= value <= high:
            # Compared as an int first: a 400-digit integer does not fit in a float.
            raise SettingsError(f"{where}: {name!r} must be in [{low:g}, {high:g}], got {_short(value)}")
        if not math.isfinite(value):
            raise SettingsError(f"{where}: {name!r} must be finite, got {value!r}")
        if name in _INTS and not float(value).is_integer():
            raise SettingsError(f"{where}: {name!r} must be a whole number, got {value!r}")
        if name == "decreasing_importance_factor":
            if not low < value <= high:
                raise SettingsError(f"{where}: 'decreasing_importance_factor' must be in (0, 1], got {value!r}")
        elif not low <= value <= high:
            raise SettingsError(f"{where}: {name!r} must be in [{low:g}, {high:g}], got {value!r}")


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 40 else f"{text[:20]}... ({len(text)} characters)"


def _canonical_name(key: object, where: str) -> str:
    name = str(key).strip().lower().replace(" ", "_").replace("-", "_")
    if name == "multiple_occurrence_factor":  # the spelling of Table 4.2
        name = "multiple_occurrences_factor"
    if name not in NAMES:
        raise SettingsError(f"{where}: unknown hyperparameter {key!r} (known: {', '.join(NAMES)})")
    return name


def from_mapping(mapping: dict[str, Any], where: str = "settings") -> Hyperparameters:
    """Build settings from a mapping: optional ``preset`` (A-N or a name) plus overrides.

    Keys may be written as in the thesis ("event horizon backwards") or in snake_case.
    """
    if not isinstance(mapping, dict):
        raise SettingsError(f"{where}: expected a mapping of hyperparameters, got {type(mapping).__name__}")
    base = PRESETS["recommended"]
    values = dict(mapping)
    if "preset" in values:
        base = preset(str(values.pop("preset")), where)
    merged: dict[str, Any] = base.to_dict()
    for key, value in values.items():
        merged[_canonical_name(key, where)] = value
    validate(merged, where)
    for name in _INTS:
        merged[name] = int(merged[name])
    return Hyperparameters(**merged)


def load_settings(path: Path | str) -> Hyperparameters:
    """Read a YAML settings file; errors name the file."""
    path = Path(path)
    from oracle.handed import SETTINGS_LIMIT

    data = read_yaml(path, SettingsError, "settings", SETTINGS_LIMIT)
    return from_mapping(data if data is not None else {}, str(path))


def save_settings(settings: Hyperparameters, path: Path | str) -> None:
    """Write settings as YAML with the thesis names as comments-free snake_case keys."""
    from oracle.files import private_file

    with private_file(path) as handle:  # 0600 whatever the umask, like every file the tool writes
        handle.write(yaml.safe_dump(settings.to_dict(), sort_keys=False))


_DEFAULTS = Hyperparameters()  # Table 4.2, "recommended"
#: Table 4.2's values, for predictors that reuse some of them in the same roles (``routine``).
THESIS_DEFAULTS = _DEFAULTS

#: Thesis Fig. 5.5 settings: each is the recommended settings with one parameter changed.
PRESETS: dict[str, Hyperparameters] = {
    "A": _DEFAULTS,
    "B": replace(_DEFAULTS, compare_situations=0.0),
    "C": replace(_DEFAULTS, time_of_day_penalty=10.0),
    "D": replace(_DEFAULTS, time_of_day_penalty=1.0),
    "E": replace(_DEFAULTS, multiple_occurrences_factor=1.0),
    "F": replace(_DEFAULTS, multiple_occurrences_factor=0.0),
    "G": replace(_DEFAULTS, decreasing_importance_factor=1.0),
    "H": replace(_DEFAULTS, object_factor=0.0),
    "I": replace(_DEFAULTS, task_factor=0.0),
    "J": replace(_DEFAULTS, penalty=_DEFAULTS.knockout),
    "K": replace(_DEFAULTS, penalty=20.0),
    "L": replace(_DEFAULTS, knockout=0.0),
    "M": replace(_DEFAULTS, knockout=20.0),
    "N": replace(_DEFAULTS, event_horizon_backwards=0),
}
PRESETS["recommended"] = PRESETS["A"]
PRESETS["no_situations"] = PRESETS["B"]


def preset(name: str, where: str = "settings") -> Hyperparameters:
    """A named preset: A-N (Fig. 5.5), "recommended" (= A) or "no_situations" (= B)."""
    key = name.strip()
    if key.upper() in PRESETS and len(key) == 1:
        key = key.upper()
    if key not in PRESETS:
        raise SettingsError(f"{where}: unknown preset {name!r} (known: {', '.join(PRESETS)})")
    return PRESETS[key]


class EstimatorParams:
    """scikit-learn's ``get_params``/``set_params``, for every predictor: a subclass lists its
    constructor arguments in ``_param_names`` and its ``__init__`` only stores them."""

    _param_names: tuple[str, ...] = ()

    def get_params(self, deep: bool = True) -> dict[str, Any]:
        return {name: getattr(self, name) for name in self._param_names}

    def set_params(self, **params: Any) -> Self:
        for name, value in params.items():
            if name not in self._param_names:
                raise SettingsError(f"unknown parameter {name!r} for {type(self).__name__}")
            setattr(self, name, value)
        return self


class OracleParams(EstimatorParams):
    """The thesis oracle's parameters (Table 4.2), shared by the reference and the fast oracle."""

    _param_names: tuple[str, ...] = ("distances", "opening_tasks", *NAMES)

    def __init__(self, distances: Any = None, *, opening_tasks: frozenset[str] = frozenset(),
                 object_factor: float = _DEFAULTS.object_factor, task_factor: float = _DEFAULTS.task_factor,
                 knockout: float = _DEFAULTS.knockout, penalty: float = _DEFAULTS.penalty,
                 event_horizon_backwards: int = _DEFAULTS.event_horizon_backwards,
                 decreasing_importance_factor: float = _DEFAULTS.decreasing_importance_factor,
                 compare_situations: float = _DEFAULTS.compare_situations,
                 time_of_day_penalty: float = _DEFAULTS.time_of_day_penalty,
                 event_horizon_forward: int = _DEFAULTS.event_horizon_forward,
                 multiple_occurrences_factor: float = _DEFAULTS.multiple_occurrences_factor) -> None:
        # The defaults are Hyperparameters' (Table 4.2), written once there; each argument is
        # spelled out so the signature shows the estimator's parameters (scikit-learn's contract).
        self.distances = distances
        self.opening_tasks = opening_tasks
        self.object_factor = object_factor
        self.task_factor = task_factor
        self.knockout = knockout
        self.penalty = penalty
        self.event_horizon_backwards = event_horizon_backwards
        self.decreasing_importance_factor = decreasing_importance_factor
        self.compare_situations = compare_situations
        self.time_of_day_penalty = time_of_day_penalty
        self.event_horizon_forward = event_horizon_forward
        self.multiple_occurrences_factor = multiple_occurrences_factor

    def hyperparameters(self) -> Hyperparameters:
        """The current hyperparameters, validated (raises SettingsError)."""
        values = {name: getattr(self, name) for name in NAMES}
        validate(values, type(self).__name__)
        for name in _INTS:
            values[name] = int(values[name])
        return Hyperparameters(**values)

    @classmethod
    def from_settings(cls, distances: Any, settings: Hyperparameters | str = "recommended",
                      opening_tasks: frozenset[str] = frozenset()) -> Self:
        """Build an oracle from a Hyperparameters record or a preset name."""
        if isinstance(settings, str):
            settings = preset(settings)
        return cls(distances, opening_tasks=opening_tasks, **settings.to_dict())
