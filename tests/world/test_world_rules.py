from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from oracle.chains import TaskCall, parse_call
from oracle.errors import ChainSyntaxError, NeemOracleError, WorldError
from oracle.world.worldfile import default_world, load_world
from oracle.world.state import HAND

TABLE_5_1 = (
    "kitchen_table counter_top thermos water_bottle bread big_drawer knife spoon fork chamomile_tea_bag "
    "peppermint_tea_bag green_tea_bag black_tea_bag chai_tea_bag small_drawer instant_coffee red_mug green_mug "
    "blue_mug drinking_glass espresso_cup cereal_bowl cereal_box plate fruit_bowl orange apple lemon banana fridge "
    "milk_carton juice beer_bottle cucumber avocado yogurt tap coffee_machine microwave dish_washer stove"
).split()


@pytest.fixture(scope="module")
def world():
    return load_world()


def calls(*texts):
    return [parse_call(t) for t in texts]


def run(world, *texts):
    state = world.initial_state()
    for call in calls(*texts):
        state = world.apply(state, call)
    return state


def test_world_has_exactly_the_table_5_1_objects(world):
    assert list(world.objects) == TABLE_5_1


def test_world_affordances_are_the_odb_tasks(world):
    odb_dir = default_world().parent / "kitchen-odb"
    if not odb_dir.is_dir():
        pytest.skip("ontology/kitchen-odb/ is absent")
    from oracle.ontology.odb import read_odb

    odb = read_odb(odb_dir)
    for name, spec in world.objects.items():
        assert name in odb, name
        assert set(odb[name].tasks) == set(spec.affords), name


def test_initial_state_follows_table_5_1_containment(world):
    state = world.initial_state()
    assert state.location["knife"] == "big_drawer"
    assert state.location["red_mug"] == "small_drawer"
    assert state.location["banana"] == "fruit_bowl"
    assert state.location["yogurt"] == "fridge"
    assert state.held is None and not state.opened and not state.switched_on


def test_closed_drawer_hides_its_contents(world):
    state = world.initial_state()
    available = set(world.available(state))
    assert TaskCall("pick", ("banana",)) in available  # fruit bowl is always open
    assert TaskCall("pick", ("red_mug",)) not in available
    state = world.apply(state, parse_call("open(small_drawer)"))
    available = set(world.available(state))
    assert TaskCall("pick", ("red_mug",)) in available
    assert TaskCall("close", ("small_drawer",)) in available
    assert TaskCall("open", ("small_drawer",)) not in available


def test_pick_needs_a_free_hand_and_place_needs_the_held_object(world):
    state = run(world, "pick(thermos)")
    assert state.held == "thermos" and state.location["thermos"] == HAND
    available = set(world.available(state))
    assert not any(c.task == "pick" for c in available)
    assert TaskCall("place", ("thermos", "kitchen_table")) in available
    assert TaskCall("drink_from", ("thermos",)) in available
    with pytest.raises(NeemOracleError, match="hand_free"):
        world.apply(state, parse_call("pick(bread)"))
    with pytest.raises(NeemOracleError, match="holding"):
        world.apply(world.initial_state(), parse_call("place(bread, kitchen_table)"))


def test_pour_needs_held_pourable_and_reachable_receiver(world):
    state = run(world, "open(small_drawer)", "pick(green_mug)", "place(green_mug, kitchen_table)", "pick(thermos)")
    available = set(world.available(state))
    assert TaskCall("pour", ("thermos", "green_mug")) in available
    assert TaskCall("pour", ("thermos", "thermos")) not in available
    assert TaskCall("pour", ("thermos", "bread")) not in available  # bread is no receiver
    closed = world.apply(world.apply(world.apply(state, parse_call("place(thermos, counter_top)")),
                                     parse_call("close(small_drawer)")), parse_call("pick(thermos)"))
    assert TaskCall("pour", ("thermos", "red_mug")) not in set(world.available(closed))


def test_items_inside_a_held_mug_move_with_it(world):
    state = run(world, "open(small_drawer)", "open(big_drawer)", "pick(red_mug)", "place(red_mug, counter_top)",
                "pick(green_tea_bag)", "place(green_tea_bag, red_mug)", "pick(red_mug)")
    assert state.location["green_tea_bag"] == "red_mug"
    assert TaskCall("pick", ("green_tea_bag",)) not in set(world.available(state))


def test_dish_washer_locks_its_contents_while_running(world):
    state = run(world, "open(small_drawer)", "pick(plate)", "place(plate, dish_washer)", "turn_on(dish_washer)")
    assert TaskCall("pick", ("plate",)) not in set(world.available(state))
    state = world.apply(state, parse_call("turn_off(dish_washer)"))
    assert TaskCall("pick", ("plate",)) in set(world.available(state))


def test_appliances_toggle(world):
    state = run(world, "turn_on(coffee_machine)")
    available = set(world.available(state))
    assert TaskCall("turn_off", ("coffee_machine",)) in available
    assert TaskCall("turn_on", ("coffee_machine",)) not in available


def test_unknown_names_and_arity_are_rejected(world):
    with pytest.raises(WorldError, match="no object 'purple_mug'"):
        world.apply(world.initial_state(), parse_call("pick(purple_mug)"))
    with pytest.raises(WorldError, match="no task 'juggle'"):
        world.apply(world.initial_state(), parse_call("juggle(apple)"))
    with pytest.raises(ChainSyntaxError, match="takes 2"):
        world.apply(world.initial_state(), parse_call("place(apple)"))


