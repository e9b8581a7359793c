"""The scenarios give the same trials under every BLAS kernel and NumPy SIMD level (review 34).

A run of the same seed must not depend on the CPU it runs on. On a recent
Intel Xeon (AVX-512) OpenBLAS and NumPy pick other kernels than on the older
CPUs that made the docs' figures; a BLAS product in the simulator's wheel
odometry made the ``demo`` estimate differ there in its last bits. Each probe
here runs in a fresh process under one choice (``OPENBLAS_CORETYPE``, and NumPy's
AVX-512 loops switched off with ``NPY_DISABLE_CPU_FEATURES``) and digests every
trial's values and trace: all must agree. (``omni-apf`` and ``soccer`` are left
out: ``OmniDrive``'s LAPACK pseudo-inverse, documented in the simulation guide's
"Reproducibility across machines", differs between kernels.)
"""

from __future__ import annotations

import json

import pytest

from openblas_kernels import has_avx512
from subprocess_probe import probe_outcome

_PROBE = """
import hashlib, json, sys
import numpy as np
from navkit.sim.scenarios import SCENARIOS
digest = hashlib.sha256()
result = SCENARIOS[sys.argv[1]]().run(seed=0, workers=None)
for trial in result.trials:
    for key, value in sorted(trial.values.items()):
        if "wall" not in key and "ms" not in key:
            digest.update(f"{key}={float(value).hex()};".encode())
    trace = trial.trace
    if trace is not None:
        for arr in (trace.times, trace.poses, trace.estimates, trace.commands):
            digest.update(np.ascontiguousarray(arr).tobytes())
print(json.dumps(digest.hexdigest()))
"""

_NO_AVX512 = "AVX512_SPR AVX512_ICL X86_V4"


def _settings() -> dict[str, dict[str, str]]:
    settings = {
        "Haswell": {"OPENBLAS_CORETYPE": "Haswell"},
        "Sandybridge": {"OPENBLAS_CORETYPE": "Sandybridge"},
        "Haswell, NumPy without AVX-512": {
            "OPENBLAS_CORETYPE": "Haswell",
            "NPY_DISABLE_CPU_FEATURES": _NO_AVX512,
        },
    }
    if has_avx512():
        settings["SkylakeX"] = {"OPENBLAS_CORETYPE": "SkylakeX"}
    return settings


@pytest.mark.slow
@pytest.mark.parametrize("name", ["demo", "greedy"])
def test_every_trial_is_the_same_under_every_kernel(
    name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    digests = {}
    for label, env in _settings().items():
        monkeypatch.delenv("NPY_DISABLE_CPU_FEATURES", raising=False)
        for key, value in env.items():
            monkeypatch.setenv(key, value)
        digests[label] = probe_outcome(_PROBE, name, timeout=600)
    assert len(set(digests.values())) == 1, json.dumps(digests, indent=1)
