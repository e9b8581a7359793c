"""Error messages name the argument the caller wrote (review 8, session 12).

The public-API fuzz test (``test_public_api_fuzz.py``) checks that a value plainly
wrong for an argument's kind is refused with ``ValueError``/``TypeError``/a
``navkit.errors`` class. This test checks the rest of the standard — "a clear
exception naming the argument and the problem" — on the same cases: when the
fuzz engine replaces one argument of a spec's call tree by a value its kind
says must be refused and navkit refuses it, the message must contain the name
the caller wrote for that value:

* the parameter's name in the public signature, when the call that takes the
  value refused it (``Pose2D(x=nan)`` must say ``x``);
* when a navkit object built from it was accepted by its own constructor but
  refused by an outer call, the name of the outer call's parameter that
  received the object (``plan(start=Pose2D(1e308, 0, 0))`` must say
  ``start``); for a receiver built from it (``self``), any name on the way;
* for a path argument, the path itself also names it (``No such file: 'x.yaml'``);
  a helper told the name to use (``as_pose(value, name="start")``) may use it, and
  an enum's value lookup may be named by its class (``7 is not a valid FusionStatus``).

Not checked: values navkit only calls (a class given as a callback: the error is
the callback's own) and well-typed paths to malformed files (their messages name
the file and the fault).

The engine tells which nested call refused (``fuzz_engine.raised_at``). Names are
matched as whole words (``x`` is not found in ``expected``), so a message that
names an internal variable (``points`` for ``waypoints``, ``value``) fails.

``test_messages_name_the_argument`` runs a fixed sample of each spec's
catalogue (a few seconds in all); ``test_messages_name_the_argument_thoroughly``
(``slow``) runs all of it. ``KNOWN`` lists the (callable, argument) pairs that
fail in files this review could not change, one strict xfail each over that
argument's whole catalogue: fixing one makes it XPASS, which fails and says to
remove it from the list.

Set ``NAVKIT_MESSAGE_REPORT=path`` to write every failure (with the file and
line that made the message) to a file.
"""

from __future__ import annotations

import enum
import math
import os
import re
import shutil
import tempfile
import traceback
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import fuzz_specs  # noqa: F401 - registers the specs
import numpy as np
import pytest
from fuzz_engine import (
    CALL_TIMEOUT_S,
    OPERATORS,
    SKIP,
    SPECS,
    Call,
    Case,
    Ctx,
    FileKind,
    Function,
    Hang,
    MatrixOrFunction,
    OutPath,
    Spec,
    _value_at,
    allowed_error,
    call,
    cases_for,
    materialize,
    memory_limit,
    quiet,
    raised_at,
    refresh_memory_limit,
    replace,
    short,
    tags_of,
    watchdog,
)

import navkit
from navkit.errors import DataNotFoundError

SRC = Path(navkit.__file__).resolve().parent
WARM_UP_TIMEOUT_S = 600.0

#: The hostile values of the default (fast) sample: for each kind, the commonest
#: ways a caller gets an argument plainly wrong. The slow test tries the whole catalogue.
SAMPLE = frozenset(
    {
        "None",
        "'abc'",
        "nan",
        "1+1j",
        "as complex",
        "ragged list",
        "a Twist2D",
        "[nan, 0, 0]",
        "(1.5, 0)",
        "'nope'",
        "[None]",
        "3.0",
    }
)
SAMPLE_PER_ARGUMENT = 3  # at most, in catalogue order


@dataclass(frozen=True)
class Verdict:
    """What navkit said when it refused a hostile value."""

    spec: str
    case: str
    call: str
    value: str
    names: tuple[str, ...]  # any of these in the message names the argument
    error: str
    message: str
    made_at: str  # file:line of the raise (and of the caller of a shared helper)
    ok: bool

    @property
    def line(self) -> str:
        want = " or ".join(repr(n) for n in self.names)
        return (
            f"{self.spec} [{self.case}]: {self.error}: {self.message!r} "
            f"does not name {want}   (made at {self.made_at})"
        )


def _names_word(name: str, message: str) -> bool:
    """Whether ``name`` appears in ``message`` as a whole identifier (or option ``--name``)."""
    spellings = {name, name.replace("_", "-")}
    return any(
        re.search(rf"(?<![A-Za-z0-9_]){re.escape(s)}(?![A-Za-z0-9_])", message)
        for s in spellings
    )


