"""ecc.batch on a 2-worker LocalCluster: a folder of meshes (some bad on
purpose), the results table, rerun skipping, and a worker killed mid-batch."""

import os
import signal
import threading

import numpy as np
import pytest

import ecc
from ecc import batch
from conftest import bumpy_grid

distributed = pytest.importorskip("dask.distributed")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def write_meshes(folder, good, n=10):
    os.makedirs(folder, exist_ok=True)
    for i in range(good):
        V, F = bumpy_grid(n, amp=0.2 + 0.05 * i, seed=i)
        ecc.write_obj(os.path.join(folder, f"good{i:03d}.obj"), V, F)
    # bad on purpose: a broken index, a closed surface (not a disk), a tet mesh
    with open(os.path.join(folder, "bad_index.obj"), "w") as fh:
        fh.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    with open(os.path.join(folder, "bad_closed.off"), "w") as fh:
        fh.write("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    with open(os.path.join(folder, "bad_tets.mesh"), "w") as fh:
        fh.write(
            "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
            "0 0 1 0\nTetrahedra\n1\n1 2 3 4 0\nEnd\n"
        )


def test_a_folder_of_meshes_and_the_table(client, tmp_path):
    meshes, out = str(tmp_path / "meshes"), str(tmp_path / "out")
    write_meshes(meshes, good=5)
    jobs = batch.mesh_jobs([meshes], ["sd", "arap"])
    assert len(jobs) == 16
    rows = batch.run_batch(jobs, out, client=client)
    table = batch.read_table(os.path.join(out, "results.csv"))
    assert [r["job"] for r in table] == sorted(j.name for j in jobs)
    assert list(table[0]) == batch.COLUMNS
    by = {r["job"]: r for r in table}
    for j in jobs:
        r = by[j.name]
        if "good" in j.input:
            assert r["status"] == "ok", r
            assert int(r["iterations"]) > 0 and float(r["final_energy"]) > 0
            files = sorted(os.listdir(os.path.join(out, "jobs", j.name)))
            assert files == ["records.json", "result.json", "uv.npy", "uv.obj"]
            uv = np.load(os.path.join(out, "jobs", j.name, "uv.npy"))
            assert uv.shape == (121, 2) and np.isfinite(uv).all()
        else:
            assert r["status"] == "failed" and r["error"], r
    assert "MeshError" in by[next(j.name for j in jobs if "bad_index" in j.input)]["error"]
    assert "triangle mesh" in by[next(j.name for j in jobs if "bad_tets" in j.input)]["error"]
    # nothing half-written: no temporary folders are left
    assert not [p for p in os.listdir(os.path.join(out, "jobs")) if p.startswith(".")]
    assert [r["status"] for r in rows] == [by[j.name]["status"] for j in jobs]

    # rerunning skips every finished job (no client needed, nothing rewritten)
    stamp = {j.name: os.stat(os.path.join(out, "jobs", j.name, "result.json")).st_mtime_ns for j in jobs}
    again = batch.run_batch(jobs, out, client=None, scheduler="tcp://127.0.0.1:1")
    assert again == rows
    for j in jobs:
        assert os.stat(os.path.join(out, "jobs", j.name, "result.json")).st_mtime_ns == stamp[j.name]


TINY_SCENE = """
name = "tiny"
frames = 2
[mesh]
generate = "bar"
resolution = 1
[energy]
name = "arap"
[[effects.handles]]
plane = { point = [-1.9, 0, 0], normal = [-1, 0, 0] }
[[effects.handles]]
plane = { point = [1.9, 0, 0], normal = [1, 0, 0] }
keys = [ { frame = 2, rotate = [60, 0, 0] } ]
"""


def test_scene_jobs(client, tmp_path):
    scenes, out = tmp_path / "scenes", str(tmp_path / "out")
    scenes.mkdir()
    (scenes / "tiny.toml").write_text(TINY_SCENE)
    # a tolerance no solve reaches in 2 iterations: the run ends unconverged
    (scenes / "tight.toml").write_text(TINY_SCENE + "[solver]\nmax_iters = 2\ntol = 1e-300\n")
    (scenes / "broken.toml").write_text("[mesh]\nfile = 3\n")
    jobs = batch.scene_jobs([str(scenes)], pictures=False)
    assert len(jobs) == 3
    batch.run_batch(jobs, out, client=client)
    by = {os.path.basename(r["input"]): r for r in batch.read_table(os.path.join(out, "results.csv"))}
    ok = by["tiny.toml"]
    assert ok["status"] == "ok" and int(ok["iterations"]) > 0 and float(ok["final_energy"]) > 0
    folder = os.path.join(out, "jobs", ok["job"])
    assert os.path.exists(os.path.join(folder, "summary.json"))
    assert os.path.exists(os.path.join(folder, "out", "frame_0002.obj"))
    assert by["tight.toml"]["status"] == "unconverged" and by["tight.toml"]["error"]
    assert by["broken.toml"]["status"] == "failed" and "SceneError" in by["broken.toml"]["error"]


def test_a_killed_worker_loses_no_job(client, tmp_path):
    meshes, out = str(tmp_path / "meshes"), str(tmp_path / "out")
    write_meshes(meshes, good=24, n=24)
    jobs = batch.mesh_jobs([meshes], ["sd"])
    pids = list(client.run(os.getpid).values())
    killed = threading.Event()

    def kill_one():
        # wait until some job has finished, then kill a worker process mid-batch
        done_dir = os.path.join(out, "jobs")
        while not (os.path.isdir(done_dir) and len(os.listdir(done_dir)) >= 2):
            if killed.wait(0.02):
                return
        os.kill(pids[0], signal.SIGKILL)
        killed.set()

    t = threading.Thread(target=kill_one, daemon=True)
    t.start()
    rows = batch.run_batch(jobs, out, client=client)
    t.join(5)
    assert killed.is_set(), "the batch ended before a worker could be killed"
    table = batch.read_table(os.path.join(out, "results.csv"))
    assert len(table) == len(jobs) == len(rows)
    for r in table:
        assert r["status"] in ("ok", "failed"), r
        folder = os.path.join(out, "jobs", r["job"])
        if r["status"] == "failed":
            assert r["error"]
            # a deterministic failure has its folder; a lost one has none (retried next run)
            if os.path.exists(folder):
                assert "bad" in r["input"]
        else:
            assert os.path.exists(os.path.join(out, "jobs", r["job"], "uv.obj"))
    # bad meshes are failures, every good one either finished or is recorded
    assert sum(r["status"] == "ok" for r in table) >= 20


def test_the_command_line(tmp_path):
    meshes, out = str(tmp_path / "meshes"), str(tmp_path / "out")
    os.makedirs(meshes)
    V, F = bumpy_grid(6)
    ecc.write_obj(os.path.join(meshes, "a.obj"), V, F)
    jobs = batch.mesh_jobs([meshes], ["snh"], batch._parse_params(["mu=1,2"]), max_iters=50)
    assert [j.params for j in jobs] == [{"mu": 1.0}, {"mu": 2.0}]
    with pytest.raises(SystemExit):
        batch.main(["batch", "--out", out])  # no jobs
