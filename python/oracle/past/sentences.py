"""The answers about the past as sentences, in English and German, from the evidence that
prolog/odb/past.pl hands over (oracle.past.evidence)."""

from __future__ import annotations

from typing import Any

from oracle.timeline import clock

#: How many actions or times a sentence names; the JSON evidence keeps them all.
SPOKEN = 6

PERIOD_WORDS = {
    "today": ("today", "heute"), "week": ("this week", "diese Woche"),
    "Morning": ("this morning", "heute morgen"), "Midday": ("at midday", "heute mittag"),
    "Evening": ("this evening", "heute abend"),
}


def when(seconds: float, now: float | None, language: str) -> str:
    """A time as spoken: the clock alone on the day of ``now``, else with its date."""
    moment = clock(seconds)
    same_day = now is not None and clock(now).date() == moment.date()
    if language == "de":
        return f"um {moment:%H:%M}" if same_day else f"am {moment:%d.%m.%Y} um {moment:%H:%M}"
    return f"at {moment:%H:%M}" if same_day else f"on {moment:%Y-%m-%d} at {moment:%H:%M}"


def _times(begins: list[float], now: float | None, language: str) -> str:
    shown = ", ".join(when(b, now, language) for b in begins[:SPOKEN])
    more = len(begins) - SPOKEN
    if more > 0:
        shown += f" und {more} weitere" if language == "de" else f" and {more} more"
    return shown


def _counted(items: list[dict[str, Any]], language: str) -> str:
    def times(n: int) -> str:
        return f"{n}-mal" if language == "de" else f"{n} time{'s' if n != 1 else ''}"

    return ", ".join(f"{i['task']} {times(i['count'])}" for i in items[:SPOKEN])


def sentences(form: str, evidence: dict[str, Any]) -> tuple[str, str]:
    """The (English, German) answer of a form from its evidence."""
    return _SAY[form](evidence, evidence.get("now"))


def _last(e: dict[str, Any], now: float | None) -> tuple[str, str]:
    task, begin = e["task"], e["begin"]
    if begin is None:
        return f"{task} was never done.", f"{task} wurde noch nie gemacht."
    return (f"{task} was last done {when(begin, now, 'en')}.", f"{task} wurde zuletzt {when(begin, now, 'de')} gemacht.")


def _count(e: dict[str, Any], now: float | None) -> tuple[str, str]:
    task, begins = e["task"], e["begins"]
    en_period, de_period = PERIOD_WORDS[e["period"]]
    if not begins:
        return f"{task} was not done {en_period}.", f"{task} wurde {de_period} nicht gemacht."
    n = len(begins)
    en = f"{task}: {n} time{'s' if n != 1 else ''} {en_period} ({_times(begins, now, 'en')})."
    de = f"{task}: {de_period} {n}-mal ({_times(begins, now, 'de')})."
    return en, de


def _after(e: dict[str, Any], now: float | None) -> tuple[str, str]:
    task, n, nexts = e["task"], e["occurrences"], e["next"]
    if n == 0:
        return f"{task} was never done, so nothing usually follows it.", f"{task} wurde noch nie gemacht, also folgt nichts darauf."
    if not nexts:
        return f"{task} was done once, as the last action so far.", f"{task} war bisher nur die letzte Handlung."
    return (f"After {task} (done {n} times) came {_counted(nexts, 'en')}.",
            f"Nach {task} ({n}-mal gemacht) kam {_counted(nexts, 'de')}.")


def _done(e: dict[str, Any], now: float | None) -> tuple[str, str]:
    actions = e["actions"]
    en_period, de_period = PERIOD_WORDS[e["period"]]
    span = f"{clock(e['from']):%H:%M}-{clock(e['to']):%H:%M}"
    if not actions:
        return f"Nothing {en_period} ({span}).", f"Nichts {de_period} ({span})."
    listed_en = ", ".join(f"{a['task']} {when(a['begin'], now, 'en')}" for a in actions[:SPOKEN])
    listed_de = ", ".join(f"{a['task']} {when(a['begin'], now, 'de')}" for a in actions[:SPOKEN])
    more = len(actions) - SPOKEN
    if more > 0:
        listed_en += f" and {more} more"
        listed_de += f" und {more} weitere"
    n = len(actions)
    return (f"{en_period.capitalize()} ({span}), {n} action{'s' if n != 1 else ''}: {listed_en}.",
            f"{de_period.capitalize()} ({span}), {n} Handlung{'en' if n != 1 else ''}: {listed_de}.")


