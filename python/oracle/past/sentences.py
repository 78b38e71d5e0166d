"""The answers about the past as sentences, in English and German, from the evidence that
prolog/odb/past.pl hands over (oracle.past.evidence)."""

from __future__ import annotations

from collections.abc import Callable
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


#: How a sentence names a task call: (call, language, way) -> words; way is "ing" (English
#: "opening the fridge"), "pp" (German "den Kühlschrank geöffnet"), "do" (the imperative in lower
#: case: "open the fridge" / "den Kühlschrank öffnen"), "does" (English third person).
Namer = Callable[[str, str, str], str]
#: How a sentence names an object: (name, language) -> words ("the green mug" / "den grünen Becher").
ObjectNamer = Callable[[str, str], str]


def _code(call: str, language: str, way: str) -> str:
    return call


def _code_obj(name: str, language: str) -> str:
    return name


def sentences(form: str, evidence: dict[str, Any], name: Namer | None = None,
              obj: ObjectNamer | None = None) -> tuple[str, str]:
    """The (English, German) answer of a form from its evidence; tasks and objects in the words
    ``name`` and ``obj`` give (default: the call syntax and the odb name)."""
    return _SAY[form](evidence, evidence.get("now"), name or _code, obj or _code_obj)


def _cap(text: str) -> str:
    return text[:1].upper() + text[1:]


def _last(e: dict[str, Any], now: float | None, name: Namer, obj: ObjectNamer) -> tuple[str, str]:
    task, begin = e["task"], e["begin"]
    if begin is None:
        return f"{_cap(name(task, 'en', 'ing'))} was never done.", f"Noch nie {name(task, 'de', 'pp')}."
    return (f"{_cap(name(task, 'en', 'ing'))} was last done {when(begin, now, 'en')}.",
            f"Zuletzt {when(begin, now, 'de')} {name(task, 'de', 'pp')}.")


def _count(e: dict[str, Any], now: float | None, name: Namer, obj: ObjectNamer) -> tuple[str, str]:
    task, begins = e["task"], e["begins"]
    en_period, de_period = PERIOD_WORDS[e["period"]]
    ing, pp = _cap(name(task, "en", "ing")), name(task, "de", "pp")
    if not begins:
        return f"{ing} was not done {en_period}.", f"{_cap(de_period)} nicht {pp}."
    n = len(begins)
    en = f"{ing}: {n} time{'s' if n != 1 else ''} {en_period} ({_times(begins, now, 'en')})."
    de = f"{_cap(de_period)} {n}-mal {pp} ({_times(begins, now, 'de')})."
    return en, de


def _counted_said(items: list[dict[str, Any]], language: str, name: Namer) -> str:
    def times(n: int) -> str:
        return f"{n}-mal" if language == "de" else f"{n} time{'s' if n != 1 else ''}"

    way = "do" if language == "de" else "ing"
    return ", ".join(f"{name(i['task'], language, way)} {times(i['count'])}" for i in items[:SPOKEN])


def _after(e: dict[str, Any], now: float | None, name: Namer, obj: ObjectNamer) -> tuple[str, str]:
    task, n, nexts = e["task"], e["occurrences"], e["next"]
    ing, pp = name(task, "en", "ing"), name(task, "de", "pp")
    if n == 0:
        return (f"{_cap(ing)} was never done, so nothing usually follows it.",
                f"Noch nie {pp}, also folgt nichts darauf.")
    if not nexts:
        return f"{_cap(ing)} was done once, as the last action so far.", f"Bisher nur einmal {pp}, als Letztes."
    return (f"After {ing} (done {n} times) came {_counted_said(nexts, 'en', name)}.",
            f"Nachdem du {pp} hast ({n}-mal), kam: {_counted_said(nexts, 'de', name)}.")


def _done(e: dict[str, Any], now: float | None, name: Namer, obj: ObjectNamer) -> tuple[str, str]:
    actions = e["actions"]
    en_period, de_period = PERIOD_WORDS[e["period"]]
    span = f"{clock(e['from']):%H:%M}-{clock(e['to']):%H:%M}"
    if not actions:
        return f"Nothing {en_period} ({span}).", f"Nichts {de_period} ({span})."
    listed_en = ", ".join(f"{name(a['task'], 'en', 'ing')} {when(a['begin'], now, 'en')}" for a in actions[:SPOKEN])
    listed_de = ", ".join(f"{name(a['task'], 'de', 'do')} {when(a['begin'], now, 'de')}" for a in actions[:SPOKEN])
    more = len(actions) - SPOKEN
    if more > 0:
        listed_en += f" and {more} more"
        listed_de += f" und {more} weitere"
    n = len(actions)
    return (f"{en_period.capitalize()} ({span}), {n} action{'s' if n != 1 else ''}: {listed_en}.",
            f"{de_period.capitalize()} ({span}), {n} Handlung{'en' if n != 1 else ''}: {listed_de}.")


