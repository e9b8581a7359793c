"""plot_scene: a scenario's map, world, plans, traces and markers in one picture."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from plot_pixels import grey_at, render
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.plot import plot_scene
from navkit.sim import Circle, MovingObstacle, Robot, Scene, Simulation, Trace, World

pytest.importorskip("matplotlib")


def _run(world: World) -> Trace:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    sim = Simulation(world, robot, lambda obs: Twist2D(0.5, 0.0, 0.0), start=(1.0, 1.0, 0.0),
                     goal=(3.0, 1.0), duration=5.0)  # fmt: skip
    return sim.run()


def _scene() -> Scene:
    """A 6 × 4 m room (walls as lines), a pillar, a moving ball, a map with a block."""
    occupied = np.zeros((40, 60), dtype=bool)
    occupied[30:36, 40:50] = True  # x in [4, 5), y in [3, 3.6)
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    ball = MovingObstacle.constant_velocity(0.1, start_xy=(2.0, 3.0), velocity_xy=(0.1, 0.0))
    world = World([box(0.0, 0.0, 6.0, 4.0).exterior, Circle((4.5, 1.5), 0.3)], moving=[ball])
    return Scene(
        "room",
        grid=grid,
        world=world,
        paths=(("plan", np.array([[1.0, 1.0], [3.0, 1.0]])),),
        traces=(("driven", _run(world)),),
        points=(("start", np.array([1.0, 1.0])), ("goal", np.array([[3.0, 1.0]]))),
    )


def test_every_part_of_the_scene_is_drawn() -> None:
    ax = plot_scene(_scene())
    assert ax.get_title() == "room"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["plan", "driven", "start", "goal"]
    assert len(ax.images) == 1  # the map
    walls = ax.collections[0].get_segments()
    assert len(walls) == 4  # the room's four edges
    circles = [p for p in ax.patches if type(p).__name__ == "Circle"]
    assert len(circles) == 1 and circles[0].get_radius() == 0.3
    moving = [p for p in ax.patches if type(p).__name__ == "Polygon"]
    assert len(moving) == 1
    np.testing.assert_allclose(moving[0].get_xy().mean(axis=0), [2.0, 3.0], atol=0.01)


def test_the_rendered_scene_puts_the_map_and_walls_in_place(tmp_path: Path) -> None:
    ax = plot_scene(_scene(), legend=False)
    image, pixel = render(ax, tmp_path)
    assert grey_at(image, pixel([4.5, 3.3])) < 0.1  # the map's block (high y: the top)
    assert grey_at(image, pixel([3.0, 0.0]), radius=0) < 0.4  # the bottom wall
    assert grey_at(image, pixel([3.0, 2.0])) > 0.95  # free floor
    assert pixel([4.5, 3.3])[0, 0] < pixel([3.0, 2.0])[0, 0]


def test_a_solid_polygon_with_a_hole_leaves_the_hole_clear(tmp_path: Path) -> None:
    # A solid square ring: the world is free inside its hole, so must the picture be.
    ring = box(0.0, 0.0, 4.0, 4.0).difference(box(1.0, 1.0, 3.0, 3.0))
    for solid in (ring, ring.reverse()):  # either orientation of the rings
        world = World([solid])
        assert not world.collides(0.1, (2.0, 2.0, 0.0))
        ax = plot_scene(Scene("ring", world=world), legend=False)
        image, pixel = render(ax, tmp_path)
        assert grey_at(image, pixel([2.0, 2.0]), radius=3) > 0.99  # the hole: white
        assert grey_at(image, pixel([0.5, 2.0]), radius=3) < 0.9  # the ring: shaded
        assert grey_at(image, pixel([2.0, 3.5]), radius=3) < 0.9


def test_the_view_is_cropped_to_the_known_map_and_the_drawing() -> None:
    known = np.zeros((400, 400), dtype=bool)
    known[190:210, 180:220] = True  # a 4 × 2 m known patch in a 40 × 40 m map
    grid = OccupancyGrid.from_probabilities(np.where(known, 0.0, 0.5), resolution=0.1,
                                            origin=(-20.0, -20.0, 0.0))  # fmt: skip
    ax = plot_scene(Scene("patch", grid=grid, points=(("far", np.array([5.0, 0.0])),)))
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    assert -3.0 < x0 < -2.0 and 5.0 < x1 < 6.0  # known x in [-2, 2], the point at 5
    assert -2.0 < y0 < -1.0 and 1.0 < y1 < 2.0


def test_an_empty_scene_draws_an_empty_titled_picture() -> None:
    ax = plot_scene(Scene("nothing"))
    assert ax.get_title() == "nothing" and ax.get_legend() is None


def test_a_non_scene_is_refused() -> None:
    with pytest.raises(TypeError, match="Scene"):
        plot_scene(np.zeros(3))  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("parts", "error", "match"),
    [
        ({"paths": (("p", np.array([[0.0, math.nan]])),)}, ValueError, r"paths\[0\]"),
        ({"paths": ((1, np.zeros((2, 2))),)}, TypeError, r"paths\[0\]\[0\]"),
        ({"traces": (("t", np.zeros((2, 3))),)}, TypeError, r"traces\[0\]"),
        ({"points": (("p", np.zeros((2, 3))),)}, ValueError, r"points\[0\]"),
        ({"points": [("p",)]}, ValueError, r"points\[0\]"),
        ({"grid": np.zeros((2, 2))}, TypeError, "grid"),
        ({"world": "room"}, TypeError, "world"),
    ],
)
def test_bad_scenes_are_refused(parts: dict[str, object], error: type, match: str) -> None:
    # A Scene checks its parts when it is made, so a bad one never reaches the plot.
    with pytest.raises(error, match=match):
        plot_scene(Scene("x", **parts))  # type: ignore[arg-type]
