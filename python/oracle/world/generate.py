"""Simulate personas for a week in the kitchen world and write their task chains (thesis 5.2).

Each routine entry names an intention; the intention becomes a short script of desired actions
shaped by the persona's preferences and habits, and the world's repair step turns every desired
action into a feasible sequence (opening drawers, putting down what is held). Every executed
action is written with its time and the available set of its moment.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from datetime import datetime, timedelta
from pathlib import Path

import yaml

from oracle.chains import ChainRow, TaskCall, parse_call, write_chains
from oracle.files import private_file
from oracle.errors import NeemOracleError
from oracle.timeline import first_hour
from oracle.world.personas import MUGS, Persona, Preferences, RoutineEntry, make_personas
from oracle.world.rules import World
from oracle.world.worldfile import load_world
from oracle.world.state import State

#: Day 1 of every simulated week (a Monday); times are wall-clock times without a zone
#: (read as UTC, oracle.timeline).
FIRST_DAY = datetime(2025, 3, 3)
#: An action takes 3-45 s; the next starts 1-10 s after it ended, so within a routine the robot
#: never idles (an idle period is 20 s or more, thesis 3.4) and between routines it always does.
ACTION_SECONDS = (3.0, 45.0)
TRANSITION_SECONDS = (1.0, 10.0)

#: A script step: an action text, or a directive evaluated against the state when it is reached.
ScriptStep = str | tuple[str, ...]


@dataclass
class _Day:
    persona: Persona
    rng: random.Random
    hour: float

    @property
    def prefs(self) -> Preferences:
        return self.persona.preferences

    def ordered(self, key: str, first: list[ScriptStep], second: list[ScriptStep]) -> list[ScriptStep]:
        """Two interchangeable blocks in the persona's habitual order, shuffled on some days."""
        swap = self.prefs.orders.get(key, False)
        if self.rng.random() < self.prefs.order_noise:
            swap = self.rng.random() < 0.5
        return second + first if swap else first + second

    def back(self, obj: str) -> ScriptStep:
        """Where a used object goes: home (drawer, fridge) for tidy persons, else the table."""
        return ("putback", obj)

    def sips(self) -> int:
        return max(1, self.prefs.sips + self.rng.choice((-1, 0, 0, 0, 1)))


def _fetch(obj: str, destination: str) -> ScriptStep:
    return ("fetch", obj, destination)


def _use(obj: str, target: str, day: _Day) -> list[ScriptStep]:
    steps: list[ScriptStep] = [f"pick({obj})", f"pour({obj}, {target})", day.back(obj)]
    return steps


def _drink(vessel: str, day: _Day) -> list[ScriptStep]:
    steps: list[ScriptStep] = [f"pick({vessel})", *[f"drink_from({vessel})"] * day.sips(), f"place({vessel}, {day.prefs.table})"]
    return steps


# --- intentions -----------------------------------------------------------------------------------
def hot_drink(day: _Day, state: State, kind: str | None = None, mug: str | None = None, drink: bool = True) -> list[ScriptStep]:
    p, t = day.prefs, day.prefs.table
    kind = kind or (p.hot_drink if p.hot_drink != "none" else "tea")
    mug = mug or (p.evening_mug if day.hour >= first_hour("Evening") else p.mug)
    if kind == "coffee" and p.coffee == "espresso" and mug in (p.mug, p.evening_mug):
        mug = "espresso_cup"
    steps: list[ScriptStep] = [_fetch(mug, t)]
    if kind == "tea":
        bag: list[ScriptStep] = [f"pick({p.tea})", f"place({p.tea}, {mug})"]
        steps += day.ordered("tea", bag, _use("thermos", mug, day))
    elif p.coffee == "instant":
        steps += day.ordered("coffee", _use("instant_coffee", mug, day), _use("thermos", mug, day))
    else:
        steps += ["turn_on(coffee_machine)", "turn_off(coffee_machine)"]
    if p.milk and mug != "espresso_cup":
        steps += _use("milk_carton", mug, day)
    if p.stir and mug != "espresso_cup":
        steps += ["pick(spoon)", f"stir(spoon, {mug})", f"place(spoon, {t})"]
    if drink:
        steps += _drink(mug, day)
    return steps


def cold_drink(day: _Day, state: State, drink: str | None = None) -> list[ScriptStep]:
    p, t = day.prefs, day.prefs.table
    drink = drink or p.cold_drink
    if drink == "tap_water":
        return [_fetch("drinking_glass", "counter_top"), "turn_on(tap)", "turn_off(tap)"] + _drink("drinking_glass", day)
    if p.from_bottle:
        return [f"pick({drink})"] + [f"drink_from({drink})"] * day.sips() + [day.back(drink)]
    return [_fetch("drinking_glass", t)] + _use(drink, "drinking_glass", day) + _drink("drinking_glass", day)


