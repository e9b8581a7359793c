"""``navkit warmup`` (issue 17): compile the kernels now, print a table, exit 0."""

from __future__ import annotations

import io

import pytest

from navkit.cli import _app
from navkit.cli._parser import build_parser
from navkit.cli._warmup import warmup_command


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def _run(argv: list[str], err: io.StringIO | None = None) -> tuple[int, str, str]:
    args = build_parser(["demo"]).parse_args(argv)
    out, err = io.StringIO(), err if err is not None else io.StringIO()
    code = warmup_command(args, out, err)
    return code, out.getvalue(), err.getvalue()


def test_prints_a_table_of_the_steps() -> None:
    code, out, err = _run(["warmup", "--only", "geometry", "--only", "reactive", "--workers", "1"])
    assert code == 0
    assert "navkit warmup (this process)" in out
    assert "geometry" in out and "reactive" in out and "total" in out
    assert "astar" not in out
    assert err == ""  # not a terminal: no progress


def test_progress_on_a_terminal_only_unless_quiet() -> None:
    code, _, err = _run(["warmup", "--only", "geometry", "--workers", "1"], Terminal())
    assert code == 0 and "1/1 steps" in err
    code, _, err = _run(["warmup", "--only", "geometry", "--workers", "1", "--quiet"], Terminal())
    assert code == 0 and err == ""


@pytest.mark.parametrize(
    "argv", [["warmup", "--only", "nope"], ["warmup", "--workers", "0"], ["warmup", "--bogus"]]
)
def test_bad_arguments_exit_2(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        build_parser(["demo"]).parse_args(argv)
    assert exc.value.code == 2
    assert "usage" in capsys.readouterr().err


def test_main_dispatches_warmup(capsys: pytest.CaptureFixture[str]) -> None:
    assert _app.main(["warmup", "--only", "geometry", "--workers", "1"]) == 0
    assert "geometry" in capsys.readouterr().out
