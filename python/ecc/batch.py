"""Batches of ecc jobs on a ``dask.distributed`` cluster.

A job is one mesh file × one energy × one parameter set (a parameterisation),
or one scene file (``ecc.simulate``). :func:`run_batch` submits every job that
has not finished yet to a Dask client — a ``LocalCluster`` by default, or any
existing cluster through its scheduler address (e.g. one started by
dask-jobqueue on Slurm/PBS: see the README) — and keeps a results table.

Guarantees:

* **Atomic outputs.** A job writes into a private temporary folder next to
  its final folder ``OUT/jobs/<job>/`` and renames it into place as the last
  step, so a job folder either holds all its files (``result.json`` among
  them) or does not exist.
* **Rerun skips finished jobs.** A job whose folder exists is finished (it
  succeeded, or failed deterministically: bad mesh, bad energy); its row is
  read back from ``result.json``.
* **Nothing is lost.** A job whose worker died is retried by Dask (its
  ``allowed-failures``), then recorded as ``failed`` with the error; such jobs
  leave no folder, so the next run tries them again.
* **The table** ``OUT/results.csv`` (job, status, iterations, final_energy,
  seconds, error, kind, input, energy, params) is rewritten atomically after
  every finished job.

Command line: ``python -m ecc batch --meshes DIR --energy sd --out OUT``
(``python -m ecc batch --help``).
"""

from __future__ import annotations

import argparse
import csv
import glob
import hashlib
import io
import itertools
import json
import os
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from typing import Any, Dict, Iterable, List, Optional, Sequence

__all__ = ["Job", "mesh_jobs", "scene_jobs", "run_job", "run_batch", "main", "COLUMNS"]

#: Columns of the results table, in order.
COLUMNS = [
    "job",
    "status",
    "iterations",
    "final_energy",
    "seconds",
    "error",
    "kind",
    "input",
    "energy",
    "params",
]

MESH_EXTENSIONS = (".obj", ".off", ".mesh", ".msh", ".vtk")


@dataclass(frozen=True)
class Job:
    """One unit of work. ``kind`` is ``"param"`` (``input`` = a triangle mesh
    file, parameterised with ``energy`` and ``params``) or ``"scene"``
    (``input`` = a scene TOML file). ``options`` go to ``ecc.parameterize``
    (e.g. ``max_iters``) or ``ecc.simulate`` (e.g. ``frames``)."""

    name: str
    kind: str
    input: str
    energy: str = ""
    params: Dict[str, float] = field(default_factory=dict)
    options: Dict[str, Any] = field(default_factory=dict)


def _slug(text: str) -> str:
    keep = "".join(c if c.isalnum() or c in "-_." else "_" for c in text)
    return keep.strip("._") or "job"


def _params_text(params: Dict[str, float]) -> str:
    return ",".join(f"{k}={params[k]:g}" for k in sorted(params))


def _expand(inputs: Iterable[str], extensions: Sequence[str]) -> List[str]:
    files: List[str] = []
    for item in inputs:
        if os.path.isdir(item):
            for name in sorted(os.listdir(item)):
                if name.lower().endswith(tuple(extensions)):
                    files.append(os.path.join(item, name))
        else:
            matches = sorted(glob.glob(item))
            files.extend(matches if matches else [item])
    return files


def mesh_jobs(
    meshes: Iterable[str],
    energies: Sequence[str] = ("sd",),
    params: Sequence[Dict[str, float]] = ({},),
    **options: Any,
) -> List[Job]:
    """Jobs for every mesh file × energy × parameter set. ``meshes`` are files,
    folders (their mesh files) or glob patterns; a ``.psi`` path is accepted
    as an energy. Job names are unique and stable across runs."""
    jobs = []
    for path, energy, ps in itertools.product(
        _expand(meshes, MESH_EXTENSIONS), energies, params
    ):
        stem = os.path.splitext(os.path.basename(path))[0]
        label = os.path.splitext(os.path.basename(energy))[0]
        name = f"{stem}-{label}"
        if ps:
            name += "-" + _params_text(ps)
        digest = hashlib.sha1(os.path.abspath(path).encode()).hexdigest()[:6]
        jobs.append(
            Job(_slug(f"{name}-{digest}"), "param", path, energy, dict(ps), dict(options))
        )
    return jobs


def scene_jobs(scenes: Iterable[str], **options: Any) -> List[Job]:
    """One job per scene file (files, folders of ``.toml`` or globs)."""
    jobs = []
    for path in _expand(scenes, (".toml",)):
        stem = os.path.splitext(os.path.basename(path))[0]
        digest = hashlib.sha1(os.path.abspath(path).encode()).hexdigest()[:6]
        jobs.append(Job(_slug(f"{stem}-{digest}"), "scene", path, options=dict(options)))
    return jobs


