"""Pictures of navkit's maps, plans, runs and fields (matplotlib, the ``plot`` extra).

Every function takes its data positionally and its options keyword-only, draws
on the matplotlib Axes given as ``ax=`` (or on new axes of a new figure on the
non-interactive Agg canvas: no pyplot state, no window, safe in threads) and
returns the Axes; none calls ``plt.show``. Coordinates are world metres with
equal scales; grids are drawn in ROS map orientation (row 0, the lowest y, at
the bottom).

* :func:`plot_grid`: an :class:`~navkit.mapping.OccupancyGrid` (free white,
  unknown grey, occupied black) over its world extent.
* :func:`plot_path`: a :class:`~navkit.planning.Path2D` or ``(n, 2)`` points.
* :func:`plot_trace`: a simulated run, true poses solid, estimates dashed.
* :func:`plot_scan`: a :class:`~navkit.mapping.LaserScan` from a sensor pose.
* :func:`plot_field`: a potential field as a surface, contours or arrows.
* :func:`plot_scene`: a scenario's :class:`~navkit.sim.Scene` (map, world,
  plans, traces, markers, title, legend).
* :func:`save_figure` writes a PNG, :func:`animate_trace` a GIF of a run; both
  write atomically (a temporary file in the same folder, then ``os.replace``).

matplotlib is imported only when something is drawn; without it every function
raises an ``ImportError`` saying ``pip install 'navkit[plot]'``.

Examples
--------
>>> import numpy as np
>>> from navkit.mapping import OccupancyGrid
>>> occupied = np.zeros((20, 30), dtype=bool)
>>> occupied[:15, 14:16] = True
>>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
>>> ax = plot_grid(grid)
>>> ax = plot_path(np.array([[0.5, 0.5], [1.5, 1.8], [2.5, 0.5]]), ax=ax, label="plan")
>>> [float(v) for v in ax.get_xlim()]
[0.0, 3.0]
"""

from navkit.plot._animate import animate_trace
from navkit.plot._field import plot_field
from navkit.plot._files import save_figure
from navkit.plot._grid import plot_grid
from navkit.plot._lines import plot_path, plot_scan, plot_trace
from navkit.plot._scene import plot_scene

__all__ = [
    "animate_trace",
    "plot_field",
    "plot_grid",
    "plot_path",
    "plot_scan",
    "plot_scene",
    "plot_trace",
    "save_figure",
]
