"""Fuzz every public callable of navkit with hostile arguments (issue 12).

Every name in the ``__all__`` of every public (sub)package and module — found by
walking ``src/navkit``, so a new subpackage or name is included — must have a
fuzz spec in ``fuzz_specs.py`` (``test_every_public_callable_has_a_spec`` fails
otherwise; see that file's docstring for how to add one). For each spec, one
argument at a time, anywhere in the call tree (the receiver's constructor and
lazily built navkit arguments included), is replaced:

1. by every value of its kind's hostile catalogue (``fuzz_engine``), in order —
   the catalogue is finite, so all of it runs every time;
2. then by values hypothesis generates (any float or huge int, arrays of random
   dtype and shape, a valid array with one element replaced...), hypothesis also
   choosing the argument, with a fixed profile (derandomized, no database) so CI
   runs the same cases every time.

``fuzz_engine.run_case`` checks navkit's promise for each call (see its
docstring). Failures are collected for the whole spec and reported together.
``test_hostile_arguments_thoroughly`` (marked ``slow``) generates 100
values per argument (about 1.5 minutes).

Set ``NAVKIT_FUZZ_REPORT=path`` to append every failure line to a file, and
``NAVKIT_FUZZ_GENERATED=n`` to change the number of generated values per argument.
Set ``NAVKIT_FUZZ_SEED=n`` (an integer) to draw other generated values: derandomize
off, hypothesis seeded with ``n`` (every spec the same seed, as the fixed profile
gives every spec the same stream), so a failure repeats with the same ``n`` and the
same hypothesis version; its report names the seed. Unset or empty, the fixed
profile runs. For example, one spec, a fresh seed each time::

    NAVKIT_FUZZ_SEED=$RANDOM python -m pytest -p no:cacheprovider \
        tests/fuzz/test_public_api_fuzz.py -k "test_hostile_arguments and sample_field"
"""

from __future__ import annotations

import math
import os
import shutil
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

import fuzz_specs  # noqa: F401 - registers the specs
import numpy as np
import pytest
from fuzz_engine import (
    NOT_FUZZED,
    SPECS,
    Case,
    Ctx,
    Failure,
    Hostile,
    Spec,
    call,
    cases_for,
    generated_strategy,
    method,
    public_callables,
    public_modules,
    quiet,
    refresh_memory_limit,
    run_case,
    slots,
)
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st
from numpy.typing import ArrayLike

# One fixed profile: no example database, derandomized, so CI runs the same cases every time.
FIXED = settings(
    database=None,
    derandomize=True,
    deadline=None,
    phases=[Phase.generate],
    suppress_health_check=list(HealthCheck),
    max_examples=10_000,  # overridden per test
)
_Test = TypeVar("_Test", bound=Callable[..., None])


def fuzz_seed() -> int | None:
    """``NAVKIT_FUZZ_SEED`` as an int, or None (the fixed profile) when unset or empty."""
    text = os.environ.get("NAVKIT_FUZZ_SEED", "").strip()
    if not text:
        return None
    try:
        return int(text)
    except ValueError:
        raise ValueError(f"NAVKIT_FUZZ_SEED must be an integer, got {text!r}") from None


def profile(draw_seed: int | None, max_examples: int) -> Callable[[_Test], _Test]:
    """Decorate a ``@given`` test: the fixed profile (None), or that seed, not derandomized."""

    def apply(test: _Test) -> _Test:
        if draw_seed is None:
            return settings(FIXED, max_examples=max_examples)(test)
        seeded = settings(FIXED, derandomize=False, max_examples=max_examples)(test)
        return seed(draw_seed)(seeded)

    return apply


FUZZ_SEED = fuzz_seed()
GENERATED_EXAMPLES = int(os.environ.get("NAVKIT_FUZZ_GENERATED", "3"))  # per argument
GENERATED_EXAMPLES_SLOW = 100
WARM_UP_TIMEOUT_S = 600.0


