"""Who performs an action: the persona's autonomy profile and the predictor of the usual mode."""

from __future__ import annotations

from oracle.past.autonomy import ModeCounts, Performed, fit
from oracle.world.autonomy import autonomy_profile, modes_of
from oracle.world.personas import make_persona


def test_the_most_specific_context_decides():
    model = fit([Performed("pour(thermos, red_mug)", "Morning", "robot")] * 2
                + [Performed("pour(milk_carton, red_mug)", "Morning", "user")] * 3
                + [Performed("pour(thermos, red_mug)", "Evening", "user")])
    assert model.predict("pour(thermos, red_mug)", "Morning") == ("robot", "call and part")
    assert model.predict("pour(milk_carton, red_mug)", "Evening") == ("user", "call")
    assert model.predict("pour(juice, red_mug)", "Morning") == ("user", "task and part")
    assert ModeCounts().predict("pick(apple)", "Morning") == ("user", "none")  # nothing seen: the user's


def test_a_weak_grip_leaves_pouring_to_the_robot():
    weak = next(p for p in (make_persona(0, i) for i in range(60)) if "weak grip" in p.persona)
    profile = autonomy_profile(weak, 0)
    assert profile.by_hand("pour", ("thermos", "red_mug"), 20.0) < profile.by_hand("pour", ("thermos", "red_mug"), 9.0)
    assert profile.by_hand("pour", ("thermos", "red_mug"), 9.0) < 0.5 < profile.by_hand("eat", ("apple",), 9.0)


def test_modes_are_a_pure_function_of_seed_and_persona():
    from oracle.world.generate import simulate
    from oracle.world.worldfile import load_world

    persona = make_persona(0, 4)
    rows, _ = simulate(persona, load_world(), 2, 0)
    assert modes_of(persona, rows, 0) == modes_of(persona, rows, 0)
    assert set(modes_of(persona, rows, 0)) == {"user", "robot"}
