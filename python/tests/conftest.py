"""Shared fixtures: the repository root, the `ecc` binary, small meshes."""

import os
import shutil
import subprocess

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def ecc_bin():
    """The CLI binary (ECC_BIN, else target/{debug,release}/ecc, else built)."""
    candidates = [os.environ.get("ECC_BIN", "")] + [
        os.path.join(ROOT, "target", p, "ecc") for p in ("debug", "release")
    ]
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    cargo = shutil.which("cargo")
    assert cargo, "no ecc binary and no cargo to build one"
    subprocess.run([cargo, "build", "-q", "-p", "ecc-cli"], cwd=ROOT, check=True)
    return os.path.join(ROOT, "target", "debug", "ecc")


def bumpy_grid(n=12, amp=0.3, seed=0):
    """A disk-topology surface: an n×n grid on [0,1]² lifted by bumps."""
    rng = np.random.default_rng(seed)
    xs = np.linspace(0.0, 1.0, n + 1)
    X, Y = np.meshgrid(xs, xs, indexing="xy")
    k = rng.uniform(1.0, 3.0, size=2)
    Z = amp * np.sin(np.pi * k[0] * X) * np.sin(np.pi * k[1] * Y)
    V = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    F = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 1, a + n + 2
            F += [[a, b, d], [a, d, c]]
    return V, np.asarray(F, dtype=np.int64)


@pytest.fixture
def grid():
    return bumpy_grid()
