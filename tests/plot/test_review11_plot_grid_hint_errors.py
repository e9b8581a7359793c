"""plot_grid's TypeError hint must not let the caller's object raise something else.

Looking for a ``.map`` to suggest ("pass its map") read the attribute of
whatever was passed: a property failing there escaped plot_grid as its own
error instead of the TypeError for a wrong ``grid``.
"""

from __future__ import annotations

import pytest

from navkit.plot import plot_grid

pytest.importorskip("matplotlib")


class _Failing:
    def __init__(self, error: Exception) -> None:
        self._error = error

    @property
    def map(self) -> object:
        raise self._error


@pytest.mark.parametrize(
    "error", [RuntimeError("not ready"), ValueError("no scans"), KeyError("map"), MemoryError()]
)
def test_a_failing_map_property_still_gives_the_type_error(error: Exception) -> None:
    expected = r"^grid must be a navkit\.mapping\.OccupancyGrid, got _Failing$"
    with pytest.raises(TypeError, match=expected):
        plot_grid(_Failing(error))  # type: ignore[arg-type]


def test_a_map_that_is_not_a_grid_gives_no_hint() -> None:
    class Other:
        map = (1, 2)

    with pytest.raises(TypeError, match=r"got Other$"):
        plot_grid(Other())  # type: ignore[arg-type]
