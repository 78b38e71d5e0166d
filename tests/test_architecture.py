"""The house rules of docs/architecture.md, checked on the tree: small modules (or a reason in the
docstring), Prolog modules of at most 20 exports, every module on that page and no stale names there,
commands that do not import each other, and a product that never imports the evaluation."""

from __future__ import annotations

import ast
import re
from pathlib import Path

from oracle.cli import COMMAND_MODULES

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "python" / "oracle"
PAGE = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
LARGE = 450
#: No module is longer than this, whatever its reason.
MOST_LINES = 600
PROLOG = ROOT / "prolog"
#: KnowRob's modules export about a dozen predicates about one concept (style.md): at most this many.
MOST_EXPORTS = 20
MODULE_HEAD = re.compile(r":- module\(\s*\w+\s*,\s*\[(.*?)\]\s*\)\.", re.S)
REEXPORT = re.compile(r":- reexport\(\s*(\[.*?\]|[^,\[\]()]+?)\s*(?:,\s*\[(.*?)\])?\s*\)\.", re.S)
INDICATOR = re.compile(r"[a-z_]\w*\s*/\s*\d+")


def modules() -> list[Path]:
    return sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


def imported(path: Path) -> set[str]:
    """Every module a file imports, at the top or inside a function."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
            names.update(f"{node.module}.{alias.name}" for alias in node.names)
    return names


def rows_by_package() -> list[tuple[str | None, str]]:
    """(package of the section, table row) for every table row of the page; the package is the
    ``pkg/`` a section heading names (``### Store `store/```), else None."""
    rows: list[tuple[str | None, str]] = []
    package: str | None = None
    for line in PAGE.splitlines():
        if line.startswith("#"):
            found = re.search(r"`([a-z_]+)/`", line)
            package = found.group(1) if found and line.startswith("### ") else None
        elif line.startswith("|"):
            rows.append((package, line))
    return rows


def test_no_module_is_large_without_saying_why():
    large = []
    for path in modules():
        lines = path.read_text(encoding="utf-8").count("\n")
        doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
        if lines > LARGE and "why this module is large" not in doc.lower():
            large.append(f"{path.relative_to(PACKAGE)} ({lines} lines)")
    assert not large, f"over {LARGE} lines without 'Why this module is large' in the docstring: {large}"


def test_no_module_is_over_the_most_lines():
    """A stated reason lets a module pass 450 lines, not 600: past that it is split."""
    huge = [f"{path.relative_to(PACKAGE)} ({lines} lines)" for path in modules()
            if (lines := path.read_text(encoding="utf-8").count("\n")) > MOST_LINES]
    assert not huge, f"over {MOST_LINES} lines (split them): {huge}"


def prolog_exports(path: Path) -> set[str]:
    """What a Prolog module exports: its header's list and what it re-exports (a reexport/2 list, or
    every export of the modules a reexport/1 names, paths relative to the file)."""
    text = re.sub(r"%[^\n]*", "", path.read_text(encoding="utf-8"))
    head = MODULE_HEAD.search(text)
    found = {pi.replace(" ", "") for pi in INDICATOR.findall(head.group(1))} if head else set()
    for spec, only in REEXPORT.findall(text):
        if only:
            found |= {pi.replace(" ", "") for pi in INDICATOR.findall(only)}
            continue
        for name in spec.strip("[]").split(","):
            found |= prolog_exports((path.parent / f"{name.strip().strip(chr(39))}.pl").resolve())
    return found


def test_no_prolog_module_exports_more_than_twenty() -> None:
    crowded = {}
    for path in sorted(PROLOG.rglob("*.pl")):
        count = len(prolog_exports(path))
        if count > MOST_EXPORTS:
            crowded[str(path.relative_to(PROLOG))] = count
    assert not crowded, f"Prolog modules exporting more than {MOST_EXPORTS} predicates (split them): {crowded}"


def test_the_export_count_sees_re_exports(tmp_path: Path) -> None:
    (tmp_path / "part.pl").write_text(":- module(part, [a/1, b/2]).\n", encoding="utf-8")
    (tmp_path / "facade.pl").write_text(":- module(facade, [c/0]).\n:- reexport(part).\n"
                                        ":- reexport(store/x, [d/1, % a comment e/9\n e/2]).\n", encoding="utf-8")
    assert prolog_exports(tmp_path / "facade.pl") == {"a/1", "b/2", "c/0", "d/1", "e/2"}
    assert len(prolog_exports(PROLOG / "neem_store.pl")) > 0  # a facade of re-exports only


def test_the_architecture_page_names_every_module():
    rows = rows_by_package()
    missing = []
    for path in modules():
        rel = path.relative_to(PACKAGE)
        if rel.name == "__init__.py" and len(rel.parts) > 1:
            continue  # a package is named by its folder
        name, package = rel.stem, rel.parts[0] if len(rel.parts) > 1 else None
        tokens = f"`{name}`", f"{name}.py`", f"{name}`,"
        found = any(
            str(rel) in row
            or (package is not None and (section == package or f"`{package}/" in row) and any(t in row for t in tokens))
            or (package is None and section is None and f"`{rel}`" in row)
            for section, row in rows
        )
        if not found:
            missing.append(str(rel))
    assert not missing, f"docs/architecture.md does not name: {missing}"


def test_the_architecture_page_names_no_module_that_is_gone():
    stale = []
    for section, row in rows_by_package():
        for token in re.findall(r"`([a-z_/]+\.py)`", row):
            path = PACKAGE / section / token if section and "/" not in token else PACKAGE / token
            if not path.exists():
                stale.append(token)
    prolog = " ".join(row for _, row in rows_by_package() if row.startswith("| `prolog/"))
    for path in (ROOT / "prolog").rglob("*.pl"):
        if "fixtures" not in path.parts and not re.search(rf"\b{re.escape(path.stem)}\b", prolog):
            stale.append(f"(not named) prolog/{path.relative_to(ROOT / 'prolog')}")
    assert not stale, f"docs/architecture.md and the tree disagree: {stale}"


def test_commands_do_not_import_each_other():
    crossing = []
    for name in COMMAND_MODULES:
        path = PACKAGE / "commands" / f"{name}.py"
        others = {f"oracle.commands.{other}" for other in COMMAND_MODULES if other != name}
        crossing += [f"{name} imports {module}" for module in imported(path) & others]
    assert not crossing, crossing


def test_the_product_never_imports_the_evaluation():
    """Flow one way: only the evaluation itself, the CLI's commands and the benchmarks sit above it."""
    above = {"evaluation", "commands", "benchmarks"}
    leaning = []
    for path in modules():
        rel = path.relative_to(PACKAGE)
        if rel.parts[0] in above:
            continue
        leaning += [f"{rel} imports {m}" for m in imported(path) if m == "oracle.evaluation" or m.startswith("oracle.evaluation.")]
    assert not leaning, leaning


def runtime_imports(path: Path, modules_by_name: dict[str, Path]) -> set[str]:
    """The package's modules a file imports when it runs (at the top or inside a function; not
    under ``if TYPE_CHECKING``); ``from pkg import mod`` is an arrow to ``pkg.mod`` alone."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    typing_only = {id(n) for node in ast.walk(tree)
                   if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test) for n in ast.walk(node)}
    found: set[str] = set()
    for node in ast.walk(tree):
        if id(node) in typing_only:
            continue
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            submodules = {f"{node.module}.{alias.name}" for alias in node.names} & modules_by_name.keys()
            found |= submodules
            if len(submodules) < len(node.names):
                found.add(node.module)
    return found & modules_by_name.keys()


def import_graph() -> dict[str, set[str]]:
    by_name = {}
    for path in modules():
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        by_name[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return {name: runtime_imports(path, by_name) - {name} for name, path in by_name.items()}


def circles(graph: dict[str, set[str]]) -> list[frozenset[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[frozenset[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        for other in graph[node]:
            if other not in index:
                visit(other)
                low[node] = min(low[node], low[other])
            elif other in stack:
                low[node] = min(low[node], index[other])
        if low[node] == index[node]:
            component = []
            while True:
                other = stack.pop()
                component.append(other)
                if other == node:
                    break
            if len(component) > 1:
                found.append(frozenset(component))

    for node in graph:
        if node not in index:
            visit(node)
    return found


def test_no_import_circle():
    """The package's modules import each other without a circle (at run time, function-level
    imports included), so each can be read, tested and loaded above the ones it uses."""
    found = circles(import_graph())
    assert not found, f"import circles: {[sorted(c) for c in found]}"


def test_the_circle_check_finds_a_circle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert circles(graph) == [frozenset({"a", "b", "c"})]



def test_only_the_doors_import_the_service():
    """The service sits on top: the words, the answers and the CLI's own commands read nothing of
    it (oracle.words lives below both), only the doors that serve (serve, simulate, rosprolog) and
    the benchmarks that measure it."""
    above = {"service", "rosprolog", "benchmarks", "commands/serve.py", "commands/simulate.py"}
    leaning = []
    for path in modules():
        rel = path.relative_to(PACKAGE)
        if rel.parts[0] in above or rel.as_posix() in above:
            continue
        leaning += [f"{rel} imports {m}" for m in imported(path) if m == "oracle.service" or m.startswith("oracle.service.")]
    assert not leaning, leaning

FOUNDATIONS = {"oracle.errors", "oracle.namespaces", "oracle.paths", "oracle.yamlfile", "oracle.timeline", "oracle.chains",
               "oracle.modulecache", "oracle.files", "oracle.handed", "oracle.xmlguard"}


def test_the_foundations_import_nothing_above_them():
    graph = import_graph()
    upward = {name: sorted(graph[name] - FOUNDATIONS) for name in FOUNDATIONS if graph[name] - FOUNDATIONS}
    assert not upward, upward


def test_only_the_bridge_imports_pyswip():
    importers = {path.relative_to(PACKAGE).parts[0] for path in modules()
                 if any(name == "pyswip" or name.startswith("pyswip.") for name in imported(path))}
    assert importers == {"bridge"}, importers
