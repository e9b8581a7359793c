"""ScanMapper's resolution message states the bound that refuses it (review 30).

Before, ``resolution=1e-7`` was refused as below a grid's 1e-6 m, and 1e-6 m,
the bound that message gave, was then refused as below the mapper's 1e-3 m.
"""

from __future__ import annotations

import pytest

from navkit.mapping import ScanMapper


@pytest.mark.parametrize("resolution", [1e-7, 1e-6, 5e-4, 2e6])
def test_one_message_names_the_mappers_own_bounds(resolution: float) -> None:
    with pytest.raises(ValueError, match=r"resolution must be >= 0\.001 and <= 1e6 m"):
        ScanMapper(resolution=resolution)


def test_the_lower_bound_itself_is_accepted() -> None:
    assert ScanMapper(resolution=1e-3).map.resolution == 1e-3
    assert ScanMapper(resolution=0.3).map.resolution == 0.3
