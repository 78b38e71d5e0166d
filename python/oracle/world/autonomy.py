"""Each persona's autonomy profile (thesis 6.3, "use it or lose it"): which actions the user does by
hand, which they do together with the robot and which they leave to it, so that predicting the
mode can be evaluated.

The chance that the user does an action by hand depends on the task (eating and drinking almost
always, cutting and pouring less), on the persona's condition (a weak grip leaves pouring, cutting
and heavy objects to the robot), on the object (a heavy bottle or the thermos is poured by the
robot more often) and on the hour (in the evening the user is tired). What the user does not do
alone is shared with the robot (``together``: the robot holds, the user pours) at the persona's
own rate where a grip or a heavy object is the obstacle, and at a third of it elsewhere; the rest
is the robot's. The same seed, persona and row always give the same mode.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import dataclass

from oracle.chains import ChainRow
from oracle.world.personas import Persona

#: The chance a user without a condition does a task by hand.
BY_HAND = {"pick": 0.7, "place": 0.7, "open": 0.8, "close": 0.8, "pour": 0.5, "cut": 0.4, "stir": 0.6,
           "turn_on": 0.85, "turn_off": 0.85, "eat": 0.95, "eat_with": 0.95, "drink_from": 0.95}
#: Objects heavy to handle: pouring or carrying them is left to the robot more often.
HEAVY = frozenset({"thermos", "milk_carton", "water_bottle", "juice", "beer_bottle", "cereal_box", "plate"})
#: The tasks a weak grip makes hard.
GRIP_TASKS = frozenset({"pour", "cut", "stir", "open", "close"})
#: The share of the persona's together rate where neither a grip nor a heavy object is the obstacle.
TOGETHER_ELSEWHERE = 1 / 3


@dataclass(frozen=True)
class AutonomyProfile:
    """How much the persona does by hand: a factor per task family, one for heavy objects, one for
    the evening (after 17:00)."""

    hands: float  # overall factor (the persona's strength and will)
    grip: float  # factor on pouring, cutting, stirring and opening
    heavy: float  # factor on actions with a heavy object
    evening: float  # factor after 17:00
    together: float = 0.0  # the share of what the user does not do alone that they share with the robot

    def by_hand(self, task: str, objects: Sequence[str], hour: float) -> float:
        """The chance the user does ``task`` on ``objects`` at ``hour`` by hand."""
        chance = BY_HAND.get(task, 0.7) * self.hands
        if task in GRIP_TASKS:
            chance *= self.grip
        if any(o in HEAVY for o in objects):
            chance *= self.heavy
        if hour >= 17.0:
            chance *= self.evening
        return min(1.0, max(0.0, chance))

    def odds(self, task: str, objects: Sequence[str], hour: float) -> dict[str, float]:
        """The chance of each mode (chains.MODES) for ``task`` on ``objects`` at ``hour``."""
        alone = self.by_hand(task, objects, hour)
        hard = task in GRIP_TASKS or any(o in HEAVY for o in objects)
        shared = (1.0 - alone) * self.together * (1.0 if hard else TOGETHER_ELSEWHERE)
        return {"user": alone, "together": shared, "robot": 1.0 - alone - shared}

    def likeliest(self, task: str, objects: Sequence[str], hour: float) -> str:
        """The mode the profile makes likeliest (a tie to the user, then together)."""
        odds = self.odds(task, objects, hour)
        return max(("user", "together", "robot"), key=lambda mode: (odds[mode], -("user", "together", "robot").index(mode)))


def autonomy_profile(persona: Persona, seed: int) -> AutonomyProfile:
    """The persona's profile, drawn from its text (a weak grip, a wheelchair, an injury) and the seed."""
    rng = random.Random(f"autonomy:{seed}:{persona.file_name}")
    weak = any(word in persona.persona for word in ("weak grip", "injury", "wheelchair"))
    hands, grip = rng.uniform(0.8, 1.15), rng.uniform(0.3, 0.6) if weak else rng.uniform(0.8, 1.1)
    heavy, evening = rng.uniform(0.3, 0.7), rng.uniform(0.5, 0.9)
    together = rng.uniform(0.3, 0.7) if weak else rng.uniform(0.1, 0.4)
    return AutonomyProfile(hands=hands, grip=grip, heavy=heavy, evening=evening, together=together)


def modes_of(persona: Persona, rows: Sequence[ChainRow], seed: int) -> list[str]:
    """Who performed each row's action: ``user`` (by hand), ``together`` or ``robot``, one draw
    per row from the profile's odds."""
    profile = autonomy_profile(persona, seed)
    rng = random.Random(f"modes:{seed}:{persona.file_name}")
    out = []
    for row in rows:
        odds = profile.odds(row.action.task, row.action.args, row_hour(row))
        draw = rng.random()
        out.append("user" if draw < odds["user"] else "together" if draw < odds["user"] + odds["together"] else "robot")
    return out


def row_hour(row: ChainRow) -> float:
    """The row's hour of the day (noon for a row without a time)."""
    return row.time.hour + row.time.minute / 60.0 if row.time is not None else 12.0
