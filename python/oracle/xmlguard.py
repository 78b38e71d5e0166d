"""XML entities bounded before any XML a user is handed is parsed (odb manifests, RDF/XML ontologies).

A document type may declare entities; nested ones grow exponentially (683 bytes of OWL cost
rdflib 160 s of CPU), external ones read files or URLs. So before rdflib or ElementTree sees a
document, expat (the parser both use) reads its declarations here, and:

- an external entity (``SYSTEM``/``PUBLIC``), an unparsed one and a parameter entity are refused;
- an internal entity may be at most ``MAX_ENTITY`` characters long once its references to
  other entities are expanded (Protégé declares IRI prefixes such as ``&owl;``, under 100);
- all references in the document together may add at most ``max(1 MiB, the file's size)``
  characters: entities can at most double a document.

A document that declares no entity costs one look at its prologue (the parse stops at the root
element); the official SOMA/DUL files declare none.
"""

from __future__ import annotations

import re
from pyexpat import ExpatError, ParserCreate, errors
from typing import Any


#: Longest expansion of one internal entity, in characters.
MAX_ENTITY = 4096
#: Expansion all references together may add, at least (else the document's own size).
MIN_BUDGET = 1 << 20

#: expat's own code for a breached amplification limit (expat >= 2.4); -1 where it has none.
_AMPLIFICATION = errors.codes.get(getattr(errors, "XML_ERROR_AMPLIFICATION_LIMIT_BREACH", ""), -1)

_REFERENCE = re.compile(r"&([A-Za-z_:][-\w.:]*);")


class _Refused(Exception):
    """Raised from a handler to stop the parse with a reason."""


class _Done(Exception):
    """Raised from a handler when nothing more needs to be read."""


class _Check:
    def __init__(self, budget: int) -> None:
        self.sizes: dict[str, int] = {}
        self.budget = budget
        self.added = 0
        self.in_dtd = False

    def expanded(self, text: str) -> int:
        """Characters ``text`` has once the references to declared entities are expanded."""
        size = len(text)
        for match in _REFERENCE.finditer(text):
            name = match.group(1)
            if name in self.sizes:
                size += self.sizes[name] - len(match.group(0))
        return size

    def declared(self, name: str, parameter: bool, value: str | None, base: Any, system: str | None,
                 public: str | None, notation: str | None) -> None:
        if parameter:
            raise _Refused(f"declares the parameter entity %{name}; (refused)")
        if value is None or system is not None or public is not None or notation is not None:
            raise _Refused(f"declares the external entity &{name}; (refused: it would read another file or URL)")
        size = self.expanded(value)
        if size > MAX_ENTITY:
            raise _Refused(f"entity &{name}; expands to {size} characters, more than {MAX_ENTITY}")
        self.sizes[name] = size

    def started(self, name: str, attributes: Any) -> None:
        if not self.sizes:
            raise _Done  # no entity declared: nothing the rest of the document can expand

    def passed(self, data: str) -> None:
        # With a default handler (and no other), expat hands over references unexpanded, start
        # tags as written (their attribute values unexpanded too).
        if "&" in data and not self.in_dtd:
            self.added += self.expanded(data) - len(data)
            if self.added > self.budget:
                raise _Refused(f"its entity references expand by more than {self.budget} characters")


def check_entities(data: bytes, where: str, error: type[Exception]) -> None:
    """Refuse (``error``, one line naming ``where``) an XML document whose entities are external,
    parameter entities or expand beyond the bounds of the module's docstring. A document that is
    not well-formed is left to the real parser, which names the fault."""
    check = _Check(max(MIN_BUDGET, len(data)))
    probe = ParserCreate()
    probe.SetParamEntityParsing(0)  # XML_PARAM_ENTITY_PARSING_NEVER: no external DTD is read
    probe.EntityDeclHandler = check.declared
    probe.UnparsedEntityDeclHandler = lambda name, *rest: check.declared(name, False, None, None, "", None, "")
    probe.StartElementHandler = check.started
    try:
        probe.Parse(data, True)
    except _Done:
        return
    except _Refused as refused:
        raise error(f"{where}: {refused}") from None
    except ExpatError as failure:
        if failure.code == _AMPLIFICATION:
            raise error(f"{where}: its entities expand too much (refused)") from None
        return  # malformed: the real parser reports it with its line
    if check.sizes:
        _count_references(data, check, where, error)


def _count_references(data: bytes, check: _Check, where: str, error: type[Exception]) -> None:
    """Parse again with only a default handler, adding up what each reference expands to."""
    counter = ParserCreate()
    counter.SetParamEntityParsing(0)
    counter.DefaultHandler = check.passed
    # the declarations themselves reach the default handler too: their references add nothing
    counter.StartDoctypeDeclHandler = lambda *_: setattr(check, "in_dtd", True)
    counter.EndDoctypeDeclHandler = lambda: setattr(check, "in_dtd", False)
    try:
        counter.Parse(data, True)
    except _Refused as refused:
        raise error(f"{where}: {refused}") from None
    except ExpatError:
        return


__all__ = ["MAX_ENTITY", "check_entities"]