def expected_names(slot: tuple[str, ...], refused_by: tuple[str, ...]) -> tuple[str, ...]:
    """The names the caller wrote for the value at ``slot``, given which call refused it.

    ``refused_by`` is the path of the refusing call (``()`` the outer call). The
    value is a parameter of the call at ``slot[:-1]``; a call on the way down
    refused the object built from it, received as its parameter ``slot[len(refused_by)]``.
    """
    if refused_by == slot[:-1]:
        return (slot[-1],)
    depth = len(refused_by)
    if slot[:depth] != refused_by:  # not on the value's way: nothing to check against
        return ()
    if slot[depth] == "self":  # refused because of the receiver's state
        return tuple(n for n in slot[depth + 1 :] if n != "self")
    return (slot[depth],)


def _call_at(tree: Call, path: tuple[str, ...]) -> Call | None:
    """The nested call at ``path`` (as :func:`fuzz_engine.materialize` names them)."""
    c: Any = tree
    for part in path:
        if not isinstance(c, Call):
            return None
        c = c.target if part == "self" else c.arguments.get(part)
    return c if isinstance(c, Call) else None


def _names_given(c: Call | None) -> tuple[str, ...]:
    """Other names a refusing call may use: the one it was told, or its enum's.

    A helper such as ``as_pose(value, name="pose")`` takes the name to put in its
    messages; an enum's value lookup ``FusionStatus(7)`` is named by its class
    (as Python's own ``7 is not a valid FusionStatus``).
    """
    if c is None:
        return ()
    out: tuple[str, ...] = ()
    param = next((p for p in c.parameters() if p.name == "name"), None)
    if param is not None and isinstance(c.value_of(param), str):
        out += (c.value_of(param),)
    if c.method is None and isinstance(c.target, type) and issubclass(c.target, enum.Enum):
        out += (c.target.__name__,)
    return out


def _made_at(exc: BaseException) -> str:
    """``file:line`` of the navkit frame that raised (and its caller for a shared helper)."""
    frames = [
        f
        for f in traceback.extract_tb(exc.__traceback__)
        if Path(f.filename).resolve().is_relative_to(SRC)
    ]
    if not frames:
        return "?"

    def where(f: traceback.FrameSummary) -> str:
        return f"{Path(f.filename).resolve().relative_to(SRC.parent)}:{f.lineno}"

    text = where(frames[-1])
    helpers = [f for f in frames if "/_shared/validation.py" not in f.filename]
    if "/_shared/validation.py" in frames[-1].filename and helpers:
        text += f" (called from {where(helpers[-1])})"
    return text


def probe(s: Spec, case: Case, root: Path, *, timeout: float = CALL_TIMEOUT_S) -> Verdict | None:
    """Run one hostile case; a verdict when navkit refused a value its kind must refuse.

    None when the case does not apply: the value is not plainly wrong, navkit
    accepted it or raised a type the fuzz test already reports, or the call hung.
    """
    if case.slot is None or case.hostile is None or case.kind is None or s.expect_error:
        return None
    ctx = Ctx(root)
    try:
        return _probe(s, case, ctx, timeout)
    finally:
        if ctx.used:
            shutil.rmtree(ctx.tmp, ignore_errors=True)


def _probe(s: Spec, case: Case, ctx: Ctx, timeout: float) -> Verdict | None:
    assert case.slot is not None and case.hostile is not None and case.kind is not None
    tree = s.make(ctx)
    path = case.slot.path
    with np.errstate(all="ignore"):
        value = case.hostile.make(_value_at(tree, path), ctx)
    if value is SKIP:
        return None
    why = case.kind.must_reject(value, tags_of(value) | set(case.hostile.tags))
    if why is None and not case.hostile.must_reject:
        return None
    if "malformed" in case.hostile.tags:
        return None  # a well-typed path to a file whose contents are wrong
    if isinstance(case.kind, (Function, MatrixOrFunction)) and callable(value):
        return None  # navkit calls it: what it raises is the caller's own code's message
    replace(tree, path, value)
    error: Exception | None = None
    with np.errstate(all="ignore"), memory_limit(), watchdog(timeout):
        try:
            receiver = None
            if tree.method is not None:
                receiver = materialize(tree.target, [], "self.")
                if tree.prepare is not None:
                    tree.prepare(receiver)
            args = {k: materialize(v, [], f"{k}.") for k, v in tree.arguments.items()}
            result = tree.invoke(receiver, args)
        except Hang:
            return None
        except Exception as exc:
            error = exc
    if error is None:
        if result is NotImplemented and tree.method in OPERATORS:
            return None  # Python's own "unsupported operand" TypeError: not navkit's message
        return None
    extra = case.kind.allowed_errors
    if not allowed_error(error, extra):
        return None  # the fuzz test reports the type
    refused_by = raised_at(error)
    names = expected_names(path, refused_by)
    if not names:
        return None
    names += _names_given(_call_at(tree, refused_by))
    message = str(error)
    ok = any(_names_word(n, message) for n in names)
    if not ok and isinstance(case.kind, (FileKind, OutPath)) and isinstance(value, (str, Path)):
        ok = bool(str(value)) and (str(value) in message or Path(value).name in message)
    if not ok and isinstance(error, FileNotFoundError) and error.filename is not None:
        ok = True  # the OS names the path the caller gave
    if not ok and isinstance(error, (FileNotFoundError, DataNotFoundError)):
        ok = isinstance(value, str) and bool(value) and value in message
    return Verdict(
        spec=s.name,
        case=case.label,
        call="" if ok else tree.render(),  # rendering costs: only for reports
        value=short(value),
        names=names,
        error=type(error).__name__,
        message=" ".join(message.split())[:300],
        made_at="" if ok else _made_at(error),
        ok=ok,
    )