def test_not_afforded_task_is_infeasible(world):
    state = run(world, "pick(bread)")
    assert world.failure(state, parse_call("drink_from(bread)")).condition.name == "affords"


def test_repair_opens_the_drawer_before_picking_from_it(world):
    plan = world.repair(world.initial_state(), parse_call("pick(red_mug)"))
    assert [str(c) for c in plan] == ["open(small_drawer)", "pick(red_mug)"]


def test_repair_puts_down_what_is_held_first(world):
    state = run(world, "pick(bread)")
    plan = world.repair(state, parse_call("pick(apple)"), park="kitchen_table")
    assert [str(c) for c in plan] == ["place(bread, kitchen_table)", "pick(apple)"]


def test_repair_gets_the_pourable_and_frees_the_hand_to_open(world):
    state = run(world, "pick(thermos)")
    plan = world.repair(state, parse_call("pour(thermos, blue_mug)"))
    assert [str(c) for c in plan] == ["place(thermos, counter_top)", "open(small_drawer)", "pick(thermos)",
                                      "pour(thermos, blue_mug)"]


def test_repair_gives_up_on_pointless_actions(world):
    state = run(world, "open(fridge)")
    assert world.repair(state, parse_call("open(fridge)")) is None
    assert world.repair(state, parse_call("pour(cereal_box, bread)")) is None


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(min_value=0, max_value=10_000), min_size=1, max_size=60))
def test_random_walks_stay_consistent(world_seq):
    """Any sequence of available actions keeps the state consistent and the chosen action feasible."""
    world = load_world()
    state = world.initial_state()
    for pick in world_seq:
        available = world.available(state)
        assert available, "the world never dead-ends"
        call = available[pick % len(available)]
        assert world.feasible(state, call)
        state = world.apply(state, call)
        holders = [o for o, where in state.location.items() if where == HAND]
        assert holders == ([state.held] if state.held else [])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(min_value=0, max_value=10_000), max_size=30), st.integers(0, 10_000))
def test_repaired_plans_are_feasible(prefix, target):
    """Whatever the state, a repaired plan replays step by step and ends with the asked action."""
    world = load_world()
    state = world.initial_state()
    for pick in prefix:
        available = world.available(state)
        state = world.apply(state, available[pick % len(available)])
    every = [TaskCall(t, (o,)) for t in ("pick", "open", "drink_from", "eat") for o in world.objects]
    every += [TaskCall(t, (a, b)) for t in ("pour", "cut", "stir", "place") for a in world.objects for b in world.objects]
    wanted = every[target % len(every)]
    plan = world.repair(state, wanted)
    if plan is None:
        return
    assert plan[-1] == wanted
    for step in plan:
        state = world.apply(state, step)


BAD = [
    ("objects: [1]\ntasks: {pick: {args: [x]}}\npark: t\n", "'objects' must be a non-empty mapping"),
    ("objects: {t: {kind: shelf}}\ntasks: {pick: {args: [x]}}\npark: t\n", "objects.t.kind"),
    ("objects: {t: {kind: surface}, a: {at: nowhere}}\ntasks: {pick: {args: [x]}}\npark: t\n", "objects.a.at"),
    ("objects: {t: {kind: surface}, a: {at: t, affords: [fly]}}\ntasks: {pick: {args: [x]}}\npark: t\n",
     "objects.a.affords: unknown task 'fly'"),
    ("objects: {t: {kind: surface}}\ntasks: {pick: {args: [x], requires: ['holdin(x)']}}\npark: t\n",
     r"tasks.pick.requires\[0\]: unknown predicate 'holdin'"),
    ("objects: {t: {kind: surface}}\ntasks: {pick: {args: [x], requires: ['holding(y)']}}\npark: t\n",
     r"tasks.pick.requires\[0\]: 'y'"),
    ("objects: {t: {kind: surface}}\ntasks: {pick: {args: [x]}}\npark: nowhere\n", "park"),
    ("objects: {t: {kind: surface}\n", "malformed YAML"),
]


@pytest.mark.parametrize("text, message", BAD)
def test_bad_world_files_name_the_file_and_entry(tmp_path, text, message):
    path = tmp_path / "w.yaml"
    path.write_text(text)
    with pytest.raises(WorldError, match=message) as info:
        load_world(path)
    assert str(path) in str(info.value)


def test_missing_world_file(tmp_path):
    with pytest.raises(WorldError, match="cannot read"):
        load_world(tmp_path / "absent.yaml")


def test_default_world_file_is_in_the_project():
    assert default_world() == Path(__file__).resolve().parents[2] / "ontology" / "kitchen-world.yaml"


@settings(max_examples=25, deadline=None)
@given(st.lists(st.integers(min_value=0, max_value=10_000), max_size=40))
def test_available_equals_brute_force_over_all_calls(walk):
    """The fast enumeration lists exactly the calls whose preconditions hold."""
    world = load_world()
    state = world.initial_state()
    for pick in walk:
        available = world.available(state)
        state = world.apply(state, available[pick % len(available)])
    brute = []
    for task, rule in world.tasks.items():
        for x in world.objects:
            seconds = [()] if len(rule.params) == 1 else [(y,) for y in world.objects]
            for rest in seconds:
                call = TaskCall(task, (x, *rest))
                if world.feasible(state, call):
                    brute.append(call)
    assert list(world.available(state)) == brute
