"""navkit._shared.deprecation: renamed keywords keep working, with a warning."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from navkit._shared.deprecation import renamed_keyword


def test_new_name_alone_is_returned_without_warning() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert renamed_keyword("old", None, "new", 2.0, 1.0) == 2.0
        assert renamed_keyword("old", None, "new", 1.0, 1.0) == 1.0


def test_old_name_is_used_and_warns_at_the_callers_line() -> None:
    def api(*, new: float = 1.0, old: float | None = None) -> float:
        return renamed_keyword("old", old, "new", new, 1.0)

    with pytest.warns(DeprecationWarning, match="old is deprecated.*use new") as caught:
        assert api(old=3.0) == 3.0
    assert caught[0].filename == __file__


def test_both_names_is_a_type_error() -> None:
    with pytest.raises(TypeError, match="both new and its old name old"):
        renamed_keyword("old", 3.0, "new", 2.0, 1.0)


def test_array_values_compare_without_ambiguity() -> None:
    default = np.array([1.0, 0.0])
    with pytest.warns(DeprecationWarning):
        assert renamed_keyword("old", np.ones(2), "new", default, default) is not None
    with pytest.raises(TypeError, match="both"):
        renamed_keyword("old", np.ones(2), "new", np.zeros(2), default)
