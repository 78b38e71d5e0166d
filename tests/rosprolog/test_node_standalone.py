"""The ROS node runs under Debian's python3, where this package is not installed: it imports
nothing of ``oracle`` (an import there broke every door start once)."""

from __future__ import annotations

import ast
from pathlib import Path

NODE = Path(__file__).resolve().parents[2] / "python" / "oracle" / "rosprolog" / "node.py"


def test_the_node_imports_nothing_of_the_package():
    imported = set()
    for node in ast.walk(ast.parse(NODE.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            imported.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            imported.add(node.module)
    assert not {name for name in imported if name == "oracle" or name.startswith("oracle.")}
