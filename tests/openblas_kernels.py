"""OpenBLAS's kernels this CPU can run, for tests comparing results across them (review 34).

A test runs a probe in fresh processes with ``OPENBLAS_CORETYPE`` set to each
(OpenBLAS reads it once, when NumPy loads it) and compares the results.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path


def has_avx512() -> bool:
    """Whether this CPU runs AVX-512 code (OpenBLAS's SkylakeX kernels and newer)."""
    cpuinfo = Path("/proc/cpuinfo")
    return cpuinfo.exists() and "avx512f" in cpuinfo.read_text().split()


def core_types(
    older: Sequence[str] = ("Haswell", "Sandybridge"), avx512: Sequence[str] = ("SkylakeX",)
) -> list[str]:
    """The ``older`` kernels, and the ``avx512`` ones where the CPU can run them."""
    return [*older, *(avx512 if has_avx512() else ())]