def _row(job: Job, **values: Any) -> Dict[str, Any]:
    row: Dict[str, Any] = {c: "" for c in COLUMNS}
    row.update(
        job=job.name,
        kind=job.kind,
        input=job.input,
        energy=job.energy,
        params=_params_text(job.params),
    )
    row.update(values)
    return row


def _energy(job: Job) -> Any:
    import ecc

    if job.energy.endswith(".psi"):
        return ecc.Energy.from_file(job.energy, **job.params)
    return ecc.Energy.builtin(job.energy, **job.params)


def _param_job(job: Job, tmp: str) -> Dict[str, Any]:
    import numpy as np

    import ecc

    mesh = ecc.read_mesh(job.input)
    if "triangles" not in mesh:
        raise ecc.MeshError(f"{job.input}: a parameterisation needs a triangle mesh")
    V, F = mesh["vertices"], mesh["triangles"]
    out = ecc.parameterize(V, F, _energy(job), **job.options)
    ecc.write_obj(os.path.join(tmp, "uv.obj"), V, F, uv=out["uv"])
    np.save(os.path.join(tmp, "uv.npy"), out["uv"])
    with open(os.path.join(tmp, "records.json"), "w") as fh:
        json.dump(out["records"], fh)
    status = "ok" if out["converged"] else f"not converged ({out['status']})"
    return {
        "status": status,
        "iterations": out["iterations"],
        "final_energy": out["final_energy"],
        "error": "" if out["converged"] else out["status"],
    }


def _scene_job(job: Job, tmp: str) -> Dict[str, Any]:
    import ecc

    summary = ecc.simulate(job.input, out=os.path.join(tmp, "out"), **job.options)
    with open(os.path.join(tmp, "summary.json"), "w") as fh:
        json.dump(summary, fh, indent=1)
    frames = summary.get("frames", [])
    last = frames[-1] if frames else {}
    # the run's own verdict: converged | unconverged | stopped (as ecc sim)
    status = summary.get("status", "converged")
    error = summary.get("stopped") or ("" if status == "converged" else "some frames did not converge")
    return {
        "status": "ok" if status == "converged" else status,
        "iterations": summary.get("newton_iterations", ""),
        "final_energy": summary.get("final_energy", last.get("energy", "")),
        "error": error,
    }


def run_job(job: Job, out_dir: str) -> Dict[str, Any]:
    """Run one job in this process and return its table row. Its folder
    ``out_dir/jobs/<name>`` appears atomically, with ``result.json`` (the row)
    and the outputs; an ecc error (bad mesh, energy, scene) is a finished job
    with status ``failed``. An existing folder is returned as is (skipped)."""
    final = os.path.join(out_dir, "jobs", job.name)
    done = _read_done(final)
    if done is not None:
        return done
    os.makedirs(os.path.dirname(final), exist_ok=True)
    tmp = tempfile.mkdtemp(prefix=f".{job.name}.", dir=os.path.dirname(final))
    t0 = time.perf_counter()
    try:
        import ecc

        try:
            values = (_param_job if job.kind == "param" else _scene_job)(job, tmp)
        except (ecc.Error, OSError) as e:
            values = {"status": "failed", "error": f"{type(e).__name__}: {e}"}
        row = _row(job, seconds=round(time.perf_counter() - t0, 6), **values)
        with open(os.path.join(tmp, "result.json"), "w") as fh:
            json.dump(row, fh, indent=1)
        try:
            os.rename(tmp, final)
        except OSError:
            # another attempt of the same job finished first: keep its result
            done = _read_done(final)
            if done is None:
                raise
            return done
        return row
    finally:
        if os.path.isdir(tmp):
            shutil.rmtree(tmp, ignore_errors=True)


def _read_done(folder: str) -> Optional[Dict[str, Any]]:
    try:
        with open(os.path.join(folder, "result.json")) as fh:
            return dict(json.load(fh))
    except (OSError, ValueError):
        return None


def write_table(path: str, rows: Sequence[Dict[str, Any]]) -> None:
    """Write the results table as CSV atomically (temporary file + rename)."""
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=COLUMNS, extrasaction="ignore")
    w.writeheader()
    for r in sorted(rows, key=lambda r: r["job"]):
        w.writerow(r)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".results.", dir=folder)
    try:
        with os.fdopen(fd, "w", newline="") as fh:
            fh.write(buf.getvalue())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def read_table(path: str) -> List[Dict[str, str]]:
    """The rows of a results table."""
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def _client(client: Any, scheduler: Optional[str], workers: int, threads: int) -> Any:
    from dask.distributed import Client, LocalCluster

    if client is not None:
        return client, None
    if scheduler:
        return Client(scheduler), None
    cluster = LocalCluster(
        n_workers=workers, threads_per_worker=threads, processes=True, dashboard_address=None
    )
    return Client(cluster), cluster


