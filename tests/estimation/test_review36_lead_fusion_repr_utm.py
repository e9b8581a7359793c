"""PlanarFusion's repr shows its state as Python writes floats (review 36, lead).

The repr rounded the state to four significant digits in NumPy's scientific
format, so a robot in a UTM frame showed ``x=[ 5.1235e+05  4.6123e+06 ...]``,
its position to 50 m (found by review 36's long-run lens, LONGRUN). It now
writes each component as ``repr(float)`` does, as ``Pose2D``'s repr and the
odometries' do: the shortest text that reads back as the same float.
Checked: fails against ``_fusion.py`` before the change.
"""

from __future__ import annotations

import re

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from navkit.estimation import PlanarFusion

finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e7, max_value=1e7)


def _state_in_repr(text: str) -> list[float]:
    match = re.fullmatch(r"PlanarFusion\(t=(.*), x=\[(.*)\]\)", text)
    assert match is not None, text
    return [float(v) for v in match.group(2).split(", ")]


def test_a_utm_position_reads_back_exactly() -> None:
    x0 = [512345.123456789, 4612345.98765, 0.3, 1e-6, -2.5e-9, 0.0]
    fusion = PlanarFusion(x0, t0=1_733_400_000.25)
    text = repr(fusion)
    assert text.startswith("PlanarFusion(t=1733400000.25, x=[512345.123456789, 4612345.98765, ")
    assert _state_in_repr(text) == x0


@given(st.lists(finite, min_size=6, max_size=6))
def test_every_state_reads_back_as_the_same_floats(x0: list[float]) -> None:
    fusion = PlanarFusion(x0)
    assert np.array_equal(_state_in_repr(repr(fusion)), fusion.x)


def test_a_log_fused_in_pieces_ends_where_the_whole_log_does() -> None:
    """update_batch's docstring: a long log may be fused in pieces, same final state."""
    from navkit.estimation import MeasurementLog

    rng = np.random.default_rng(36)
    t = np.arange(1, 301) * 0.01
    log = MeasurementLog.from_streams(
        odometry=(t, 1 + 0.1 * rng.standard_normal(300), 0.2 * rng.standard_normal(300)),
        yaw=(t[::5] + 0.001, 0.01 * rng.standard_normal(60)),
    )
    whole = PlanarFusion(t0=0.0)
    expected = whole.update_batch(log)
    pieces = PlanarFusion(t0=0.0)
    states = []
    for i, j in ((0, 1), (1, 97), (97, 250), (250, len(log))):
        part = MeasurementLog(
            log.times[i:j], log.values[i:j], log.variances[i:j], log.observed[i:j]
        )
        states.append(pieces.update_batch(part).states)
    assert np.array_equal(np.concatenate(states), expected.states)
    assert np.array_equal(pieces.x, whole.x)
    assert np.array_equal(pieces.P, whole.P)