def _fruit(day: _Day) -> str:
    return day.rng.choices(day.prefs.snacks, weights=(0.65, 0.25, 0.1))[0]


def snack(day: _Day, state: State) -> list[ScriptStep]:
    fruit = _fruit(day)
    bites = [f"eat({fruit})"] * day.sips()
    return [f"pick({fruit})"] + bites + [day.back(fruit)]


def breakfast(day: _Day, state: State) -> list[ScriptStep]:
    p, t = day.prefs, day.prefs.table
    kind = p.breakfast
    if kind == "cereal":
        food = [_fetch("cereal_bowl", t)] + _use("cereal_box", "cereal_bowl", day) + _use("milk_carton", "cereal_bowl", day)
        food += _drink("cereal_bowl", day)
    elif kind == "yogurt":
        fruit = _fruit(day)
        food = [_fetch("cereal_bowl", t)] + _use("yogurt", "cereal_bowl", day)
        food += [_fetch(fruit, t), "pick(knife)", f"cut(knife, {fruit})", f"place(knife, {t})"] + _drink("cereal_bowl", day)
    elif kind == "bread":
        food = [_fetch("plate", t), _fetch("bread", "plate"), "pick(knife)", "cut(knife, bread)", f"place(knife, {t})"]
        food += ["pick(bread)"] + ["eat(bread)"] * day.sips() + ["place(bread, counter_top)"]
    else:
        food = snack(day, state)
    if not p.breakfast_drink:
        return food
    drink = hot_drink(day, state) if p.hot_drink != "none" else cold_drink(day, state)
    return day.ordered("breakfast", food, drink)


def meal(day: _Day, state: State) -> list[ScriptStep]:
    p, t = day.prefs, day.prefs.table
    if p.meal == "salad":
        steps = [_fetch("plate", t)] + day.ordered("meal", [_fetch("cucumber", "plate")], [_fetch("avocado", "plate")])
        steps += ["pick(knife)", "cut(knife, cucumber)", "cut(knife, avocado)", f"place(knife, {t})"]
        steps += ["pick(fork)", "eat_with(fork, cucumber)", "eat_with(fork, avocado)", f"place(fork, {t})"]
    elif p.meal == "bread":
        steps = [_fetch("plate", t), _fetch("bread", "plate"), "pick(knife)", "cut(knife, bread)"]
        steps += day.ordered("meal", ["cut(knife, bread)"], [])
        steps += [f"place(knife, {t})", _fetch("cucumber", "plate"), "pick(bread)", "eat(bread)", "place(bread, plate)"]
        steps += ["pick(cucumber)", "eat(cucumber)", day.back("cucumber")]
    elif p.meal == "microwave":
        steps = [_fetch("plate", "counter_top"), _fetch("avocado", "plate"), "turn_on(microwave)", "turn_off(microwave)"]
        steps += ["pick(plate)", f"place(plate, {t})", "pick(fork)", "eat_with(fork, avocado)", f"place(fork, {t})"]
    else:
        steps = day.ordered("meal", ["turn_on(stove)"], [_fetch("plate", t), _fetch("cucumber", "plate")])
        steps += ["pick(knife)", "cut(knife, cucumber)", f"place(knife, {t})", "turn_off(stove)"]
        steps += ["pick(fork)", "eat_with(fork, cucumber)", f"place(fork, {t})"]
    return steps


def dinner(day: _Day, state: State) -> list[ScriptStep]:
    steps = meal(day, state)
    if day.rng.random() < 0.3:
        steps += cold_drink(day, state)
    return steps


def evening(day: _Day, state: State) -> list[ScriptStep]:
    p = day.prefs
    if p.hot_drink != "none" and p.cold_drink != "beer_bottle":
        steps = hot_drink(day, state)
    else:
        steps = cold_drink(day, state)
    if day.rng.random() < 0.4:
        steps += snack(day, state)
    return steps


def cleanup(day: _Day, state: State) -> list[ScriptStep]:
    dishes = [name for name in ("plate", "cereal_bowl", "knife", "fork", "spoon", "drinking_glass", "espresso_cup", *MUGS)
              if state.location.get(name) in ("kitchen_table", "counter_top")]
    if day.prefs.orders.get("cleanup"):
        dishes.reverse()
    steps: list[ScriptStep] = [_fetch(name, "dish_washer") for name in dishes]
    return steps + ["turn_on(dish_washer)"] if dishes else steps


