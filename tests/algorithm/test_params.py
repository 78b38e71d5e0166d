"""Hyperparameters: Table 4.2 defaults, Fig. 5.5 presets, YAML round trip, validation."""

from __future__ import annotations

import pytest

from algoworld import random_matrix
from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import PRESETS, Hyperparameters, load_settings, preset, save_settings
from oracle.errors import SettingsError


def test_defaults_are_table_4_2():
    assert Hyperparameters().to_dict() == {
        "object_factor": 1.0, "task_factor": 2.0, "knockout": 1.16, "penalty": 3.7,
        "event_horizon_backwards": 16, "decreasing_importance_factor": 0.81, "compare_situations": 1.0,
        "time_of_day_penalty": 1.18, "event_horizon_forward": 3, "multiple_occurrences_factor": 0.25}
    assert PreferenceOracle().get_params() | {"distances": None} == {
        "distances": None, "opening_tasks": frozenset(), **Hyperparameters().to_dict()}


@pytest.mark.parametrize("name, field, value", [
    ("B", "compare_situations", 0.0), ("C", "time_of_day_penalty", 10.0), ("D", "time_of_day_penalty", 1.0),
    ("E", "multiple_occurrences_factor", 1.0), ("F", "multiple_occurrences_factor", 0.0),
    ("G", "decreasing_importance_factor", 1.0), ("H", "object_factor", 0.0), ("I", "task_factor", 0.0),
    ("J", "penalty", 1.16), ("K", "penalty", 20.0), ("L", "knockout", 0.0), ("M", "knockout", 20.0),
    ("N", "event_horizon_backwards", 0)])
def test_fig_5_5_presets_change_one_parameter(name, field, value):
    changed = {k for k, v in PRESETS[name].to_dict().items() if v != PRESETS["A"].to_dict()[k]}
    assert changed == {field} and getattr(PRESETS[name], field) == value


def test_yaml_round_trip_with_thesis_names_and_preset(tmp_path):
    path = tmp_path / "s.yaml"
    save_settings(PRESETS["K"], path)
    assert load_settings(path) == PRESETS["K"]
    path.write_text("preset: no_situations\nevent horizon backwards: 4\nmultiple occurrence factor: 0.7\n")
    loaded = load_settings(path)
    assert (loaded.compare_situations, loaded.event_horizon_backwards, loaded.multiple_occurrences_factor) == (0.0, 4, 0.7)
    oracle = PreferenceOracle.from_settings(random_matrix(0), loaded)
    assert oracle.get_params()["event_horizon_backwards"] == 4


@pytest.mark.parametrize("text, message", [
    ("knockout: -1\n", "knockout"), ("nockout: 1\n", "unknown hyperparameter"),
    ("decreasing importance factor: 0\n", "decreasing_importance_factor"),
    ("event horizon forward: 2.5\n", "whole number"), ("penalty: high\n", "number"),
    ("[1, 2]\n", "mapping"), ("knockout: [\n", "malformed YAML"), ("preset: Z\n", "unknown preset")])
def test_bad_settings_name_the_file_and_entry(tmp_path, text, message):
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(SettingsError, match=message) as error:
        load_settings(path)
    assert "bad.yaml" in str(error.value)


def test_invalid_constructor_params_fail_at_fit():
    with pytest.raises(SettingsError, match="penalty"):
        PreferenceOracle(random_matrix(0), penalty=float("nan")).fit([])
    assert preset("b") == PRESETS["B"]


def test_every_predictor_takes_table_4_2_defaults_from_one_place():
    """The routine predictor reuses some thesis parameters in the same roles: same defaults, and
    the scikit-learn contract from the same base (get_params lists exactly the constructor's)."""
    import inspect

    from oracle.algorithm.fast import PreferenceOracle
    from oracle.algorithm.params import Hyperparameters
    from oracle.algorithm.routine import RoutineOracle

    thesis = Hyperparameters().to_dict()
    for cls in (PreferenceOracle, RoutineOracle):
        signature = inspect.signature(cls.__init__)
        shared = {name: p.default for name, p in signature.parameters.items() if name in thesis}
        assert shared and shared == {name: thesis[name] for name in shared}, cls.__name__
        model = cls()
        assert set(model.get_params()) == set(signature.parameters) - {"self"}
        with pytest.raises(SettingsError, match="unknown parameter"):
            model.set_params(no_such_parameter=1)
