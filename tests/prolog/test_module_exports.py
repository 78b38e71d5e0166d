"""The bridge imports every module it loads into ``user``: two of them exporting the same
predicate make that import fail (SWI-Prolog's "No permission to import"), and the second
module's predicate is then missing from every query. One predicate, one home."""

from __future__ import annotations

import re
from collections import defaultdict

from oracle.bridge import MODULES
from oracle.paths import prolog_dir

MODULE_HEAD = re.compile(r":- module\(\s*(\w+)\s*,\s*\[(.*?)\]\s*\)\.", re.S)


def exports(path: str) -> tuple[str, list[str]]:
    text = (prolog_dir() / f"{path}.pl").read_text(encoding="utf-8")
    head = MODULE_HEAD.search(text)
    assert head, f"{path}.pl has no module header"
    body = re.sub(r"%[^\n]*", "", head.group(2))
    return head.group(1), [pi.replace(" ", "") for pi in re.findall(r"[a-z_]\w*\s*/\s*\d+", body)]


def test_no_two_loaded_modules_export_the_same_predicate():
    homes: dict[str, list[str]] = defaultdict(list)
    for path in MODULES:
        module, names = exports(path)
        for name in names:
            homes[name].append(module)
    twice = {name: found for name, found in homes.items() if len(found) > 1}
    assert not twice, f"exported by more than one loaded module: {twice}"
