"""A real local Dask cluster for the tests (test helper)."""

from __future__ import annotations

import os
from typing import Any


def local_cluster(distributed: Any) -> Any:
    """A ``LocalCluster`` of two worker processes, one thread each.

    The scheduler always starts an HTTP server: with ``dashboard_address=None`` it
    takes port 8787 and warns (an error under the suite's ``filterwarnings =
    error``) when another cluster, or a second test run at the same time, holds
    that port. ``"127.0.0.1:0"`` lets the OS pick a free port, on this machine only;
    ``dashboard=False`` keeps the dashboard (bokeh, if installed) off. The
    process's environment is left as it was.
    """
    environ = dict(os.environ)
    try:
        return distributed.LocalCluster(
            n_workers=2,
            processes=True,
            threads_per_worker=1,
            dashboard_address="127.0.0.1:0",
            scheduler_kwargs={"dashboard": False},
        )
    finally:
        # The nanny sets its workers' variables (OMP_NUM_THREADS=1, PYTHONHASHSEED,
        # ...) in this process's os.environ before it starts them: put back, or the
        # probe processes of every later test would inherit them.
        os.environ.clear()
        os.environ.update(environ)
