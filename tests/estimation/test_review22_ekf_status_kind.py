"""`UpdateResult(status=)` refuses what `FusionStatus` refuses, with the same kind (review 22).

A masked 0-d integer code raised ``TypeError`` from ``UpdateResult`` but
``ValueError`` from ``FusionStatus`` itself; both now raise ``ValueError``, and
``UpdateResult``'s message names ``status``.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.estimation import FusionStatus, UpdateResult

_INT_DTYPES = [np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16, np.uint32, np.uint64]
_REJECTED = [s for s in FusionStatus if s is not FusionStatus.ACCEPTED]


def _kind(call: object, value: object) -> type[BaseException] | None:
    try:
        call(value)  # type: ignore[operator]
    except (TypeError, ValueError) as exc:
        return type(exc)
    return None


def _result(status: object) -> UpdateResult:
    return UpdateResult(False, 0.5, np.array([0.1]), "gated", status)  # type: ignore[arg-type]


@given(st.sampled_from(_REJECTED), st.sampled_from(_INT_DTYPES), st.booleans())
def test_a_masked_code_is_refused_as_fusion_status_refuses_it(
    status: FusionStatus, dtype: type, masked: bool
) -> None:
    value: object = np.ma.array(np.array(int(status), dtype=dtype), mask=masked)
    assert _kind(_result, value) is _kind(FusionStatus, value)
    if masked:
        with pytest.raises(ValueError, match=r"^status has masked entries"):
            _result(value)
    else:  # a masked array without masked entries is its data
        assert _result(value).status is status


@pytest.mark.parametrize(
    "value",
    [np.ma.masked, np.array(True), np.array(2.0), 1.5, "GATED", True, np.array(99), 99, -1],
    ids=repr,
)
def test_other_refused_codes_have_the_kind_fusion_status_gives(value: object) -> None:
    kind = _kind(FusionStatus, value)
    assert kind is not None
    with pytest.raises(kind, match=r"^status "):
        _result(value)
