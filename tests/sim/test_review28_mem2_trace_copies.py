"""Trace copies each array once (review 28).

``Trace.__post_init__`` copied poses, estimates and commands before checking
them and again to store them read-only: building a trace peaked at 1.34 times
its arrays, and a whole run (whose trace is built from views of the
simulation's buffer) at 2.85 times its trace at 10⁵ steps; now 1.04 and 2.55
(review 29: the run records into the trace's own arrays, 1.3).
"""

from __future__ import annotations

import numpy as np
import pytest

from memory_peak import peak_bytes
from navkit.sim import Event, Metrics, Trace

T = 100_000


def _parts() -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(28)
    times = np.arange(T) / 100.0
    poses = rng.normal(size=(T, 3))
    estimates = rng.normal(size=(T, 3))
    estimates[:10] = np.nan  # before the first estimate
    # Views with strides, as Simulation passes columns of its buffer.
    commands = np.ascontiguousarray(rng.normal(size=(T, 6)))[:, ::2]
    return times, poses, estimates, commands


def _metrics() -> Metrics:
    nan = float("nan")
    return Metrics(False, "timeout", (T - 1) / 100.0, nan, nan, nan, nan, nan, nan, 1.0, 0, 5.0)


def test_a_trace_peaks_at_the_size_of_its_arrays() -> None:
    parts = _parts()
    events = (Event((T - 1) / 100.0, "timeout", "the run hit its duration"),)
    peak, trace = peak_bytes(lambda: Trace(*parts, (), events, _metrics()))
    size = sum(a.nbytes for a in (trace.times, trace.poses, trace.estimates, trace.commands))
    assert peak < 1.15 * size, f"peak {peak / size:.2f} times the trace's arrays"


def test_the_caller_arrays_stay_as_they_were_and_the_trace_owns_copies() -> None:
    parts = _parts()
    kept = [a.copy() for a in parts]
    trace = Trace(*parts, (), (), _metrics())
    for given, stored, copy in zip(
        parts, (trace.times, trace.poses, trace.estimates, trace.commands), kept, strict=True
    ):
        assert given.flags.writeable and not stored.flags.writeable
        assert not np.shares_memory(given, stored)
        np.testing.assert_array_equal(given, copy)
        np.testing.assert_array_equal(stored, copy)
    bad = parts[1].copy()
    bad[5, 1] = np.inf
    with pytest.raises(ValueError, match="poses"):
        Trace(parts[0], bad, parts[2], parts[3], (), (), _metrics())
    assert bad.flags.writeable and bad[5, 1] == np.inf  # untouched on failure too
