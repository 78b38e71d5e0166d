"""Routine mining and recognition scored against the persona generator's own routines
(docs/beyond.md): a mined routine is right when most of its episodes served one entry of the
persona's daily routine (each entry claimed once); a routine in progress is recognised when,
after the first steps of an episode of a later day, ``recognise`` names the routine mined for
that episode's entry."""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from datetime import timedelta

from oracle.past.routines import Done, MiningSettings, Routine, episodes_of, mine_routines, recognise
from oracle.timeline import seconds_of
from oracle.world.generate import FIRST_DAY, simulate_entries
from oracle.world.personas import Persona, RoutineEntry, make_personas
from oracle.world.worldfile import load_world


@dataclass(frozen=True)
class PersonaScore:
    persona: str
    mined: int
    truth: int
    matched: int
    runs: dict[int, int]  # steps seen -> episodes of later days recognised correctly
    tried: int  # episodes of later days whose entry has a mined routine
    false_alarms: int  # episodes of later days serving no routine entry, recognised as one
    others: int  # such episodes


@dataclass(frozen=True)
class RoutineScores:
    personas: int
    precision: float
    recall: float
    recognised: dict[int, float]
    runs: int
    false_alarm_rate: float
    others: int


def _labelled(persona: Persona, days: int, seed: int) -> tuple[list[Done], dict[float, RoutineEntry]]:
    rows, entries = simulate_entries(persona, load_world(), days, seed)
    done = [Done(seconds_of(r.time), seconds_of(r.end), str(r.action)) for r in rows if r.time and r.end]
    entry_at = {seconds_of(r.time): e for r, e in zip(rows, entries) if r.time}
    return done, entry_at


def _majority(routine: Routine, entry_at: dict[float, RoutineEntry]) -> tuple[RoutineEntry | None, int]:
    counts = Counter(entry_at.get(b) for b in routine.begins)
    (entry, n), = counts.most_common(1)
    return entry, n


def _match(routines: list[Routine], entry_at: dict[float, RoutineEntry], truth: set[RoutineEntry]) -> dict[str, RoutineEntry]:
    """Routine key -> the daily entry it recovered, one-to-one, the best-supported claim first."""
    claims = sorted(((n, r.key, e) for r in routines for e, n in [_majority(r, entry_at)] if e in truth), reverse=True)
    taken: dict[str, RoutineEntry] = {}
    for _, key, entry in claims:
        if entry not in taken.values() and key not in taken:
            taken[key] = entry
    return taken


def score_persona(persona: Persona, days: int, seed: int, train_days: int, settings: MiningSettings,
                  steps: tuple[int, ...] = (1, 2, 3)) -> PersonaScore:
    done, entry_at = _labelled(persona, days, seed)
    truth = set(persona.daily_routine)
    every = mine_routines(done, settings)
    matched = _match(every, entry_at, truth)
    cut = seconds_of(FIRST_DAY + timedelta(days=train_days))
    trained = mine_routines([d for d in done if d.begin < cut], settings)
    routine_of = {entry: key for key, entry in _match(trained, entry_at, truth).items()}
    runs = dict.fromkeys(steps, 0)
    tried = alarms = others = 0
    for episode in episodes_of([d for d in done if d.begin >= cut]):
        entry = entry_at.get(episode.begin)
        key = routine_of.get(entry) if entry is not None else None
        if key is None:
            if entry not in truth:
                others += 1
                alarms += recognise(trained, episode.calls[:2], episode.hour) is not None
            continue
        tried += 1
        for n in steps:
            found = recognise(trained, episode.calls[:n], episode.hour)
            runs[n] += found is not None and found.routine.key == key
    return PersonaScore(persona.file_name, len(every), len(truth), len(matched), runs, tried, alarms, others)


def score_routines(personas: int = 105, days: int = 7, seed: int = 0, train_days: int = 5, split: str = "test",
                   settings: MiningSettings | None = None,
                   progress: Callable[[PersonaScore], None] | None = None) -> RoutineScores:
    """Precision and recall of the mined routines over the split's personas (pooled), and the
    share of later-day episodes recognised after 1, 2 and 3 steps."""
    settings = settings or MiningSettings()
    scores = []
    for persona in make_personas(personas, seed):
        if persona.split != split:
            continue
        score = score_persona(persona, days, seed, train_days, settings)
        scores.append(score)
        if progress is not None:
            progress(score)
    mined = sum(s.mined for s in scores)
    truth = sum(s.truth for s in scores)
    matched = sum(s.matched for s in scores)
    runs = sum(s.tried for s in scores)
    others = sum(s.others for s in scores)
    recognised = {n: sum(s.runs[n] for s in scores) / runs if runs else 0.0 for n in (1, 2, 3)}
    return RoutineScores(len(scores), matched / mined if mined else 0.0, matched / truth if truth else 0.0,
                         recognised, runs, sum(s.false_alarms for s in scores) / others if others else 0.0, others)


