"""Test doubles that misreport their class, shared by the type-check tests."""

from __future__ import annotations

from typing import Any

import numpy as np


class Liar:
    """A wrapper whose ``__class__`` says ``np.ndarray``; NumPy reads it through ``__array__``."""

    def __init__(self, data: Any) -> None:
        self._data = np.asarray(data)

    @property  # type: ignore[misc]
    def __class__(self) -> type:
        return np.ndarray

    def __array__(self, dtype: Any = None, copy: bool | None = None) -> np.ndarray:
        return np.array(self._data, dtype=dtype, copy=True)

    def __repr__(self) -> str:
        return "Liar()"