def _where(e: dict[str, Any], now: float | None, name: Namer, obj: ObjectNamer) -> tuple[str, str]:
    thing, pose, used = e["object"], e["pose"], e["used"]
    en_obj, de_obj = obj(thing, "en"), obj(thing, "de")
    en: list[str] = []
    de: list[str] = []
    if pose is not None:
        x, y, z = (f"{v:.2f}" for v in pose["position"])
        en.append(f"{_cap(en_obj)} was last seen at ({x}, {y}, {z}) in {pose['frame']} {when(pose['time'], now, 'en')}.")
        de.append(f"Ich habe {de_obj} zuletzt {when(pose['time'], now, 'de')} bei ({x}, {y}, {z}) in {pose['frame']} gesehen.")
    if used is not None:
        en.append(f"{_cap(en_obj)} was last used {when(used['time'], now, 'en')} ({name(used['task'], 'en', 'ing')}).")
        de.append(f"Zuletzt benutzt {when(used['time'], now, 'de')}: {name(used['task'], 'de', 'pp')}.")
    if not en:
        return f"I have no record of where {en_obj} is.", f"Ich habe {de_obj} noch nirgends gesehen."
    return " ".join(en), " ".join(de)


def _ordinal(n: int) -> str:
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def _suggested(e: dict[str, Any], now: float | None, name: Namer, obj: ObjectNamer) -> tuple[str, str]:
    task = e["task"]
    ing, do = name(task, "en", "ing"), name(task, "de", "do")
    if e["time"] is None:
        return f"I never suggested {ing}.", f"Ich habe nie vorgeschlagen: {do}."
    at_en, at_de = when(e["time"], now, "en"), when(e["time"], now, "de")
    en = f"{at_en.capitalize()} I ranked {ing} {_ordinal(e['rank'])}"
    de = f"{at_de.capitalize()} habe ich \u201e{do}\u201c auf Platz {e['rank']} gesetzt"
    if e["rank"] != 1:
        en += f"; first was {name(e['top'], 'en', 'ing')}"
        de += f"; vorn lag \u201e{name(e['top'], 'de', 'do')}\u201c"
    routine = e.get("routine")
    if routine is not None:
        en += f". It was the next step of your routine \"{routine['name']}\" ({routine['left']} steps left)"
        de += f". Es war der nächste Schritt deiner Routine \"{routine['name']}\" (noch {routine['left']} Schritte)"
    before = e.get("before")
    if before is not None:
        en += (f". The action before was {name(before['task'], 'en', 'ing')}, after which {ing} came "
               f"{before['followed']} of {before['occurrences']} times")
        de += (f". Davor kam \u201e{name(before['task'], 'de', 'do')}\u201c; danach folgte \u201e{do}\u201c "
               f"{before['followed']} von {before['occurrences']} Malen")
    return en + ".", de + "."


def _who(e: dict[str, Any], now: float | None, name: Namer, obj: ObjectNamer) -> tuple[str, str]:
    task, usual, counts = e["task"], e["usual"], e["counts"]
    known = counts["user"] + counts["robot"] + counts.get("together", 0)
    if usual is None:
        return (f"I have no record of who did {name(task, 'en', 'ing')}.",
                f"Ich weiß nicht, wer {name(task, 'de', 'pp')} hat.")
    mine = counts[usual]
    times = "time" if known == 1 else "times"
    do, de_do = name(task, "en", "do"), name(task, "de", "do")
    if usual == "user":
        return (f"You usually {do} yourself ({mine} of {known} {times}).",
                f"\u201e{_cap(de_do)}\u201c machst du meistens selbst ({mine} von {known} Malen).")
    if usual == "together":
        return (f"You usually {do} together with the robot ({mine} of {known} {times}).",
                f"\u201e{_cap(de_do)}\u201c machst du meistens zusammen mit dem Roboter ({mine} von {known} Malen).")
    return (f"The robot usually {name(task, 'en', 'does')} for you ({mine} of {known} {times}).",
            f"\u201e{_cap(de_do)}\u201c macht meistens der Roboter für dich ({mine} von {known} Malen).")


_SAY: dict[str, Callable[[dict[str, Any], float | None, Namer, ObjectNamer], tuple[str, str]]] = {
    "last": _last, "count": _count, "after": _after, "done": _done, "where": _where, "suggested": _suggested,
    "who": _who}