def other_hot_drink(day: _Day, state: State) -> list[ScriptStep]:
    usual = day.prefs.hot_drink
    return hot_drink(day, state, kind="coffee" if usual == "tea" else "tea")


def doctor(day: _Day, state: State) -> list[ScriptStep]:
    return cold_drink(day, state, drink=day.rng.choice(("tap_water", "water_bottle")))


def late_food(day: _Day, state: State) -> list[ScriptStep]:
    return ["pick(bread)", "eat(bread)", "place(bread, counter_top)"] + snack(day, state)


def guest(day: _Day, state: State) -> list[ScriptStep]:
    p = day.prefs
    other = next(m for m in MUGS if m not in (p.mug, p.evening_mug))
    return hot_drink(day, state, mug=other, drink=False) + hot_drink(day, state)


def quick_breakfast(day: _Day, state: State) -> list[ScriptStep]:
    return snack(day, state) + cold_drink(day, state)


INTENTIONS: dict[str, Callable[[_Day, State], list[ScriptStep]]] = {
    "breakfast": breakfast,
    "hot_drink": hot_drink,
    "cold_drink": cold_drink,
    "snack": snack,
    "lunch": meal,
    "dinner": dinner,
    "evening": evening,
    "cleanup": cleanup,
    "bedtime": snack,
    "other_hot_drink": other_hot_drink,
    "doctor": doctor,
    "late_food": late_food,
    "guest": guest,
    "quick_breakfast": quick_breakfast,
}


# --- simulation ------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Summary:
    """Figures of one generated benchmark."""

    personas: int
    days: int
    actions: int
    tune_actions: int
    test_actions: int
    mean_actions_per_persona: float
    mean_available: float
    skipped_steps: int


class _Simulator:
    def __init__(self, world: World, persona: Persona, seed: int):
        self.world = world
        self.persona = persona
        self.rng = random.Random(f"days:{seed}:{persona.file_name}")
        self.homes = {name: spec.at for name, spec in world.objects.items() if spec.at is not None}
        self.skipped = 0
        #: The routine entry behind each row yielded, in order (what routine mining is scored on).
        self.entries: list[RoutineEntry] = []

    def week(self, days: int) -> Iterator[ChainRow]:
        clock = FIRST_DAY
        for number in range(days):
            date = FIRST_DAY + timedelta(days=number)
            state = self.world.initial_state()  # the kitchen is tidied overnight
            for entry in self._agenda():
                start = date + timedelta(hours=entry.time, minutes=self.rng.uniform(-12, 12))
                clock = max(clock + timedelta(minutes=1), start)
                day = _Day(self.persona, self.rng, entry.time)
                steps = INTENTIONS[entry.intention](day, state) + self._closing(day)
                # _execute hands back the state and clock after each row: the next intention starts there
                for row, state, clock in self._execute(day, steps, state, clock):  # noqa: B007, B020
                    self.entries.append(entry)
                    yield row

    def _agenda(self) -> list[RoutineEntry]:
        prefs, rng = self.persona.preferences, self.rng
        entries: list[RoutineEntry] = []
        for entry in self.persona.daily_routine:
            roll = rng.random()
            if roll < prefs.variation_rate and self.persona.variations:
                entries.append(rng.choice(self.persona.variations))
            elif roll < prefs.variation_rate + 0.04:
                continue
            else:
                entries.append(entry)
        if self.persona.variations and rng.random() < 0.1:
            entries.append(rng.choice(self.persona.variations))
        return sorted(entries, key=lambda e: e.time)

    def _closing(self, day: _Day) -> list[ScriptStep]:
        return [("close_if_tidy", name) for name in ("fridge", "small_drawer", "big_drawer")]

    def _expand(self, day: _Day, step: ScriptStep, state: State) -> list[TaskCall]:
        if isinstance(step, str):
            return [parse_call(step)]
        kind, obj = step[0], step[1]
        if kind == "fetch":
            if state.location.get(obj) == step[2]:
                return []
            return [TaskCall("pick", (obj,)), TaskCall("place", (obj, step[2]))]
        if kind == "putback":
            home = self.homes[obj]
            if day.rng.random() >= day.prefs.tidy or home == "counter_top":
                home = "counter_top" if home == "counter_top" else day.prefs.table
            return [TaskCall("place", (obj, home))] if state.held == obj else []
        if kind == "close_if_tidy":
            if obj in state.opened and day.rng.random() < day.prefs.tidy:
                return [TaskCall("close", (obj,))]
            return []
        raise AssertionError(f"unknown script directive {kind}")

    def _execute(self, day: _Day, steps: list[ScriptStep], state: State,
                 clock: datetime) -> Iterator[tuple[ChainRow, State, datetime]]:
        user = self.persona.file_name
        world, prefs = self.world, day.prefs
        for step in steps:
            for wanted in self._expand(day, step, state):
                if day.rng.random() < prefs.noise:
                    stray = day.rng.choice(world.available(state))
                    end = clock + timedelta(seconds=day.rng.uniform(*ACTION_SECONDS))
                    row = ChainRow(user, stray, clock, world.available(state), end=end)
                    state = world.apply(state, stray)
                    yield row, state, clock
                    clock = end + timedelta(seconds=day.rng.uniform(*TRANSITION_SECONDS))
                plan = world.repair(state, wanted, park=prefs.table)
                if plan is None:
                    self.skipped += 1
                    continue
                for call in plan:
                    end = clock + timedelta(seconds=day.rng.uniform(*ACTION_SECONDS))
                    row = ChainRow(user, call, clock, world.available(state), end=end)
                    state = world.apply(state, call)
                    yield row, state, clock
                    clock = end + timedelta(seconds=day.rng.uniform(*TRANSITION_SECONDS))


