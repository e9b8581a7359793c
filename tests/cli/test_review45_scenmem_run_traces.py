"""``navkit run`` keeps the trials' traces only for a picture (review 45, SCENMEM).

The tables and ``--json`` are made of the trials' values; only ``--plot`` and
``--animate`` draw the scene's traces. Without them the run sweeps with
``keep_traces=False``, so a long run from the command line holds no trace.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import navkit.cli._scenarios as scenarios_module
from navkit.cli import main


class Stop(Exception):
    """Ends the run once the sweep's arguments are seen (nothing runs or is drawn)."""


@pytest.mark.parametrize(
    ("options", "kept"),
    [
        ([], False),
        (["--json", "r.json"], False),
        (["--plot", "r.png"], True),
        (["--animate", "r.gif"], True),
        (["--json", "r.json", "--plot", "r.png"], True),
    ],
)
def test_the_traces_are_kept_only_for_a_picture(
    options: list[str], kept: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    seen: list[Any] = []

    def spy(*args: Any, **kwargs: Any) -> Any:
        seen.append(kwargs.get("keep_traces", "not given"))
        raise Stop

    monkeypatch.setattr(scenarios_module, "sweep", spy)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(Stop):
        main(["run", "demo", "--trials", "1", "--workers", "1", "--quiet", *options])
    assert seen == [kept]
