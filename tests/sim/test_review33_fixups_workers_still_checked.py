"""Review 33 (FIXUPS): ``workers`` with an ``executor`` is "not used (still checked)".

``sweep`` and ``Scenario.run`` said ``workers`` was "ignored" with an
``executor``, yet an invalid ``workers`` is refused there too. Checked: against
HEAD's docstrings the first test fails ("Ignored"); the second pins the
behaviour the new words describe (it held before).
"""

from __future__ import annotations

import concurrent.futures
import inspect

import pytest

from navkit.sim import Scenario, sweep
from navkit.sim.scenarios import Demo


@pytest.mark.parametrize("func", [sweep, Scenario.run], ids=["sweep", "Scenario.run"])
def test_the_docs_say_workers_is_still_checked_with_an_executor(func: object) -> None:
    doc = " ".join((inspect.getdoc(func) or "").split())
    assert "executor`` (still checked)" in doc or "is given (still checked)" in doc
    assert "Ignored" not in doc


def test_an_invalid_workers_is_refused_with_an_executor() -> None:
    demo = Demo(map="office", duration=0.2)
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        with pytest.raises(ValueError, match=r"^workers must "):
            sweep(demo, trials=1, seeds=7, workers=0, executor=pool)
        with pytest.raises(ValueError, match=r"^workers must "):
            demo.run(trials=1, seed=7, workers=0, executor=pool)