def run_batch(
    jobs: Sequence[Job],
    out_dir: str,
    *,
    client: Any = None,
    scheduler: Optional[str] = None,
    workers: int = 2,
    threads_per_worker: int = 1,
    retries: int = 1,
    progress: bool = False,
) -> List[Dict[str, Any]]:
    """Run ``jobs`` on Dask and return the table rows (also in
    ``out_dir/results.csv``).

    ``client``: an existing ``dask.distributed.Client``; else ``scheduler``
    (an address such as ``tcp://host:8786``); else a ``LocalCluster`` with
    ``workers`` processes, closed at the end. ``retries``: Dask retries of a
    job whose task raised (worker deaths are retried by the scheduler's
    ``distributed.scheduler.allowed-failures``). Finished jobs are skipped.
    """
    from dask.distributed import as_completed

    names = [j.name for j in jobs]
    if len(set(names)) != len(names):
        raise ValueError("job names must be unique")
    os.makedirs(out_dir, exist_ok=True)
    table = os.path.join(out_dir, "results.csv")
    rows: Dict[str, Dict[str, Any]] = {}
    todo = []
    for j in jobs:
        done = _read_done(os.path.join(out_dir, "jobs", j.name))
        if done is not None:
            rows[j.name] = done
        else:
            todo.append(j)
    if not todo:
        write_table(table, list(rows.values()))
        return [rows[n] for n in names]
    c, cluster = _client(client, scheduler, workers, threads_per_worker)
    try:
        futures = {
            c.submit(run_job, j, os.path.abspath(out_dir), key=f"ecc-{j.name}", retries=retries): j
            for j in todo
        }
        for fut in as_completed(list(futures)):
            j = futures[fut]
            if fut.status == "finished":
                rows[j.name] = fut.result()
            else:
                exc = fut.exception()
                rows[j.name] = _row(j, status="failed", error=f"{type(exc).__name__}: {exc}")
            write_table(table, list(rows.values()))
            if progress:
                r = rows[j.name]
                print(f"{len(rows)}/{len(jobs)} {j.name}: {r['status']}", file=sys.stderr)
    finally:
        if cluster is not None:
            c.close()
            cluster.close()
    return [rows[n] for n in names]


def _parse_params(items: Sequence[str]) -> List[Dict[str, float]]:
    """``["mu=1,2", "lambda=10"]`` → the product ``[{mu:1, lambda:10}, {mu:2, lambda:10}]``."""
    axes = []
    for item in items:
        name, _, values = item.partition("=")
        if not name or not values:
            raise SystemExit(f"error: --param expects NAME=V1,V2,..., got {item!r}")
        try:
            axes.append([(name, float(v)) for v in values.split(",")])
        except ValueError:
            raise SystemExit(f"error: --param {item!r}: values must be numbers") from None
    return [dict(combo) for combo in itertools.product(*axes)] or [{}]


def main(argv: Optional[Sequence[str]] = None) -> int:
    """``python -m ecc batch``: see ``--help``."""
    p = argparse.ArgumentParser(
        prog="python -m ecc batch",
        description="Run ecc jobs (meshes × energies × parameters, or scenes) on Dask.",
    )
    p.add_argument("command", choices=["batch"])
    p.add_argument("--meshes", nargs="*", default=[], help="mesh files, folders or globs")
    p.add_argument("--energy", action="append", help="energy name or .psi file (repeatable; default sd)")
    p.add_argument("--param", action="append", default=[], help="NAME=V1,V2 (repeatable; product)")
    p.add_argument("--scenes", nargs="*", default=[], help="scene files, folders or globs")
    p.add_argument("--max-iters", type=int, default=None)
    p.add_argument("--out", required=True, help="output folder (results.csv and jobs/)")
    p.add_argument("--scheduler", default=None, help="address of an existing Dask scheduler")
    p.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    p.add_argument("--retries", type=int, default=1)
    a = p.parse_args(argv)
    opts = {} if a.max_iters is None else {"max_iters": a.max_iters}
    jobs = mesh_jobs(a.meshes, a.energy or ["sd"], _parse_params(a.param), **opts)
    jobs += scene_jobs(a.scenes)
    if not jobs:
        p.error("no jobs: give --meshes and/or --scenes")
    t0 = time.perf_counter()
    rows = run_batch(
        jobs, a.out, scheduler=a.scheduler, workers=a.workers, retries=a.retries, progress=True
    )
    ok = sum(r["status"] == "ok" for r in rows)
    print(
        f"{len(rows)} jobs: {ok} ok, {len(rows) - ok} not ok, "
        f"{time.perf_counter() - t0:.1f} s; table {os.path.join(a.out, 'results.csv')}"
    )
    return 0 if ok == len(rows) else 1
