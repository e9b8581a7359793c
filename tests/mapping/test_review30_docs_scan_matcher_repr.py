"""ScanMatcher's repr names every option that changes a match."""

from __future__ import annotations

from navkit.mapping import ScanMapper, ScanMatcher


def test_repr_names_the_pull_and_the_pre_search() -> None:
    matcher = ScanMatcher(
        translation_weight=2.5, rotation_weight=3.5, search_distance=0.2, search_angle=0.05
    )
    text = repr(matcher)
    for option in (
        "translation_weight=2.5",
        "rotation_weight=3.5",
        "search_distance=0.2",
        "search_angle=0.05",
    ):
        assert option in text


def test_scan_mappers_default_matcher_does_not_print_as_a_bare_matcher() -> None:
    # ScanMapper's default matcher pulls towards the guess (weights 1) and pre-searches;
    # the bare ScanMatcher() does neither, so the two must not read alike.
    default = ScanMapper()._matcher
    assert repr(default) != repr(ScanMatcher())
    again = eval(repr(default), {"ScanMatcher": ScanMatcher})
    assert repr(again) == repr(default)
