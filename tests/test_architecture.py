"""The house rules of docs/architecture.md, checked on the tree: small modules (or a reason in the
docstring), every module on that page and no stale names there, commands that do not import each
other, and a product that never imports the evaluation."""

from __future__ import annotations

import ast
import re
from pathlib import Path

from oracle.cli import COMMAND_MODULES

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "python" / "oracle"
PAGE = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
LARGE = 450


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
