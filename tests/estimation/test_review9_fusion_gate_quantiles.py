"""PlanarFusion's gates are the chi-square quantiles, computed without scipy.stats.

``scipy.stats`` costs about 0.7 s to import on first use; the quantile is
``2 * gammaincinv(k / 2, p)``, what ``scipy.stats.chi2.ppf`` computes.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from scipy.stats import chi2

from navkit.estimation import PlanarFusion


@pytest.mark.parametrize("probability", [1e-9, 0.5, 0.95, 0.997, 1.0 - 1e-12])
def test_gates_are_the_chi_square_quantiles(probability: float) -> None:
    fusion = PlanarFusion(gate_probability=probability)
    gates = np.asarray(fusion._gates)
    assert gates[0] == np.inf
    np.testing.assert_array_equal(gates[1:], chi2.ppf(probability, np.arange(1, 5)))


def test_gated_fusion_does_not_import_scipy_stats() -> None:
    code = (
        "import sys\n"
        "from navkit.estimation import PlanarFusion\n"
        "PlanarFusion(gate_probability=0.99)\n"
        "print('scipy.stats' in sys.modules)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    assert out.stdout.strip() == "False"