@dataclass(frozen=True)
class PrepareScores:
    """Of the objects suggested the evening before, the share used the next morning (and the
    same for the most-used-objects baseline), over the nights scored."""

    personas: int
    nights: int
    routines: float
    baseline: float
    suggested: int
    baseline_suggested: int


def score_preparation(personas: int = 105, days: int = 7, seed: int = 0, first_night: int = 3, split: str = "test",
                      settings: MiningSettings | None = None) -> PrepareScores:
    """For each persona and each night from ``first_night`` on: the routines mined from the days
    before, the objects to prepare for the next Morning, and whether each is used then."""
    from oracle.past.prepare import most_used, to_prepare, used_in

    settings = settings or MiningSettings()
    hits = base_hits = shown = base_shown = nights = count = 0
    for persona in make_personas(personas, seed):
        if persona.split != split:
            continue
        count += 1
        done, _ = _labelled(persona, days, seed)
        for night in range(first_night, days):
            cut = seconds_of(FIRST_DAY + timedelta(days=night))
            before = [d for d in done if d.begin < cut]
            morning = (FIRST_DAY + timedelta(days=night)).date().isoformat()
            used = used_in(done, morning, "Morning")
            ours = [p.obj for p in to_prepare(mine_routines(before, settings), before, "Morning")]
            base = most_used(before)
            nights += 1
            hits += sum(o in used for o in ours)
            shown += len(ours)
            base_hits += sum(o in used for o in base)
            base_shown += len(base)
    return PrepareScores(count, nights, hits / shown if shown else 0.0, base_hits / base_shown if base_shown else 0.0,
                         shown, base_shown)


@dataclass(frozen=True)
class AutonomyScores:
    """Share of actions whose mode was predicted right, replayed progressively (each from the
    earlier actions only, as ``rank`` and the service serve it): the learned predictor (the one
    served, oracle.past.modelogit), the weighted contexts it is fitted to (oracle.past.autonomy)
    and the per-task majority baseline."""

    personas: int
    actions: int
    learned: float
    context: float
    task_majority: float
    robot_share: float
    ceiling: float  # the generator's own likeliest mode, which no predictor beats on average
    learned_only: int  # actions the learned predictor got right and the baseline wrong
    baseline_only: int  # and the other way round (the discordant pairs of a McNemar test)
    together_share: float
    together_recall: float  # of the actions done together, the share the learned predictor said


def score_autonomy(personas: int = 105, days: int = 7, seed: int = 0, split: str = "test") -> AutonomyScores:
    from oracle.past.autonomy import ModeCounts, Performed, majority
    from oracle.past.modelogit import ranked_modes
    from oracle.timeline import part_of_day_at
    from oracle.world.autonomy import autonomy_profile, modes_of, row_hour

    right = context = base_right = total = robot = count = best = only = base_only = together = together_right = 0
    for persona in make_personas(personas, seed):
        if persona.split != split:
            continue
        count += 1
        rows, _ = simulate_entries(persona, load_world(), days, seed)
        modes = modes_of(persona, rows, seed)
        profile = autonomy_profile(persona, seed)
        model = ModeCounts()
        by_task: dict[str, Counter[str]] = {}
        for row, mode in zip(rows, modes):
            call, part = str(row.action), part_of_day_at(seconds_of(row.time)) if row.time else "Midday"
            (usual,), _ = ranked_modes(model, [call], [], part)
            guess = usual.mode or "user"  # nothing of its task known: the user, as a tie goes
            task_counts = by_task.get(row.action.task)
            base = majority(task_counts) if task_counts else "user"
            best += profile.likeliest(row.action.task, row.action.args, row_hour(row)) == mode
            right += guess == mode
            context += model.predict(call, part)[0] == mode
            base_right += base == mode
            only += guess == mode != base
            base_only += base == mode != guess
            total += 1
            robot += mode == "robot"
            together += mode == "together"
            together_right += mode == "together" == guess
            model.add(Performed(call, part, mode))
            by_task.setdefault(row.action.task, Counter())[mode] += 1
    share = (lambda n: n / total) if total else (lambda n: 0.0)
    return AutonomyScores(count, total, share(right), share(context), share(base_right), share(robot), share(best),
                          only, base_only, share(together), together_right / together if together else 0.0)
