"""All-pairs (pairwise) combinations of keyword options, for the review-33 PAIRS tests.

Defects hide where two options meet (review 31: ``ScanMatcher``'s plateau rule never
ran with prior weights; review 33: ``RegulatedPurePursuit``'s near-goal turn never
ran with ``rotate_to_heading=False``). Every value of every option, extremes and
special values included, is met with every value of every other option in at least
one row, in far fewer rows than the full product: 10 options of 3 values need 23
rows instead of 59,049.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import Any


def all_pairs(options: Mapping[str, Sequence[Any]]) -> list[dict[str, Any]]:
    """Rows of keyword values covering every pair of values of every two options.

    Deterministic (a greedy cover, the same rows every run): each row starts from
    the first pair not yet covered and fills the other options with the value that
    covers most new pairs, the first such value on ties.

    >>> rows = all_pairs({"a": [0, 1], "b": ["x", "y"], "c": [None, 2.0]})
    >>> len(rows), rows[0]
    (4, {'a': 0, 'b': 'x', 'c': None})
    >>> {(r["a"], r["c"]) for r in rows} == {(0, None), (0, 2.0), (1, None), (1, 2.0)}
    True
    """
    names = list(options)
    values = [list(options[name]) for name in names]
    if any(not v for v in values):
        raise ValueError("every option needs at least one value")
    uncovered = {
        (a, i, b, j)
        for a, b in itertools.combinations(range(len(names)), 2)
        for i in range(len(values[a]))
        for j in range(len(values[b]))
    }
    rows: list[dict[str, Any]] = []
    while True:
        if not uncovered:
            if not rows:  # a single option: one row per value
                rows = [{names[0]: v} for v in values[0]] if len(names) == 1 else [{}]
            return rows
        a, i, b, j = min(uncovered)
        chosen = {a: i, b: j}
        for k in range(len(names)):
            if k in chosen:
                continue
            best, gain = 0, -1
            for v in range(len(values[k])):
                new = sum(
                    ((k, v, m, w) if k < m else (m, w, k, v)) in uncovered
                    for m, w in chosen.items()
                )
                if new > gain:
                    best, gain = v, new
            chosen[k] = best
        for x, y in itertools.combinations(sorted(chosen), 2):
            uncovered.discard((x, chosen[x], y, chosen[y]))
        rows.append({names[k]: values[k][chosen[k]] for k in range(len(names))})
