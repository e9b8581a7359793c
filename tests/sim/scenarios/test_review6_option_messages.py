"""Option messages of soccer and omni-apf show the refused value exactly, not rounded."""

from __future__ import annotations

import pytest

from navkit.sim.scenarios import OmniApf, Soccer


@pytest.mark.parametrize(
    ("option", "value", "shown"),
    [
        ("perception_noise", 0.5000001, "got 0.5000001"),
        ("max_speed", 5.0000001, "got 5.0000001"),
        ("wheel_slip", 0.5000001, r"\[0, 0.5\], got 0.5000001"),  # no unit, no stray space
        ("duration", 600.0000001, "got 600.0000001"),
    ],
)
def test_message_shows_the_value(option: str, value: float, shown: str) -> None:
    with pytest.raises(ValueError, match=rf"{option} must lie in .*{shown}$"):
        Soccer(**{option: value})  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("target", "obstacles", "shown"),
    [
        ((50.0000001, 0.0), False, "50.0000001 m away"),
        ((0.4999999, 0.0), False, "0.4999999 m away"),
        ((0.0, 0.9999999), None, "0.9999999 m away"),
    ],
)
def test_omni_apf_target_messages_show_the_distance(
    target: tuple[float, float], obstacles: bool | None, shown: str
) -> None:
    with pytest.raises(ValueError, match=rf"targets\[0\] must lie .*{shown}$"):
        OmniApf(obstacles=obstacles, targets=[target])
