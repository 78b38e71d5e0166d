"""The page's own control words (the "More" button, the offline line, a kept choice), English
and German. The task words and reasons live in ``oracle.service.words``; these only name what
the page itself does, so they are merged under its text (words.py's keys win)."""

from __future__ import annotations

#: By language; ``{...}`` are filled in by the page's script.
PAGE_TEXT: dict[str, dict[str, str]] = {
    "en": {
        "more": "More suggestions ({n})", "fewer": "Fewer suggestions",
        "offline": "The robot cannot be reached. The buttons are off until it is back; reconnecting\u2026",
        "kept": "Your choice \u201c{task}\u201d is kept. It goes to the robot as soon as the robot is back.",
        "kept_sent": "The robot is back. Your choice \u201c{task}\u201d has been sent.",
        "kept_gone": "The robot is back, but it cannot do \u201c{task}\u201d any more. Nothing was sent.",
        "chosen": "Chosen", "off": "(not now: the robot cannot be reached)",
    },
    "de": {
        "more": "Weitere Vorschl\u00e4ge ({n})", "fewer": "Weniger Vorschl\u00e4ge",
        "offline": "Der Roboter ist nicht erreichbar. Die Kn\u00f6pfe sind aus, bis er wieder da ist; verbinde neu\u2026",
        "kept": "Ihre Wahl \u201e{task}\u201c ist gespeichert. Sie geht an den Roboter, sobald er wieder da ist.",
        "kept_sent": "Der Roboter ist wieder da. Ihre Wahl \u201e{task}\u201c wurde gesendet.",
        "kept_gone": "Der Roboter ist wieder da, kann \u201e{task}\u201c aber nicht mehr tun. Nichts wurde gesendet.",
        "chosen": "Gew\u00e4hlt", "off": "(gerade nicht: der Roboter ist nicht erreichbar)",
    },
}


def page_text(lang: str, text: dict[str, str]) -> dict[str, str]:
    """The page's words: these controls' in ``lang`` (else English) under ``text``."""
    return {**PAGE_TEXT.get(lang, PAGE_TEXT["en"]), **text}
