"""navkit warmup compiles the EKF's gated-retry check too (review 28).

The check of S a gated update's retry runs (a kernel of its own since review
28, compiled at the first gated update of two or more components) was left
to the first such update in a program that had run ``warmup``.
"""

from __future__ import annotations

from kernel_signatures import compiled_signatures


def test_warmup_of_the_estimation_step_compiles_the_gated_retry_check() -> None:
    setup = "from navkit.sim import warmup\nwarmup(workers=1, only=['estimation'])\n"
    signatures = compiled_signatures(setup, ["navkit.estimation._ekf_kernels"])
    assert signatures.get("_ekf_kernels.gated_s_ill"), sorted(signatures)
