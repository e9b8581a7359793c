"""``array_objects._layout_ok`` refuses a layout any one of its offsets misreads
(review 44, MUTANT22).

The guard decides whether the kernels may read NumPy's structs directly; on
this NumPy it passes (``test_review35_lead_layout_guard``), but a mutant joining
its checks with ``or`` passed too, so no test showed that each check counts.
Each case points one offset at another real field of the same objects (so
nothing outside them is read) and the guard must then say no.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared import array_objects as ao

pytestmark = pytest.mark.skipif(
    not ao.LAYOUT_OK, reason="NumPy's structs are not laid out as the module reads them"
)

#: Each offset, and one that reads another field of the array (or of its dtype).
WRONG = {
    "_HEAD": ao._HEAD + 8,  # ob_type read from .data
    "_DATA": ao._DESCR,  # .data read from .descr
    "_NDIM": ao._FLAGS,  # .nd read from .flags
    "_DIMS": ao._STRIDES,  # shape[0] read from strides[0] (16)
    "_STRIDES": ao._DIMS,  # strides[1] read from shape[1] (2)
    "_DESCR": ao._DATA,  # .descr read from .data
    "_TYPE_NUM": ao._BYTEORDER - 2,  # type_num read from kind, type, byteorder, ...
    "_BYTEORDER": ao._BYTEORDER - 2,  # byteorder read from kind ('f')
    "_FLAGS": ao._NDIM,  # .flags read from .nd (2)
}


def test_the_offsets_read_this_numpy_right() -> None:
    assert ao._layout_ok()
    assert np.empty((3, 2)).flags.num != 2  # the _FLAGS case below reads 2


@pytest.mark.parametrize("offset", sorted(WRONG))
def test_one_misread_field_fails_the_guard(offset: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every check of the guard counts (mutants: any ``and`` of it made ``or``)."""
    monkeypatch.setattr(ao, offset, WRONG[offset])
    assert not ao._layout_ok()
