"""The tests' Dask cluster starts while port 8787 is taken (review 39, FLAKY).

The scheduler always starts an HTTP server. With ``dashboard_address=None`` it took
Dask's dashboard port 8787 and, where another cluster or a second test run at the
same time held it, warned "Port 8787 is already in use" (an error under the suite's
``filterwarnings = error``): every test of ``tests/sim/test_sweep.py`` using the
cluster errored with "Cluster failed to start". ``tests/dask_cluster.py`` now gives
it a port the OS picks.
"""

from __future__ import annotations

import contextlib
import os
import socket
from collections.abc import Iterator

import pytest

from dask_cluster import local_cluster

distributed = pytest.importorskip("distributed")

DASHBOARD_PORT = 8787


@contextlib.contextmanager
def _port_taken(port: int) -> Iterator[None]:
    """``port`` held by a listening socket here (or by someone else already)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        with contextlib.suppress(OSError):  # taken already: all the better
            sock.bind(("", port))
            sock.listen()
        yield


def test_the_cluster_starts_and_runs_with_the_dashboard_port_taken() -> None:
    with _port_taken(DASHBOARD_PORT):
        cluster = local_cluster(distributed)
        try:
            with distributed.Client(cluster) as client:
                assert client.submit(pow, 3, 4).result(timeout=120) == 81
                assert len(client.scheduler_info()["workers"]) == 2
            port = cluster.scheduler.http_server.port
            assert port != DASHBOARD_PORT and port > 0
        finally:
            cluster.close()


def test_starting_the_cluster_leaves_this_processs_environment_as_it_was() -> None:
    # distributed's nanny sets its workers' variables (OMP_NUM_THREADS=1,
    # PYTHONHASHSEED, MALLOC_TRIM_THRESHOLD_, ...) in os.environ of the process
    # starting them: every later test's probe process inherited them, a hash
    # seed and BLAS threads fixed or not by whether a Dask test ran before (FLAKY).
    before = dict(os.environ)
    cluster = local_cluster(distributed)
    try:
        assert dict(os.environ) == before
    finally:
        cluster.close()
    assert dict(os.environ) == before
