"""Per-job overhead of ecc.batch, and a 100-mesh batch on a 2-worker LocalCluster.

    python python/examples/batch_bench.py [--meshes 100] [--n 20] [--out DIR]

Generates `--meshes` bumpy-grid surfaces (n×n quads, 2n² triangles) and times:
1. the solver alone: ecc.parameterize on arrays already in memory;
2. a job in-process: ecc.batch.run_job (read the file, solve, write uv.obj,
   uv.npy, records.json, result.json, rename the folder) — no Dask;
3. the batch: ecc.batch.run_batch on a LocalCluster with `--workers` worker
   processes (default 2; cluster start-up timed separately).
The solver itself is multi-threaded (rayon): on a 2-core machine one job
in-process already uses both cores, so `--workers 1` isolates the per-job
overhead of Dask and the job folder.
Prints the numbers and the table's status counts.
"""

import argparse
import collections
import os
import sys
import tempfile
import time

import numpy as np

import ecc
from ecc import batch


def bumpy_grid(n, seed):
    rng = np.random.default_rng(seed)
    xs = np.linspace(0.0, 1.0, n + 1)
    X, Y = np.meshgrid(xs, xs)
    k = rng.uniform(1.0, 3.0, size=2)
    Z = rng.uniform(0.1, 0.6) * np.sin(np.pi * k[0] * X) * np.sin(np.pi * k[1] * Y)
    V = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    a = (np.arange(n)[None, :] + (n + 1) * np.arange(n)[:, None]).ravel()
    F = np.concatenate([np.stack([a, a + 1, a + n + 2], 1), np.stack([a, a + n + 2, a + n + 1], 1)])
    return V, F.astype(np.int64)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--meshes", type=int, default=100)
    p.add_argument("--n", type=int, default=20)
    p.add_argument("--out", default=None)
    p.add_argument("--workers", type=int, default=2)
    a = p.parse_args()
    root = a.out or tempfile.mkdtemp(prefix="ecc-batch-bench-")
    folder = os.path.join(root, "meshes")
    os.makedirs(folder, exist_ok=True)
    meshes = [bumpy_grid(a.n, s) for s in range(a.meshes)]
    for i, (V, F) in enumerate(meshes):
        ecc.write_obj(os.path.join(folder, f"m{i:03d}.obj"), V, F)
    jobs = batch.mesh_jobs([folder], ["sd"])

    t = time.perf_counter()
    for V, F in meshes:
        ecc.parameterize(V, F, "sd")
    solver = (time.perf_counter() - t) / len(meshes)

    direct_dir = os.path.join(root, "direct")
    t = time.perf_counter()
    for j in jobs:
        batch.run_job(j, direct_dir)
    in_process = (time.perf_counter() - t) / len(jobs)

    from dask.distributed import Client, LocalCluster

    t = time.perf_counter()
    cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True, dashboard_address=None)
    client = Client(cluster)
    startup = time.perf_counter() - t
    t = time.perf_counter()
    rows = batch.run_batch(jobs, os.path.join(root, "dask"), client=client)
    wall = time.perf_counter() - t
    client.close()
    cluster.close()
    counts = collections.Counter(r["status"] for r in rows)
    per_job_worker = wall * a.workers / len(jobs)
    print(f"meshes: {len(jobs)} × {2 * a.n * a.n} triangles, energy sd")
    print(f"solver alone      : {solver * 1e3:8.2f} ms/job")
    print(f"job in-process    : {in_process * 1e3:8.2f} ms/job (file I/O + atomic folder: +{(in_process - solver) * 1e3:.2f} ms)")
    print(f"dask, {a.workers} worker(s)  : {wall:8.2f} s wall for {len(jobs)} jobs = {wall / len(jobs) * 1e3:.2f} ms/job, "
          f"{per_job_worker * 1e3:.2f} worker-ms/job (overhead vs in-process: +{(per_job_worker - in_process) * 1e3:.2f} ms)")
    print(f"cluster start-up  : {startup:8.2f} s")
    print(f"table             : {os.path.join(root, 'dask', 'results.csv')}: {dict(counts)}")
    return 0 if counts.get("ok", 0) == len(jobs) else 1


if __name__ == "__main__":
    sys.exit(main())
