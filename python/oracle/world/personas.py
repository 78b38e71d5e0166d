"""Seeded personas in the shape of thesis appendix B: a persona text, a daily routine, variations.

The thesis had an LLM invent personas; here each one is drawn from explicit distributions over
preferences (favourite mug, tea or coffee, snacks, ...), habits (orderings, tidiness, where to sit)
and a daily routine whose entries name an intention at an hour (docs/world.md describes the model).
The same seed and index always give the same persona.
"""

from __future__ import annotations

import random
from dataclasses import asdict, dataclass, field

MUGS = ("red_mug", "green_mug", "blue_mug")
TEAS = ("chamomile_tea_bag", "peppermint_tea_bag", "green_tea_bag", "black_tea_bag", "chai_tea_bag")
FRUITS = ("banana", "apple", "orange", "lemon")
COLD_DRINKS = ("water_bottle", "juice", "milk_carton", "beer_bottle", "tap_water")
BREAKFASTS = ("cereal", "yogurt", "bread", "fruit")
MEALS = ("salad", "bread", "microwave", "stove")

#: Intention keys the generator knows (generate.py), with the texts of their routine entries.
DESCRIPTIONS: dict[str, tuple[str, ...]] = {
    "breakfast": ("You want to prepare breakfast.", "You want to prepare something to eat for breakfast."),
    "hot_drink": ("You are having a little break from work.", "You want a hot drink.", "You want to relax with a warm cup."),
    "cold_drink": ("You want to drink something.", "You are thirsty."),
    "snack": ("You want to snack.", "You feel like eating a piece of fruit."),
    "lunch": ("You want to eat lunch.", "You prepare a light lunch."),
    "dinner": ("You want to eat dinner.", "You want to prepare dinner."),
    "evening": ("You want to relax in the evening.", "You get home and want to relax."),
    "cleanup": ("You tidy up the kitchen.", "You load the dish washer."),
    "bedtime": ("You are preparing a snack for bedtime.", "You want something small before bed."),
    # variations only
    "other_hot_drink": ("You find yourself drinking coffee.", "You try a different drink today."),
    "doctor": ("You are getting home from the doctor.", "You are coming home from an appointment."),
    "late_food": ("You are getting home late, looking for something to eat.",),
    "guest": ("A friend visits and you make two drinks.",),
    "quick_breakfast": ("You are late and grab something quick for breakfast.",),
}

_OCCUPATIONS = (
    "programmer", "nurse", "student", "retired teacher", "carpenter", "artist", "accountant", "librarian",
    "night-shift worker", "gardener", "musician", "engineer", "pensioner", "writer", "baker", "physiotherapist",
)
_AGES = ("in your twenties", "in your thirties", "in your forties", "in your fifties", "in your sixties",
         "in your seventies", "in your eighties", "of 90 years")
_CONDITIONS = ("", "", "", " recovering from an injury", " with a weak grip", " using a wheelchair",
               " with a heart condition", " trying to eat healthier")


@dataclass(frozen=True)
class RoutineEntry:
    """One appendix-B entry: what the persona wants, at which hour, and the intention it stands for."""

    description: str
    time: float
    intention: str

    def to_yaml(self) -> dict[str, object]:
        hour, minute = int(self.time), round((self.time % 1) * 60)
        return {"description": self.description, "time": f"{hour:02d}:{minute:02d}", "intention": self.intention}


@dataclass(frozen=True)
class Preferences:
    """What the persona likes and how it habitually does things."""

    hot_drink: str  # tea | coffee | none
    tea: str
    coffee: str  # machine | instant | espresso
    mug: str  # favourite mug, mornings and midday
    evening_mug: str
    cold_drink: str
    from_bottle: bool  # drinks straight from the bottle instead of pouring into the glass
    breakfast: str
    snacks: tuple[str, ...]  # fruits, most liked first
    meal: str  # lunch and dinner style
    milk: bool
    breakfast_drink: bool  # a drink with breakfast, not only food
    stir: bool
    table: str  # where things are set down: kitchen_table or counter_top
    tidy: float  # chance of putting things back and closing drawers after an intention
    sips: int
    orders: dict[str, bool] = field(default_factory=dict)  # habitual order of interchangeable steps
    order_noise: float = 0.2  # chance on a given day to do the interchangeable steps in random order
    noise: float = 0.03  # chance of a stray action before a step
    variation_rate: float = 0.15  # chance a routine entry is replaced by a variation on a day


@dataclass(frozen=True)
class Persona:
    file_name: str
    persona: str
    daily_routine: tuple[RoutineEntry, ...]
    variations: tuple[RoutineEntry, ...]
    preferences: Preferences
    split: str = "test"

    def to_yaml(self) -> dict[str, object]:
        prefs = asdict(self.preferences)
        prefs["snacks"] = list(self.preferences.snacks)
        return {
            "file_name": self.file_name,
            "persona": self.persona,
            "daily_routine": [e.to_yaml() for e in self.daily_routine],
            "variations": [e.to_yaml() for e in self.variations],
            "preferences": prefs,
            "split": self.split,
        }