@pytest.fixture(autouse=True)
def _in_a_scratch_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Run in an empty folder: a hostile relative path never lands in the checkout."""
    monkeypatch.chdir(tmp_path)


def _report(failures: list[Failure]) -> None:
    path = os.environ.get("NAVKIT_FUZZ_REPORT")
    if path and failures:
        with open(path, "a", encoding="utf-8") as f:
            for failure in failures:
                f.write(failure.line + "\n")


def _fuzz(name: str, generated: int) -> list[Failure]:
    spec = SPECS[name]
    cases = cases_for(spec)
    root = Path(tempfile.mkdtemp(prefix="navkit-fuzz-"))
    found: dict[tuple[str, str], Failure] = {}
    try:
        _run_all(spec, cases, root, generated, found)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    failures = list(found.values())
    _report(failures)
    return failures


def _run_all(
    spec: Spec, cases: list[Case], root: Path, generated: int, found: dict[tuple[str, str], Failure]
) -> None:
    def record(failures: list[Failure]) -> None:
        for f in failures:
            found.setdefault((f.case, f.problem), f)

    refresh_memory_limit()
    with quiet():
        # The valid call first, with time to compile numba kernels (never a "hang").
        record(run_case(spec, cases[0], root, timeout=WARM_UP_TIMEOUT_S))

        # The catalogue is finite: every case, in order. (Letting hypothesis draw them
        # would cost 0.6 ms per case and add none; it generates the values below.)
        for case in cases[1:]:
            record(run_case(spec, case, root))

        tree = spec.make(Ctx(root))
        targets = []
        for slot, kind, value, nested in slots(tree):
            strategy = None if nested else generated_strategy(kind, value)
            if strategy is not None:
                targets.append((slot, kind, strategy))
        if targets and generated:

            @profile(FUZZ_SEED, generated * len(targets))
            @given(st.data())
            def generated_values(data: st.DataObject) -> None:
                slot, kind, strategy = data.draw(st.sampled_from(targets), label="slot")
                value = data.draw(strategy, label=str(slot))
                label = " ".join(repr(value).split())  # one line, whatever the repr
                hostile = Hostile(
                    f"generated {label:.80}",
                    lambda _v, _c, x=value: x.copy() if isinstance(x, np.ndarray) else x,
                )
                record(run_case(spec, Case(slot, hostile, kind), root))

            generated_values()


def _explain(failures: list[Failure]) -> str:
    drawn = "" if FUZZ_SEED is None else f" (generated with NAVKIT_FUZZ_SEED={FUZZ_SEED})"
    lines = [f"{len(failures)} broken promise(s){drawn}:"]
    lines += [f"  {f.call}\n      -> {f.problem}   [{f.case}]" for f in failures[:60]]
    if len(failures) > 60:
        lines.append(f"  ... and {len(failures) - 60} more")
    return "\n".join(lines)


def test_public_packages_are_found() -> None:
    found = set(public_modules())
    for name in (
        "navkit",
        "navkit.errors",
        "navkit.geometry",
        "navkit.kinematics",
        "navkit.mapping",
        "navkit.mapping.io",
        "navkit.estimation",
        "navkit.planning",
        "navkit.planning.grid",
        "navkit.planning.reactive",
        "navkit.control",
        "navkit.behaviours",
    ):
        assert name in found


def test_every_public_callable_has_a_spec() -> None:
    """A new public function, class or method fails here until it gets a spec."""
    names = {c.name for c in public_callables()}
    abstract = {c.name for c in public_callables() if c.abstract}
    missing = sorted(n for n in names - abstract if n not in SPECS and n not in NOT_FUZZED)
    stale = sorted(n for n in set(SPECS) | set(NOT_FUZZED) if n not in names)
    assert not missing, (
        "public callables without a fuzz spec (add them to fuzz_specs.py):\n  "
        + "\n  ".join(missing)
    )
    assert not stale, "fuzz specs of names that are not public (any more):\n  " + "\n  ".join(stale)


@pytest.mark.parametrize("name", sorted(SPECS))
def test_every_parameter_has_a_kind(name: str, tmp_path: Path) -> None:
    """Each parameter of each spec's call tree has a kind (explicit or from its annotation)."""
    tree = SPECS[name].make(Ctx(tmp_path))
    found = {str(slot) for slot, *_ in slots(tree)}
    params = {p.name for p in tree.parameters()}
    missing = sorted(p for p in params if p not in found)
    assert not missing, f"{name}: no kind for {missing}; give kinds= in its spec"


@pytest.mark.parametrize("name", sorted(SPECS))
def test_hostile_arguments(name: str) -> None:
    failures = _fuzz(name, GENERATED_EXAMPLES)
    assert not failures, _explain(failures)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(SPECS))
def test_hostile_arguments_thoroughly(name: str) -> None:
    failures = _fuzz(name, GENERATED_EXAMPLES_SLOW)
    assert not failures, _explain(failures)


# --------------------------------------------------------------------------- the fuzzer itself


def _modifies_its_input(points: ArrayLike) -> float:
    arr = np.asarray(points)
    if arr.dtype == np.float64 and arr.flags.writeable and arr.size:
        arr.flat[0] = 0.0
    return 1.0


def _nan_for_huge_values(x: float) -> float:
    if isinstance(x, str):
        return float(x)  # a numeric string slips through
    if not isinstance(x, (int, float)) or isinstance(x, bool):
        return x.real.missing  # type: ignore[attr-defined, no-any-return]  # AttributeError
    return math.inf - math.inf if abs(x) > 1e300 else float(x)


def _flag(x: float, *, fast: bool = False) -> float:
    return float(x) * (2.0 if fast else 1.0)


class _Counter:
    """Counts calls, even those it then refuses."""

    __module__ = "navkit._selftest"  # the fuzzer compares navkit objects by their public state

    def __init__(self) -> None:
        self.calls = 0

    def step(self, dt: float) -> float:
        self.calls += 1
        if not isinstance(dt, float) or dt <= 0.0:
            raise ValueError("dt must be a positive float")
        return dt


@pytest.mark.parametrize(
    ("spec", "problem"),
    [
        (
            Spec("selftest.modifies", lambda c: call(_modifies_its_input, np.ones(3))),
            "modified its input points",
        ),
        (Spec("selftest.nan", lambda c: call(_nan_for_huge_values, 2.0)), "NaN in the output"),
        (
            Spec("selftest.attr", lambda c: call(_nan_for_huge_values, 2.0)),
            "builtins.AttributeError",
        ),
        (Spec("selftest.str", lambda c: call(_nan_for_huge_values, 2.0)), "accepted a str"),
        (Spec("selftest.flag", lambda c: call(_flag, 2.0)), "for a bool"),
        (
            Spec("selftest.state", lambda c: method(call(_Counter), "step", 0.1)),
            "a failed call changed the receiver's public state",
        ),
    ],
    ids=lambda v: v.name if isinstance(v, Spec) else "",
)
def test_the_fuzzer_sees_broken_promises(spec: Spec, problem: str, tmp_path: Path) -> None:
    with quiet():
        found = [f.problem for case in cases_for(spec) for f in run_case(spec, case, tmp_path)]
    assert any(problem in p for p in found), f"{spec.name}: no {problem!r} among {found[:5]}"
