"""An old PlanarFusion subclass pickle reports its new steps' residuals (review 53, MUTANT33).

7177aaa restores what a subclass added to an old pickle (before 1efa428),
every slot but the filter's own of then (``_OLD_SLOTS``). Its tests compared
the loaded filter's estimate only: mutants leaving ``_residuals`` or
``_odometry_residual`` out of the old slots passed them, and restored those
arrays over today's, views of the filter's buffer that the kernels write, so
that every later result reported the residual of the release's last step.
"""

from __future__ import annotations

import base64
import pickle
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import PlanarFusion

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_review52_lead_fusion_subclass_old_pickles import MODULE, OLD, SUBCLASSES

from old_release import install_module


@pytest.mark.parametrize("commit", sorted(OLD))
def test_an_old_subclass_pickle_reports_its_new_residuals(
    commit: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    install_module(monkeypatch, MODULE, SUBCLASSES)
    for text in OLD[commit]:
        loaded = pickle.loads(zlib.decompress(base64.b64decode("".join(text))))
        fresh = PlanarFusion(t0=0.0)
        fresh.update_odometry(0.1, 0.5, 0.1, v_variance=0.01, omega_variance=0.01)
        got = loaded.update_odometry(0.2, 0.7, -0.2, v_variance=0.01, omega_variance=0.01)
        want = fresh.update_odometry(0.2, 0.7, -0.2, v_variance=0.01, omega_variance=0.01)
        assert got.residual is not None and want.residual is not None
        np.testing.assert_allclose(got.residual, want.residual, rtol=0, atol=1e-12)
        got = loaded.update_yaw(0.3, 0.05, variance=1e-3)
        want = fresh.update_yaw(0.3, 0.05, variance=1e-3)
        assert got.residual is not None and want.residual is not None
        np.testing.assert_allclose(got.residual, want.residual, rtol=0, atol=1e-12)
        if hasattr(loaded, "__dict__"):  # Named: its own attribute, and nothing of then
            assert vars(loaded) == {"name": "left"}
