"""Sweeps: a 24-point sweep on a 2-worker LocalCluster completes, survives a worker killed in
the middle (Dask reschedules; no point lost or duplicated), and a second call does no work;
failures are rows; local processes without a client."""

from __future__ import annotations

import os
import signal
import threading
import time

import pytest

import wrinkle

#: 4 × 6 = 24 points of the fast scene.
GRID = {
    "load.tension_y": [5.0, 10.0, 15.0, 20.0],
    "geometry.lx": [300.0, 340.0, 380.0, 420.0, 460.0, 500.0],
}


def test_a_sweep_on_two_dask_workers_survives_a_killed_worker(tmp_path, fast_scene):
    distributed = pytest.importorskip("distributed")
    out = tmp_path / "sweep"
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        outcome: dict = {}
        thread = threading.Thread(
            target=lambda: outcome.update(
                table=wrinkle.sweep(fast_scene, GRID, client=client, out=out, threads_per_point=1)
            )
        )
        thread.start()
        _wait_for_points(out, at_least=4)
        victim = next(iter(client.run(os.getpid).values()))
        os.kill(victim, signal.SIGKILL)
        thread.join(timeout=600)
        table = outcome["table"]

        assert len(table) == 24
        records = table.records()
        assert sorted(r["index"] for r in records) == list(range(24))
        assert {r["outcome"] for r in records} == {"reached"}, records
        assert len({r["hash"] for r in records}) == 24
        directories = [p for p in (out / "points").iterdir() if not p.name.startswith(".")]
        assert len(directories) == 24
        assert table.csv.is_file()
        assert table.ran == 24

        again = wrinkle.sweep(fast_scene, GRID, client=client, out=out)
        assert again.ran == 0
        assert all(r["reused"] for r in again.records())
        assert again.column("critical_load").tolist() == table.column("critical_load").tolist()


def _wait_for_points(out, at_least: int, timeout: float = 300.0) -> None:
    """Waits until `at_least` points have written their result."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if len(list(out.glob("points/*/point.json"))) >= at_least:
            return
        time.sleep(0.05)
    raise AssertionError("the sweep did not start")


def test_a_local_sweep_reports_failures_as_rows(tmp_path, fast_scene):
    grid = {"material.poisson": [0.3, 0.7], "load.tension_y": [10.0]}
    table = wrinkle.sweep(fast_scene, grid, out=tmp_path / "local", workers=2)
    records = table.records()
    assert [r["outcome"] for r in records] == ["reached", "error"]
    assert records[1]["exit_code"] == 2
    assert "material.poisson" in records[1]["reason"]
    assert records[0]["peak_memory_bytes"] is None or records[0]["peak_memory_bytes"] > 0
    assert records[0]["load_at_amplitude_0.5"] > records[0]["critical_load"] * 0.5


def test_a_list_of_scenes_is_a_sweep_and_equal_scenes_run_once(tmp_path, fast_scene):
    same = dict(fast_scene, load={"tension_y": 10.0})
    scenes = [fast_scene, same, wrinkle.Scene(fast_scene, {"load.tension_y": 5.0})]
    table = wrinkle.sweep(None, scenes, out=tmp_path / "list", command="buckle", workers=1)
    records = table.records()
    assert table.ran == 2
    assert records[0]["hash"] == records[1]["hash"] != records[2]["hash"]
    assert records[2]["critical_load"] != records[0]["critical_load"]
    pandas = pytest.importorskip("pandas")
    assert isinstance(table.to_pandas(), pandas.DataFrame)