def simulate(persona: Persona, world: World, days: int, seed: int) -> tuple[list[ChainRow], int]:
    """The rows of one persona's simulated days and how many desired steps had to be skipped."""
    simulator = _Simulator(world, persona, seed)
    rows = list(simulator.week(days))
    return rows, simulator.skipped


def simulate_entries(persona: Persona, world: World, days: int, seed: int) -> tuple[list[ChainRow], list[RoutineEntry]]:
    """The rows of ``simulate`` with the routine entry (daily or variation) each row served."""
    simulator = _Simulator(world, persona, seed)
    rows = list(simulator.week(days))
    return rows, simulator.entries


def generate(out: Path | str, personas: int = 105, days: int = 7, seed: int = 0, world: World | None = None,
             progress: Callable[[int, int], None] | None = None, modes: bool = False) -> Summary:
    """Write ``personas.yaml``, ``tune.jsonl`` and ``test.jsonl`` into ``out``; return the figures.
    With ``modes`` each row says who performed it (``performed_by``: the user or the robot, drawn
    from the persona's autonomy profile, oracle.world.autonomy); the rows are otherwise the same."""
    if personas < 1 or days < 1:
        raise NeemOracleError(f"need at least one persona and one day, got --personas {personas} --days {days}")
    world = load_world() if world is None else world
    from oracle.files import private_folder

    out = Path(out)
    try:
        private_folder(out)
    except OSError as error:
        raise NeemOracleError(f"{out}: cannot create output folder ({error.strerror})") from None
    people = make_personas(personas, seed)
    splits: dict[str, list[ChainRow]] = {"tune": [], "test": []}
    per_persona: list[int] = []
    available_total = 0
    skipped = 0
    for number, persona in enumerate(people, start=1):
        rows, missed = simulate(persona, world, days, seed)
        if modes:
            from dataclasses import replace

            from oracle.world.autonomy import modes_of

            rows = [replace(row, extra={**row.extra, "performed_by": mode})
                    for row, mode in zip(rows, modes_of(persona, rows, seed))]
        splits[persona.split].extend(rows)
        per_persona.append(len(rows))
        available_total += sum(len(row.available or ()) for row in rows)
        skipped += missed
        if progress is not None:
            progress(number, len(people))
    header = {
        "generator": "neem-oracle persona benchmark (docs/world.md)",
        "seed": seed,
        "days": days,
        "world": world.source.name,
        "personas": [p.to_yaml() for p in people],
    }
    try:
        with private_file(out / "personas.yaml") as handle:
            handle.write(yaml.safe_dump(header, sort_keys=False, allow_unicode=True, width=100))
        for name, rows in splits.items():
            write_chains(rows, out / f"{name}.jsonl")
    except OSError as error:
        raise NeemOracleError(f"{out}: cannot write benchmark ({error.strerror})") from None
    total = sum(per_persona)
    return Summary(
        personas=len(people),
        days=days,
        actions=total,
        tune_actions=len(splits["tune"]),
        test_actions=len(splits["test"]),
        mean_actions_per_persona=total / len(people),
        mean_available=available_total / total if total else 0.0,
        skipped_steps=skipped,
    )
