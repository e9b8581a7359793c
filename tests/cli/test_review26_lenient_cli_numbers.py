"""Command-line numbers are read as C's strtod reads them, not as Python's float() (session 30).

``--start 1_0,0`` was x = 10 (float() takes ``_`` between digits), ``--trials
1_0`` ten trials, and digits of other scripts (``١``) read as numbers. Each is
refused with the option's own message; spaces around a number still are fine.
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.cli import main
from navkit.cli._parser import build_parser, join_negative_points


def usage_error(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The last line of a usage error (exit code 2, no traceback)."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: navkit") and "Traceback" not in err
    return err.strip().splitlines()[-1]


PLAN = ["plan", "m.yaml", "--goal", "0,0"]


@pytest.mark.parametrize(
    "text", ["1_0,0", "0,1_0", "(1_0, 0)", "1__0,0", "1.0_0,0", "1e1_0,0", "١,0", "1,٢",
             "１,0", "0x10,0", "1,2j", "in f,0"],
)  # fmt: skip
def test_python_only_spellings_of_a_point_are_refused(
    text: str, capsys: pytest.CaptureFixture[str]
) -> None:
    line = usage_error([*PLAN, "--start", text], capsys)
    assert line.endswith(f"argument --start: expected X,Y in metres, got {text!r}")


@pytest.mark.parametrize(
    ("option", "text", "words"),
    [("--radius", "0_1", "expected a radius in metres"),
     ("--radius", "٠.1", "expected a radius in metres"),
     ("--start-tolerance", "1_0", "expected a distance in metres")],
)  # fmt: skip
def test_python_only_spellings_of_a_distance_are_refused(
    option: str, text: str, words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    line = usage_error([*PLAN, "--start", "0,0", option, text], capsys)
    assert line.endswith(f"argument {option}: {words}, got {text!r}")


@pytest.mark.parametrize(
    ("option", "text"),
    [("--trials", "1_0"), ("--seed", "1_000"), ("--workers", "٢"), ("--trials", "１"),
     ("--seed", "_1"), ("--seed", "1_" + "0" * 5000)],
)  # fmt: skip
def test_python_only_spellings_of_an_integer_are_refused(
    option: str, text: str, capsys: pytest.CaptureFixture[str]
) -> None:
    line = usage_error(["run", "demo", option, text], capsys)
    assert line.endswith(f"argument {option}: expected an integer, got {text!r}")


def test_plain_spellings_are_still_read() -> None:
    argv = ["plan", "m.yaml", "--start", " ( 1.5 , -2 ) ", "--goal", "1e1,.5",
            "--radius", " 0.25 ", "--start-tolerance", "+1.", ]  # fmt: skip
    args = build_parser().parse_args(join_negative_points(argv))
    read = (args.start, args.goal, args.radius, args.start_tolerance)
    assert read == ((1.5, -2.0), (10.0, 0.5), 0.25, 1.0)
    run = build_parser(["demo"]).parse_args(["run", "demo", "--seed", " 007 ", "--trials", "+3"])
    assert (run.seed, run.trials) == (7, 3)


def test_an_over_long_integer_is_still_out_of_range(capsys: pytest.CaptureFixture[str]) -> None:
    line = usage_error(["run", "demo", "--seed", "9" * 5000], capsys)
    assert line.endswith("--seed: must be in [0, 2**64), got an integer of 5000 characters")


@given(x=st.floats(allow_nan=False, allow_infinity=False),
       fmt=st.sampled_from(["{!r}", "{:.6e}", "{:.3f}"]))  # fmt: skip
def test_every_float_python_prints_is_read_as_float_reads_it(x: float, fmt: str) -> None:
    text = fmt.format(x)
    argv = join_negative_points(["plan", "m.yaml", "--start", f"{text},{text}", "--goal", "0,0"])
    assert build_parser().parse_args(argv).start == (float(text), float(text))
