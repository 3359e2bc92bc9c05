"""ecc: isotropic energies compiled from formulas, from Python.

    >>> import numpy as np, ecc
    >>> snh = ecc.Energy.builtin("snh", mu=1, lambda_=10)
    >>> r = snh.eval(np.diag([1.1, 0.9, 1.0]))
    >>> r["psi"], r["gradient"].shape, r["hessian"].shape
    >>> out = ecc.parameterize(V, F, energy="sd")     # uv + per-iteration stats

Energies evaluate through the same interpreter and runtime formulas as
``ecc eval`` (same numbers); solves are ecc-fem's projected Newton, run with
the GIL released; Ctrl-C stops a solve between iterations. Errors are
subclasses of :class:`ecc.Error`. Batches on Dask: :mod:`ecc.batch`.
"""

from __future__ import annotations

import json as _json
import os as _os
from typing import Any, Callable, Dict, Optional, Union

import numpy as _np

from . import _ecc
from ._ecc import (  # noqa: F401  (re-exported)
    Energy,
    EnergyError,
    Error,
    MeshError,
    SceneError,
    SolveError,
    builtin_names,
)

__version__ = _ecc.__version__

__all__ = [
    "Energy",
    "Error",
    "EnergyError",
    "MeshError",
    "SceneError",
    "SolveError",
    "builtin_names",
    "parameterize",
    "deform",
    "simulate",
    "read_mesh",
    "write_obj",
]


ProgressFn = Callable[[Dict[str, Any]], Optional[bool]]


def _vertices(V: Any) -> "_np.ndarray":
    try:
        return _np.asarray(V, dtype=_np.float64)
    except (TypeError, ValueError) as e:
        raise MeshError(f"vertex array: {e}") from None


def _indices(T: Any, name: str) -> "_np.ndarray":
    a = _np.asarray(T)
    if a.size and a.dtype.kind not in "iu":
        raise MeshError(f"{name} must hold integer vertex indices, got dtype {a.dtype}")
    if a.ndim != 2:
        raise MeshError(f"{name} must be a 2D array of vertex indices, got shape {a.shape}")
    return a.astype(_np.int64, copy=False)


def _two_d(a: "_np.ndarray", name: str) -> "_np.ndarray":
    if a.ndim != 2:
        raise MeshError(f"{name} must be a 2D array, got shape {a.shape}")
    return a


def parameterize(
    V: Any,
    F: Any,
    energy: Union[str, Energy] = "sd",
    *,
    tutte: str = "uniform",
    normalize_area: bool = True,
    mean_energy: bool = True,
    max_iters: Optional[int] = None,
    tol: Optional[float] = None,
    progress: Optional[ProgressFn] = None,
) -> Dict[str, Any]:
    """Parameterise a disk-topology triangle mesh (ecc-fem's projected Newton).

    Minimises the area-weighted mean Σ|q|Ψ(J_q)/Σ|q| over uv, from a Tutte
    embedding with the boundary on a circle.

    Parameters
    ----------
    V : (n, 3) or (n, 2) float array — vertex positions (C or Fortran order).
    F : (m, 3) integer array — triangles (0-based).
    energy : a built-in name ("sd", "arap", "mips", ...) or an :class:`Energy`
        with a 2D version.
    tutte : start weights, "uniform" | "mean_value" | "cotangent".
    normalize_area : scale the mesh to unit area first (uv in those units).
    mean_energy : minimise/report the mean energy (SD of an isometry = 2).
    max_iters, tol : Newton limits (default: ecc-fem's).
    progress : called after every Newton step with a dict (iter, energy,
        grad_inf, step, ...); return False to stop (status "Interrupted").

    Returns
    -------
    dict with ``uv`` (n, 2), ``status``, ``converged``, ``iterations``,
    ``initial_energy``, ``final_energy``, ``grad_inf``, ``flipped``,
    ``seconds``, ``records`` (per-iteration statistics), ``position_scale``,
    ``rest_area``.

    Raises ``MeshError`` (bad arrays, degenerate or non-disk mesh),
    ``EnergyError``, ``SolveError``; ``KeyboardInterrupt`` on Ctrl-C.
    """
    v = _two_d(_vertices(V), "V")
    f = _indices(F, "F")
    return _ecc.parameterize(
        v, f, energy, tutte, normalize_area, mean_energy, max_iters, tol, progress
    )