def _where(e: dict[str, Any], now: float | None) -> tuple[str, str]:
    obj, pose, used = e["object"], e["pose"], e["used"]
    en: list[str] = []
    de: list[str] = []
    if pose is not None:
        x, y, z = (f"{v:.2f}" for v in pose["position"])
        en.append(f"The {obj} was last seen at ({x}, {y}, {z}) in {pose['frame']} {when(pose['time'], now, 'en')}.")
        de.append(f"{obj} wurde zuletzt {when(pose['time'], now, 'de')} bei ({x}, {y}, {z}) in {pose['frame']} gesehen.")
    if used is not None:
        en.append(f"The {obj} was last used in {used['task']} {when(used['time'], now, 'en')}.")
        de.append(f"{obj} wurde zuletzt {when(used['time'], now, 'de')} bei {used['task']} benutzt.")
    if not en:
        return f"I have no record of where the {obj} is.", f"Ich weiß nicht, wo {obj} ist."
    return " ".join(en), " ".join(de)


def _ordinal(n: int) -> str:
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def _suggested(e: dict[str, Any], now: float | None) -> tuple[str, str]:
    task = e["task"]
    if e["time"] is None:
        return f"I never suggested {task}.", f"Ich habe {task} nie vorgeschlagen."
    at_en, at_de = when(e["time"], now, "en"), when(e["time"], now, "de")
    en = f"{at_en.capitalize()} I ranked {task} {_ordinal(e['rank'])} (score {e['score']:.3g})"
    de = f"{at_de.capitalize()} habe ich {task} auf Rang {e['rank']} gesetzt (Wert {e['score']:.3g})"
    if e["rank"] != 1:
        en += f"; first was {e['top']}"
        de += f"; vorn lag {e['top']}"
    routine = e.get("routine")
    if routine is not None:
        en += f". It was the next step of your routine \"{routine['name']}\" ({routine['left']} steps left)"
        de += f". Es war der nächste Schritt deiner Routine \"{routine['name']}\" (noch {routine['left']} Schritte)"
    before = e.get("before")
    if before is not None:
        en += (f". The action before was {before['task']}, after which {task} came "
               f"{before['followed']} of {before['occurrences']} times")
        de += (f". Davor kam {before['task']}; danach folgte {task} "
               f"{before['followed']} von {before['occurrences']} Malen")
    return en + ".", de + "."


def _who(e: dict[str, Any], now: float | None) -> tuple[str, str]:
    task, usual, counts = e["task"], e["usual"], e["counts"]
    known = counts["user"] + counts["robot"] + counts.get("together", 0)
    if usual is None:
        return (f"I have no record of who did {task}.", f"Ich weiß nicht, wer {task} gemacht hat.")
    mine = counts[usual]
    times = "time" if known == 1 else "times"
    if usual == "user":
        return (f"You usually do {task} yourself ({mine} of {known} {times}).",
                f"Du machst {task} meistens selbst ({mine} von {known} Malen).")
    if usual == "together":
        return (f"You usually do {task} together with the robot ({mine} of {known} {times}).",
                f"Du machst {task} meistens zusammen mit dem Roboter ({mine} von {known} Malen).")
    return (f"The robot usually does {task} for you ({mine} of {known} {times}).",
            f"Der Roboter macht {task} meistens für dich ({mine} von {known} Malen).")


_SAY = {"last": _last, "count": _count, "after": _after, "done": _done, "where": _where, "suggested": _suggested, "who": _who}