def message_cases(s: Spec, *, sample: bool) -> list[Case]:
    """A spec's hostile cases (if ``sample``, a few of the sample's per argument)."""
    cases = [c for c in cases_for(s) if c.hostile is not None]
    if not sample:
        return cases
    out = []
    per_slot: dict[str, int] = {}
    for c in cases:
        assert c.hostile is not None
        if c.hostile.label in SAMPLE and per_slot.get(str(c.slot), 0) < SAMPLE_PER_ARGUMENT:
            per_slot[str(c.slot)] = per_slot.get(str(c.slot), 0) + 1
            out.append(c)
    return out


#: (callable, argument) pairs whose messages name no argument the caller wrote,
#: in files this review may not change, with where the message is made (details:
#: ``/work/helpers/s12/out/e1_failures.md``). Each runs as a strict xfail.
KNOWN: dict[tuple[str, str], str] = {}


def _known(name: str, case: Case) -> bool:
    return case.slot is not None and (name, str(case.slot)) in KNOWN


def verdicts(
    name: str, *, sample: bool, known: bool | None = False, slot: str | None = None
) -> Iterator[Verdict]:
    """Verdicts of a spec's cases: ``known`` False skips the ``KNOWN`` slots, True keeps
    only them, None runs both; ``slot`` keeps one argument's cases."""
    s = SPECS[name]
    root = Path(tempfile.mkdtemp(prefix="navkit-messages-"))
    refresh_memory_limit()
    try:
        with quiet():
            first = True
            for case in message_cases(s, sample=sample):
                if known is not None and _known(name, case) != known:
                    continue
                if slot is not None and str(case.slot) != slot:
                    continue
                v = probe(s, case, root, timeout=WARM_UP_TIMEOUT_S if first else CALL_TIMEOUT_S)
                first = False
                if v is not None:
                    yield v
    finally:
        shutil.rmtree(root, ignore_errors=True)


def _report(bad: list[Verdict]) -> None:
    path = os.environ.get("NAVKIT_MESSAGE_REPORT")
    if path and bad:
        with open(path, "a", encoding="utf-8") as f:
            for v in bad:
                f.write(f"{v.line}\n    {v.call}\n")


def _explain(bad: list[Verdict]) -> str:
    lines = [f"{len(bad)} message(s) do not name the argument:"]
    lines += [f"  {v.line}" for v in bad[:40]]
    return "\n".join(lines)