def deform(
    V: Any,
    T: Any,
    energy: Union[str, Energy] = "snh",
    *,
    handles: Any,
    targets: Any,
    substeps: int = 1,
    max_iters: Optional[int] = None,
    tol: Optional[float] = None,
    progress: Optional[ProgressFn] = None,
) -> Dict[str, Any]:
    """Deform a tet mesh by moving handle vertices (ecc-fem's HandleDeformation).

    Parameters
    ----------
    V : (n, 3) float array — rest positions.  T : (m, 4) integer array — tets.
    energy : a built-in name or an :class:`Energy` with a 3D version.
    handles : vertex ids held fixed (and moved to ``targets``).
    targets : (len(handles), 3) float array — where the handles go.
    substeps : split the handle motion into this many solves.
    progress : called after every Newton step (of every substep) with a dict
        (iter, energy, grad_inf, step, ...); return False to stop (status
        "Interrupted", no further substep). Ctrl-C stops it the same way.

    Returns a dict with ``x`` (n, 3) final positions, ``status``,
    ``converged``, ``iterations`` (all substeps), ``substeps``, ``inverted``,
    ``final_energy``, ``grad_inf``, ``records`` (last substep).
    """
    v = _two_d(_vertices(V), "V")
    t = _indices(T, "T")
    h = _np.asarray(handles).reshape(-1)
    if h.size and h.dtype.kind not in "iu":
        raise MeshError(f"handles must be integer vertex ids, got dtype {h.dtype}")
    tg = _two_d(_vertices(targets), "targets")
    return _ecc.deform(
        v, t, energy, [int(x) for x in h], tg, int(substeps), max_iters, tol, progress
    )


def simulate(
    scene: Union[str, "_os.PathLike[str]"],
    out: Optional[Union[str, "_os.PathLike[str]"]] = None,
    *,
    frames: Optional[int] = None,
    pictures: Optional[bool] = None,
    progress: Optional[ProgressFn] = None,
) -> Dict[str, Any]:
    """Run a scene file (TOML, as ``ecc sim``) and return its summary as a dict.

    ``out`` overrides the output folder; ``frames`` the number of frames;
    ``pictures=False`` skips result.png/convergence.png. ``progress`` is
    called after every Newton step with a dict (iter, energy, grad_inf, ...);
    returning False stops the run early (summary ``status`` "stopped", what
    was computed is written); Ctrl-C stops it the same way and then raises
    ``KeyboardInterrupt``. Raises ``SceneError``.
    """
    text = _ecc.simulate(
        _os.fspath(scene),
        None if out is None else _os.fspath(out),
        frames,
        pictures,
        progress,
    )
    return _json.loads(text)


def read_mesh(path: Union[str, "_os.PathLike[str]"]) -> Dict[str, Any]:
    """Read a mesh file with ecc's readers (OBJ, OFF, MEDIT .mesh, Gmsh .msh, VTK).

    Returns ``{"vertices": (n, 3) float64, "triangles": (m, 3) int64}`` (plus
    ``"uv"`` when an OBJ has one per vertex) or ``{"vertices", "tets": (m, 4)}``.
    Raises ``MeshError`` with the file, line and reason on bad input.
    """
    return dict(_ecc.read_mesh(_os.fspath(path)))


def write_obj(
    path: Union[str, "_os.PathLike[str]"], V: Any, F: Any, uv: Any = None
) -> None:
    """Write a triangle mesh (and optional per-vertex uv) as OBJ, atomically."""
    v = _two_d(_vertices(V), "V")
    f = _indices(F, "F")
    u = None if uv is None else _two_d(_vertices(uv), "uv")
    _ecc.write_obj(_os.fspath(path), v, f, u)
