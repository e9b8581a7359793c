"""The defaults the docstrings quote are the signatures' defaults.

Every public function, method and constructor (as ``test_docstrings`` finds
them) whose ``Parameters`` (``Other Parameters``, or a dataclass's
``Attributes``) entry says ``name : type, default X`` — or whose description
says ``(default X)`` — is checked against ``inspect.signature``: ``X`` is
evaluated (``inf``, ``π``, ``logit(p)``, ``Pose2D(0, 0, 0)``, the sim's sensor
classes) and compared with the real default, numbers within the rounding of the
quoted digits. Entries that group names (``kp, ki, kd : float, default 3.0,
0.0, 0.1``) give one value per name. A default written as prose ("the four
above") is listed in ``PROSE``, so a new one is added on purpose.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import re
from collections.abc import Callable, Iterator
from typing import Any

import test_docstrings as docstrings
from navkit.geometry import Pose2D, as_pose
from navkit.sim import RangeNoise, WheelEncoders

# (callable, parameter): defaults the docstring describes in words.
PROSE = {
    ("navkit.behaviours.GameState", "teammates_xy"),  # "no teammates"
    ("navkit.behaviours.GameState", "opponents_xy"),  # "no opponents"
    ("navkit.sim.scenarios.Greedy", "pairs"),  # "the four above"
    ("navkit.sim.scenarios.OmniApf", "targets"),  # "the paper's four"
    ("navkit.cli.main", "argv"),  # None reads ``sys.argv[1:]``, as argparse
}

NAMESPACE: dict[str, Any] = {
    "inf": math.inf,
    "pi": math.pi,
    "logit": lambda p: math.log(p / (1.0 - p)),
    "Pose2D": Pose2D,
    "RangeNoise": RangeNoise,
    "WheelEncoders": WheelEncoders,
    "__builtins__": {},
}
TYPE_LINE = re.compile(r"^(?P<names>[\w*, ]+?)\s*:\s*(?P<type>.*)$")
TYPE_DEFAULT = re.compile(r"(?:^|,\s*)default\s+(?P<value>.+)$")
DESC_DEFAULT = re.compile(r"\(default (?P<value>``[^`]+``|[-+\w.]+)\)")


def _callables() -> Iterator[tuple[str, str, Callable[..., Any]]]:
    """``(qualified name, docstring, function whose signature it documents)``."""
    for items in docstrings._inventory().items.values():
        for item in items:
            if item.kind == "class":
                init = docstrings._class_init(item.obj)
                if init is not None:
                    yield item.qualname, docstrings._own_doc(item.obj), init
            elif item.kind in ("function", "method"):
                func = item.obj
                if isinstance(func, (staticmethod, classmethod)):
                    func = func.__func__
                yield item.qualname, docstrings._own_doc(func), func


def _entries(doc: str) -> Iterator[tuple[list[str], str, str]]:
    """``(names, type text, description)`` of each parameter entry."""
    sections = docstrings._sections(doc)
    for title in (*docstrings.PARAM_SECTIONS, "Attributes"):
        head: re.Match[str] | None = None
        description: list[str] = []
        for line in [*sections.get(title, "").splitlines(), "END"]:
            if line and not line[0].isspace():
                if head is not None:
                    names = [n.strip().lstrip("*") for n in head["names"].split(",")]
                    yield names, head["type"], " ".join(description)
                head = TYPE_LINE.match(line)
                description = []
            elif head is not None:
                description.append(line.strip())


def _split(text: str, count: int) -> list[str]:
    """One quoted value per grouped name: ``1.0 and 2.0``, ``3.0, 0.0, 0.1``."""
    if count == 1:
        return [text]
    parts = [p.strip() for p in re.split(r",\s*|\s+and\s+", text) if p.strip()]
    return parts if len(parts) == count else [text] * count


def _value(text: str) -> Any:
    text = text.strip().strip("`").strip()
    # An angle quoted in degrees with its radians: ``10° (0.1745 rad)``.
    radians = re.fullmatch(r"[\d.]+° \(([\d.]+) rad\)", text)
    if radians:
        text = radians[1]
    text = re.sub(r"(\d)π", r"\1*pi", text).replace("π", "pi")
    return eval(text, NAMESPACE)  # the package's own docstrings: no untrusted input


def _digits_tolerance(text: str) -> float:
    """Half a unit of the last digit quoted: ``0.1745`` stands for [0.17445, 0.17455]."""
    numbers = re.findall(r"\d+\.(\d+)", text)
    return 0.5 * 10.0 ** -max((len(n) for n in numbers), default=0) if numbers else 0.0


def _same(quoted: Any, actual: Any, text: str) -> bool:
    if isinstance(quoted, (int, float)) and isinstance(actual, (int, float)):
        if isinstance(quoted, bool) or isinstance(actual, bool):
            return quoted is actual
        if math.isinf(quoted) or math.isinf(actual):
            return quoted == actual
        return abs(quoted - actual) <= _digits_tolerance(text) + 1e-12 * abs(actual)
    if isinstance(actual, Pose2D) and isinstance(quoted, (tuple, Pose2D)):
        return _same(tuple(as_pose(quoted).as_array()), tuple(actual.as_array()), text)
    if isinstance(actual, (tuple, list)) and isinstance(quoted, (tuple, list)):
        return len(quoted) == len(actual) and all(
            _same(q, a, text) for q, a in zip(quoted, actual, strict=True)
        )
    if isinstance(actual, (float, int, str, type(None))) or dataclasses.is_dataclass(actual):
        return bool(quoted == actual)
    return False


def _claims() -> list[tuple[str, str, str, inspect.Parameter | None]]:
    """``(callable, parameter, quoted default, the parameter)`` of every claim."""
    out = []
    for qualname, doc, func in _callables():
        try:
            parameters = inspect.signature(func).parameters
        except (TypeError, ValueError):
            continue
        for names, type_text, description in _entries(doc):
            quoted: list[list[str]] = []
            in_type = TYPE_DEFAULT.search(type_text)
            if in_type:
                quoted.append(_split(in_type["value"], len(names)))
            quoted += [[m["value"]] * len(names) for m in DESC_DEFAULT.finditer(description)]
            for values in quoted:
                for name, text in zip(names, values, strict=True):
                    if (qualname, name) not in PROSE:
                        out.append((qualname, name, text, parameters.get(name)))
    return out


CLAIMS = _claims()


def test_quoted_defaults_are_the_signatures() -> None:
    wrong = []
    for qualname, name, text, parameter in CLAIMS:
        where = f"{qualname}({name}): the docstring says default {text!r}"
        if parameter is None:
            wrong.append(f"{where}, but there is no such parameter")
        elif parameter.default is inspect.Parameter.empty:
            wrong.append(f"{where}, but the parameter is required")
        else:
            try:
                quoted = _value(text)
            except Exception as exc:  # prose that is not in PROSE
                wrong.append(f"{where}, which does not evaluate ({exc}); add it to PROSE?")
                continue
            if not _same(quoted, parameter.default, text):
                wrong.append(f"{where}, the signature {parameter.default!r}")
    assert not wrong, "\n".join(wrong)


def test_the_checker_reads_many_claims_and_catches_a_wrong_one() -> None:
    assert len(CLAIMS) > 250
    assert {(q, n) for q, n, _, _ in CLAIMS} >= {
        ("navkit.control.PotentialFieldController", "max_decel"),  # "1.0 and 2.0"
        ("navkit.control.PotentialFieldController", "kd"),  # "3.0, 0.0, 0.1"
        ("navkit.control.OnOffTracker", "rotate_angle"),  # "10° (0.1745 rad)"
        ("navkit.sim.Lidar", "fov"),  # "2π"
        ("navkit.estimation.PlanarFusion", "history"),  # "(default 0)"
    }
    assert _same(_value("10° (0.1745 rad)"), math.radians(10.0), "0.1745")
    assert not _same(_value("0.1746"), math.radians(10.0), "0.1746")
    assert not _same(_value("(0, 0, 1)"), Pose2D(0.0, 0.0, 0.0), "(0, 0, 1)")
    assert not _same(_value('("house",)'), ("house", "building"), "")
    assert not _same(_value('"trinary"'), "scale", '"trinary"')
    assert _same(_value(["logit(0.9)", " logit(0.4)"][0]), math.log(9.0), "logit(0.9)")
    assert _same(_value("Pose2D(0, 0, 0)"), Pose2D(0.0, 0.0, 0.0), "")
    assert not _same(_value("True"), 1, "True")
