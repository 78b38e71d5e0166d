"""Small readable worlds for the algorithm tests: a distance matrix and generators of histories."""

from __future__ import annotations


import numpy as np
from hypothesis import strategies as st

from oracle.algorithm.situation import Option, Step
from oracle.ontology.distance import DistanceMatrix
from oracle.timeline import TIME_OF_DAY_NAMES

ODB = "https://ontology.dlr.de/soma/odb#"
TASKS = tuple(f"{ODB}{name}" for name in ("Pick", "Place", "Pour", "Open", "Close", "Drink"))
OBJECTS = tuple(f"{ODB}{name}" for name in ("RedMug", "BlueMug", "Thermos", "Drawer", "Table", "Spoon", "Plate"))
IDLE = f"{ODB}IdleTask"
OPEN = f"{ODB}Open"


def random_matrix(seed: int, classes=TASKS + OBJECTS + (IDLE,), scale: float = 1.5) -> DistanceMatrix:
    rng = np.random.default_rng(seed)
    n = len(classes)
    upper = np.triu(rng.uniform(0.05, scale, size=(n, n)), 1)
    # a few exact ties and zeros between distinct classes make knockout edges likely
    upper = np.where(rng.random((n, n)) < 0.1, np.round(upper, 1), upper)
    values = upper + upper.T
    np.fill_diagonal(values, 0.0)
    return DistanceMatrix.from_values(tuple(classes), values)


def option_strategy():
    obj = st.one_of(st.none(), st.sampled_from(OBJECTS[:5]))
    return st.builds(Option, st.sampled_from(TASKS[:5]), obj, obj)


def options_strategy(max_size: int = 5):
    return st.lists(option_strategy(), max_size=max_size).map(tuple)


@st.composite
def step_strategy(draw):
    idle = draw(st.integers(0, 7)) == 0
    options = draw(options_strategy())
    if idle:
        return Step(IDLE, None, None, options, draw(st.sampled_from((None,) + TIME_OF_DAY_NAMES)), True, "idle")
    if options and draw(st.booleans()):
        chosen = draw(st.sampled_from(options))
    else:
        obj = st.one_of(st.none(), st.sampled_from(OBJECTS[:5]))
        chosen = Option(draw(st.sampled_from(TASKS[:5])), draw(obj), draw(obj))
    tod = draw(st.sampled_from((None,) + TIME_OF_DAY_NAMES))
    return Step(chosen.task, chosen.target, chosen.reference, options, tod, False, str(chosen))


def histories(max_size: int = 30):
    return st.lists(step_strategy(), max_size=max_size)


def synthetic_history(n: int, seed: int, n_options: int = 20, n_states: int = 40,
                      classes: tuple[str, ...] = TASKS + OBJECTS + (IDLE,)) -> list[Step]:
    """A routine-like history: a Markov chain over world states, each with its own option set."""
    rng = np.random.default_rng(seed)
    tasks = [c for c in classes if c in TASKS]
    objects = [c for c in classes if c in OBJECTS]
    pool = [Option(t, o1, o2) for t in tasks for o1 in (None, *objects) for o2 in (None, *objects)]
    states = [tuple(pool[i] for i in rng.choice(len(pool), size=n_options, replace=False)) for _ in range(n_states)]
    favourite = rng.integers(0, n_options, size=n_states)
    steps: list[Step] = []
    state = 0
    for i in range(n):
        options = states[state]
        if rng.random() < 0.06:
            steps.append(Step(IDLE, None, None, options, TIME_OF_DAY_NAMES[(i // 50) % 4], True, "idle"))
        else:
            k = favourite[state] if rng.random() < 0.7 else rng.integers(0, n_options)
            chosen = options[k]
            steps.append(Step(chosen.task, chosen.target, chosen.reference, options,
                              TIME_OF_DAY_NAMES[(i // 50) % 4], False, str(chosen)))
        state = (state * 7 + int(k if not steps[-1].idle else 3) + 1) % n_states
    return steps
