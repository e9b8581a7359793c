"""The help and ``navkit.cli``'s docstring say what ``navkit demo`` runs on.

The demo runs on the Willow Garage office when the data is found, and on a
synthetic office built in code when it is not (a fresh clone): the help and
the package docstring said "a real map" alone, a promise the fresh clone
does not keep.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import navkit.cli
from navkit.cli import main
from navkit.sim.scenarios import get_scenario


def _help(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    assert main(argv) == 0
    return " ".join(capsys.readouterr().out.split())


def test_the_demo_really_falls_back_to_the_synthetic_office(tmp_path: Path) -> None:
    # What the help is to say: no data found, the default map is the synthetic office.
    # (map_path None: the synthetic office, as the scenario documents; running it takes seconds.)
    assert get_scenario("demo")(data_dir=tmp_path, map="auto").map_path is None


def test_the_top_level_help_names_the_fallback(capsys: pytest.CaptureFixture[str]) -> None:
    text = _help(["--help"], capsys)
    commands = text[text.index("demo") : text.index(" list ")]
    assert "real office map" in commands
    assert "synthetic office when no data is found" in commands


def test_the_demo_help_names_the_fallback_of_its_default_map(
    capsys: pytest.CaptureFixture[str],
) -> None:
    text = _help(["demo", "--help"], capsys)
    assert "default auto: Willow Garage if found, else the synthetic office" in text


def test_the_package_docstring_names_the_fallback() -> None:
    doc = " ".join((navkit.cli.__doc__ or "").split())
    entry = doc[doc.index("``navkit demo`` —") : doc.index("``navkit list``")]
    assert "a synthetic office built in code when no data is found" in entry
