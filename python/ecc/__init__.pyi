"""Type stubs of the ecc package (the native part is ecc._ecc)."""

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, "os.PathLike[str]"]
ArrayLike = npt.ArrayLike
ProgressFn = Callable[[Dict[str, Any]], Optional[bool]]

class Error(Exception):
    """Base class of every error raised by ecc."""

class EnergyError(Error):
    """An energy could not be loaded or evaluated."""

    line: Optional[int]
    column: Optional[int]
    diagnostic: str

class MeshError(Error):
    """Bad mesh input (shape, dtype, non-finite, out-of-range, degenerate)."""

class SceneError(Error):
    """A scene file could not be read, validated or run."""

class SolveError(Error):
    """A solve could not be set up or run."""

class Energy:
    """An isotropic energy density Ψ(F) compiled from .psi text."""

    def __init__(self, text: str, *, name: str = "energy", **params: float) -> None: ...
    @staticmethod
    def from_file(path: PathLike, **params: float) -> "Energy": ...
    @staticmethod
    def builtin(name: str, **params: float) -> "Energy": ...
    @property
    def name(self) -> str: ...
    @property
    def dims(self) -> List[int]: ...
    @property
    def params(self) -> List[Tuple[str, float]]: ...
    def source(self, dim: Optional[int] = None) -> str: ...
    def report(self, dim: Optional[int] = None) -> str: ...
    def emit_rust(self, type_name: Optional[str] = None, dim: Optional[int] = None) -> str: ...
    def psi(self, sigma: Sequence[float]) -> float: ...
    def eval(self, F: ArrayLike) -> Dict[str, Any]:
        """Keys: psi, sigma, gradient, P, hessian, hessian_projected, eigenvalues."""

def builtin_names() -> List[str]: ...
def parameterize(
    V: ArrayLike,
    F: ArrayLike,
    energy: Union[str, Energy] = "sd",
    *,
    tutte: str = "uniform",
    normalize_area: bool = True,
    mean_energy: bool = True,
    max_iters: Optional[int] = None,
    tol: Optional[float] = None,
    progress: Optional[ProgressFn] = None,
) -> Dict[str, Any]: ...
def deform(
    V: ArrayLike,
    T: ArrayLike,
    energy: Union[str, Energy] = "snh",
    *,
    handles: ArrayLike,
    targets: ArrayLike,
    substeps: int = 1,
    max_iters: Optional[int] = None,
    tol: Optional[float] = None,
    progress: Optional[ProgressFn] = None,
) -> Dict[str, Any]: ...
def simulate(
    scene: PathLike,
    out: Optional[PathLike] = None,
    *,
    frames: Optional[int] = None,
    pictures: Optional[bool] = None,
    progress: Optional[ProgressFn] = None,
) -> Dict[str, Any]: ...
def read_mesh(path: PathLike) -> Dict[str, np.ndarray]: ...
def write_obj(path: PathLike, V: ArrayLike, F: ArrayLike, uv: Optional[ArrayLike] = None) -> None: ...