def _entry(rng: random.Random, intention: str, low: float, high: float) -> RoutineEntry:
    hour = round(rng.uniform(low, high) * 4) / 4  # quarter hours, like a person states them
    return RoutineEntry(rng.choice(DESCRIPTIONS[intention]), hour, intention)


def make_persona(seed: int, index: int, split: str = "test") -> Persona:
    """Draw persona ``index`` of the benchmark made with ``seed``; pure function of both."""
    rng = random.Random(f"persona:{seed}:{index}")
    hot = rng.choices(("tea", "coffee", "none"), weights=(0.42, 0.45, 0.13))[0]
    mug = rng.choice(MUGS)
    prefs = Preferences(
        hot_drink=hot,
        tea=rng.choice(TEAS),
        coffee=rng.choices(("machine", "instant", "espresso"), weights=(0.5, 0.3, 0.2))[0],
        mug=mug,
        evening_mug=mug if rng.random() < 0.6 else rng.choice([m for m in MUGS if m != mug]),
        cold_drink=rng.choices(COLD_DRINKS, weights=(0.3, 0.2, 0.15, 0.15, 0.2))[0],
        from_bottle=rng.random() < 0.35,
        breakfast=rng.choice(BREAKFASTS),
        snacks=tuple(rng.sample(FRUITS, 3)),
        meal=rng.choice(MEALS),
        milk=rng.random() < 0.25,
        stir=rng.random() < 0.3,
        breakfast_drink=rng.random() < 0.5,
        table=rng.choices(("kitchen_table", "counter_top"), weights=(0.65, 0.35))[0],
        tidy=rng.choice((0.15, 0.5, 0.85)),
        sips=rng.choice((1, 2, 2, 3)),
        orders={key: rng.random() < 0.5 for key in ("tea", "breakfast", "meal", "coffee", "cleanup")},
        order_noise=rng.choice((0.1, 0.2, 0.3)),
        noise=rng.choice((0.01, 0.03, 0.05)),
        variation_rate=rng.choice((0.1, 0.15, 0.25)),
    )
    routine = [_entry(rng, "breakfast", 6.0, 10.0)]
    later = [("hot_drink" if hot != "none" else "cold_drink", 10.0, 11.5), (rng.choice(("lunch", "snack")), 12.0, 13.5),
             (rng.choice(("hot_drink", "cold_drink", "snack")) if hot != "none" else "cold_drink", 14.5, 16.5),
             ("dinner", 18.0, 20.0), (rng.choice(("evening", "bedtime")), 21.0, 22.5)]
    count = rng.choices((1, 2, 3), weights=(0.25, 0.55, 0.2))[0]
    for intention, low, high in sorted(rng.sample(later, count), key=lambda item: item[1]):
        routine.append(_entry(rng, intention, low, high))
    variation_pool = ["other_hot_drink", "doctor", "late_food", "guest", "quick_breakfast", "snack", "cold_drink", "cleanup"]
    if hot == "none":
        variation_pool.remove("other_hot_drink")
    variations = []
    for intention in rng.sample(variation_pool, rng.choice((1, 2, 2, 3))):
        low, high = {"quick_breakfast": (7.0, 9.0), "late_food": (22.0, 23.5), "doctor": (15.0, 17.0)}.get(intention, (13.0, 18.0))
        variations.append(_entry(rng, intention, low, high))
    colour = mug.split("_")[0]
    occupation = rng.choice(_OCCUPATIONS)
    drink_text = {
        "tea": f"love {prefs.tea.replace('_tea_bag', '').replace('_', ' ')} tea",
        "coffee": "live on coffee",
        "none": "stay away from hot drinks",
    }[hot]
    text = (
        f"You are {_article(occupation)} {occupation} {rng.choice(_AGES)}{rng.choice(_CONDITIONS)}; you {drink_text}, "
        f"always prefer your {colour} mug and like {prefs.snacks[0]}s as a snack."
    )
    slug = f"{hot}-{colour}-{prefs.breakfast}"  # hyphens: the user id is also the NEEM id
    return Persona(
        file_name=f"p{index:03d}-{slug}",
        persona=text,
        daily_routine=tuple(sorted(routine, key=lambda e: e.time)),
        variations=tuple(variations),
        preferences=prefs,
        split=split,
    )


def _article(word: str) -> str:
    return "an" if word[0] in "aeiou" else "a"


def tune_count(n: int) -> int:
    """How many of ``n`` personas go to the tuning split: 17 of 105 as in the thesis (5.3)."""
    return max(1, round(n * 17 / 105)) if n > 1 else 0


def make_personas(n: int, seed: int) -> list[Persona]:
    """``n`` personas; the first ``tune_count(n)`` form the tuning split, the rest the test split."""
    k = tune_count(n)
    return [make_persona(seed, i, "tune" if i < k else "test") for i in range(n)]
