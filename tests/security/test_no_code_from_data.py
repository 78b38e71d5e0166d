"""Nothing read from a store, a dump, a cache or a request is unpickled or evaluated: every place
in the product that could turn bytes into code (pickle, marshal, shelve, eval, exec, unsafe YAML,
numpy pickles, a multiprocessing pipe) is listed here with why its bytes are the package's own.
A new one fails this test until it is listed, with its reason."""

from __future__ import annotations

import re
from pathlib import Path

PRODUCT = Path(__file__).resolve().parents[2] / "python" / "oracle"
#: The reproductions read files too (a shard, a report): held to the same rule, named from the
#: package's folder as ``../../experiments/NAME``.
EXPERIMENTS = PRODUCT.parents[1] / "experiments"
#: What turns bytes into objects that can name code.
RISKY = re.compile(r"pickle\.loads?\(|Unpickler|marshal\.loads?\(|\bshelve\b|(?<![\w.])eval\(|(?<![\w.])exec\(|"
                   r"yaml\.load\(|yaml\.unsafe_load|allow_pickle\s*=\s*True|jsonpickle|\bdill\b|\.recv\(\)")
#: (file, a text on the line, why the bytes there are the package's own, made in this process or
#: by this user alone).
ALLOWED = [
    ("algorithm/routine.py", "pickle.loads(pickle.dumps(self",
     "a copy of a model in memory: the bytes were made by pickle.dumps on the line itself"),
    ("algorithm/routine.py", "pickle.loads(pickle.dumps(value",
     "a copy of a part of a model's state in memory (one without a fork of its own), pickled on the same line"),
    ("algorithm/chaining.py", "pickle.loads(pickle.dumps(model",
     "the chain's copy of a model in memory, pickled on the same line"),
    ("../../experiments/chains.py", "model = pickle.loads(pickle.dumps(model))",
     "a copy of a model in memory, pickled on the same line"),
    ("../../experiments/plainstate-cost.py", "pickle.loads(pickled)",
     "the cost of reading back the pickle this script made two lines above, in memory (what the plain format replaced)"),
    ("service/explore_routes.py", "ok, value = parent.recv()",
     "the pipe from /explore's own replay child (multiprocessing), which pickles the replay it computed; "
     "both ends are this package's own processes: the bytes are made by its own pickler, never read from a file or a request"),
]


def _risky_lines() -> list[tuple[str, str]]:
    found = []
    for path in sorted(PRODUCT.rglob("*.py")) + sorted(EXPERIMENTS.rglob("*.py")):
        inside = PRODUCT in path.parents
        name = path.relative_to(PRODUCT).as_posix() if inside else f"../../experiments/{path.relative_to(EXPERIMENTS).as_posix()}"
        for line in path.read_text(encoding="utf-8").splitlines():
            code = line.split("#", 1)[0]
            if RISKY.search(code) and not code.strip().startswith(('"', "'")):
                found.append((name, line.strip()))
    return found


def test_every_place_that_could_turn_bytes_into_code_is_listed_with_its_reason():
    unlisted = [(name, line) for name, line in _risky_lines()
                if not any(name == where and text in line for where, text, _ in ALLOWED)]
    assert not unlisted, f"unpickling or evaluation not listed in {__file__} (with the reason its bytes are ours): {unlisted}"


def test_the_kept_fit_the_history_view_and_the_users_cache_use_no_pickle_to_read():
    for name in ("fitcache.py", "historycache.py", "plainstate.py", "store/kept.py", "store/dump.py",
                 "files.py", "ontology/cache.py", "ontology/plain.py", "ontology/model.py", "store/ontology_tbox.py"):
        text = (PRODUCT / name).read_text(encoding="utf-8")
        assert not re.search(r"pickle\.loads?\(|Unpickler", text), name


def test_the_list_names_only_what_is_still_there():
    lines = _risky_lines()
    stale = [(where, text) for where, text, _ in ALLOWED if not any(name == where and text in line for name, line in lines)]
    assert not stale, f"listed but gone (drop them from ALLOWED): {stale}"
