"""Count the noise matrices ExtendedKalmanFilter validates in Python (test helper)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import navkit.estimation._ekf as ekf_module
from navkit.estimation._covariance import covariance

Array = np.ndarray[Any, np.dtype[np.float64]]


def counting(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """Record the name of every matrix the public layer validates in Python."""
    seen: list[str] = []

    def counted(value: Any, name: str, n: int, *, semidefinite: bool = False) -> Array:
        seen.append(name)
        return covariance(value, name, n, semidefinite=semidefinite)

    monkeypatch.setattr(ekf_module, "covariance", counted)
    return seen
