"""The CLI's compile-time notice counts the distance transform's kernel (review 46).

``navkit plan`` and ``navkit run`` say about how long compiling their kernels
takes on a cold cache: one measured number per kind of work
(``navkit.cli._kernels.KERNELS``). Since review 45 every costmap runs navkit's
own exact distance transform (a kernel compiled on first use, about 0.5 s);
the numbers predated it. They are now the kind's own kernels plus the
transform's, re-measured.
"""

from __future__ import annotations

import pytest

from navkit._shared.jit import load_numba
from navkit.cli import _kernels, _plan


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_a_plans_warm_up_runs_the_distance_transform(planner: str) -> None:
    # What the plan command compiles before its timed plan includes the
    # transform: its notice must count it.
    load_numba()
    from navkit.mapping import _edt_kernels

    calls: list[int] = []
    kernel = _edt_kernels.band_distances

    def counted(*args: object) -> None:
        calls.append(len(args))
        kernel(*args)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr("navkit.mapping._obstacle_distance.band_distances", counted)
        _plan._warm_up(0.05, 0.3, planner)  # type: ignore[arg-type]
    assert calls


def test_every_estimate_counts_the_distance_transform() -> None:
    part = _kernels._DISTANCE_TRANSFORM
    assert 0.0 < part < 2.0
    for (_, module, _), seconds in _kernels.KERNELS.values():
        assert seconds > part, module