@pytest.fixture(autouse=True)
def _in_a_scratch_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Run in an empty folder: a hostile relative path never lands in the checkout."""
    monkeypatch.chdir(tmp_path)


@pytest.mark.parametrize("name", sorted(SPECS))
def test_messages_name_the_argument(name: str) -> None:
    bad = [v for v in verdicts(name, sample=True) if not v.ok]
    _report(bad)
    assert not bad, _explain(bad)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(SPECS))
def test_messages_name_the_argument_thoroughly(name: str) -> None:
    bad = [v for v in verdicts(name, sample=False) if not v.ok]
    _report(bad)
    assert not bad, _explain(bad)


if KNOWN:  # an empty ledger parametrized over nothing showed as a skip in every run

    @pytest.mark.parametrize(
        ("name", "slot"),
        [
            pytest.param(
                name,
                slot,
                marks=pytest.mark.xfail(strict=True, raises=AssertionError, reason=why),
            )
            for (name, slot), why in sorted(KNOWN.items())
        ],
    )
    def test_known_misnamed_arguments(name: str, slot: str) -> None:
        """A known case XPASSes (and fails, strict) once fixed: then remove it from ``KNOWN``."""
        found = list(verdicts(name, sample=False, known=True, slot=slot))
        assert found, f"{name}: no refused value for {slot} (stale KNOWN entry?)"
        bad = [v for v in found if not v.ok]
        assert not bad, _explain(bad)


def test_known_entries_are_specs(tmp_path: Path) -> None:
    for name, slot in KNOWN:
        assert name in SPECS, name
        tree = SPECS[name].make(Ctx(tmp_path))
        assert any(p.name == slot for p in tree.parameters()), (name, slot)


def test_a_known_entry_moves_its_cases_from_the_main_test_to_its_xfail(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # With the ledger empty the xfail test is not defined, so nothing else runs this
    # path: an entry must leave the main test and reach its own strict xfail, and a
    # fixed entry (every message names ``dt``) must make that xfail's body pass (XPASS).
    name = "navkit.control.limit_velocity_change"
    everything = list(verdicts(name, sample=False))
    assert any(v.case.startswith("dt ") for v in everything)
    monkeypatch.setitem(KNOWN, (name, "dt"), "a stand-in entry")
    rest = list(verdicts(name, sample=False))
    assert rest and not any(v.case.startswith("dt ") for v in rest)
    assert len(rest) < len(everything)
    found = list(verdicts(name, sample=False, known=True, slot="dt"))
    assert found and all(v.case.startswith("dt ") for v in found)
    assert len(found) + len(rest) == len(everything)
    assert all(v.ok for v in found)


# --------------------------------------------------------------------------- the check itself


def _misnamed(waypoints: float) -> float:
    if not isinstance(waypoints, float) or math.isnan(waypoints):
        raise ValueError("points must be a finite float")  # an internal name
    return waypoints


def _named(waypoints: float) -> float:
    if not isinstance(waypoints, float) or math.isnan(waypoints):
        raise ValueError(f"waypoints must be a finite float, got {waypoints!r}")
    return waypoints


class _Inner:
    __module__ = "navkit._selftest"

    def __init__(self, x: float, *, checks: bool) -> None:
        if checks and abs(x) > 1e300:
            raise ValueError("x is too large")
        self.x = x


def _outer(start: _Inner, *, misnamed: bool) -> float:
    if abs(start.x) > 1e300:
        raise ValueError(f"{'pose' if misnamed else 'start'} is too far away")
    return float(start.x)


def _verdicts_of(s: Spec, root: Path) -> list[Verdict]:
    with quiet():
        found = [probe(s, c, root) for c in message_cases(s, sample=False)]
    return [v for v in found if v is not None]


def test_a_message_naming_an_internal_argument_fails(tmp_path: Path) -> None:
    bad = _verdicts_of(Spec("selftest.misnamed", lambda c: call(_misnamed, 1.0)), tmp_path)
    good = _verdicts_of(Spec("selftest.named", lambda c: call(_named, 1.0)), tmp_path)
    assert bad and not any(v.ok for v in bad)
    assert good and all(v.ok for v in good)
    assert all(v.names == ("waypoints",) for v in bad + good)


@pytest.mark.parametrize("misnamed", [False, True])
@pytest.mark.parametrize("checks", [False, True])
def test_a_nested_refusal_names_the_constructor_or_the_outer_argument(
    checks: bool, misnamed: bool, tmp_path: Path
) -> None:
    s = Spec(
        "selftest.nested",
        lambda c: call(_outer, call(_Inner, 1.0, checks=checks), misnamed=misnamed),
    )
    found = {v.case: v for v in _verdicts_of(s, tmp_path)}
    huge = found["start.x = 10**400 (a huge int)"]
    if checks:
        # The constructor refused it: its own argument is where the caller wrote it.
        assert huge.names == ("x",) and huge.ok
    else:
        # The constructor took it and the outer call refused the object: ``start``.
        assert huge.names == ("start",)
        assert huge.ok is not misnamed


def test_expected_names() -> None:
    assert expected_names(("start",), ()) == ("start",)
    assert expected_names(("start", "x"), ("start",)) == ("x",)
    assert expected_names(("start", "x"), ()) == ("start",)
    assert expected_names(("self", "grid", "resolution"), ("self",)) == ("grid",)
    assert expected_names(("self", "resolution"), ()) == ("resolution",)
    assert expected_names(("goal",), ("start",)) == ()


# --------------------------------------------------------------------------- the command line


def test_a_bad_scheduler_address_names_the_option(capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("dask.distributed")
    from navkit.cli import main

    assert main(["run", "demo", "--scheduler", "no-port-here", "--quiet"]) == 1
    err = capsys.readouterr().err
    assert _names_word("--scheduler", err) and "no-port-here" in err, err
