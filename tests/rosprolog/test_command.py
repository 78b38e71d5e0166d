"""``oracle rosprolog``'s errors a user can cause: one line, exit 1, nothing started."""

from __future__ import annotations

import pytest

from oracle.cli import main


@pytest.mark.parametrize(("argv", "says"), [
    (["--ros-python", "/nonexistent/python3"], "ROS 1's Python packages are missing from /nonexistent/python3"),
    (["--namespace", "a b"], "--namespace 'a b': expected a ROS name"),
    (["--query-seconds", "0"], "--query-seconds 0.0: expected more than 0"),
])
def test_one_line_errors(argv, says, tmp_path, capsys):
    assert main(["rosprolog", "--store", str(tmp_path / "none.sqlite"), *argv]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: ") and says in err and err.count("\n") == 1
