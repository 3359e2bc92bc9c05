"""Mesh files (round trips with meshio) and bad arrays: they raise, never crash."""

import os

import meshio
import numpy as np
import pytest

import ecc
from conftest import bumpy_grid


def test_meshio_writes_ecc_reads(tmp_path):
    V, F = bumpy_grid(5)
    for ext in ("obj", "off", "vtk"):
        path = str(tmp_path / f"m.{ext}")
        kw = {"binary": False} if ext == "vtk" else {}  # ecc reads ASCII VTK
        meshio.write(path, meshio.Mesh(V, [("triangle", F)]), **kw)
        m = ecc.read_mesh(path)
        np.testing.assert_allclose(m["vertices"], V, rtol=0, atol=1e-12)
        np.testing.assert_array_equal(m["triangles"], F)
        assert m["vertices"].dtype == np.float64 and m["triangles"].dtype == np.int64


def test_ecc_writes_meshio_reads_with_uv(tmp_path):
    V, F = bumpy_grid(6)
    out = ecc.parameterize(V, F, "sd")
    path = str(tmp_path / "uv.obj")
    ecc.write_obj(path, V, F, uv=out["uv"])
    m = meshio.read(path)
    np.testing.assert_allclose(m.points, V, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(m.cells_dict["triangle"], F)
    back = ecc.read_mesh(path)
    np.testing.assert_allclose(back["uv"], out["uv"], rtol=1e-12, atol=1e-12)
    assert not [p for p in os.listdir(tmp_path) if p != "uv.obj"]  # no temporary left


def test_a_tet_mesh_file(root):
    m = ecc.read_mesh(os.path.join(root, "data", "bar-2523.mesh"))
    assert m["tets"].shape[1] == 4 and m["tets"].max() < len(m["vertices"])


def test_a_broken_file_is_a_located_mesh_error(tmp_path):
    p = tmp_path / "bad.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    with pytest.raises(ecc.MeshError, match="bad.obj"):
        ecc.read_mesh(str(p))


V0, F0 = bumpy_grid(3)


@pytest.mark.parametrize(
    "V,F,what",
    [
        (V0[:, :1], F0, "shape"),
        (V0, F0[:, :2], "shape"),
        (np.where(np.arange(V0.size).reshape(V0.shape) == 4, np.nan, V0), F0, "finite"),
        (V0, np.where(F0 == 5, 999, F0), "outside"),
        (V0, np.where(F0 == 5, -1, F0), "outside"),
        (V0, F0.astype(float) + 0.5, "integer"),
        (V0, np.zeros((0, 3), dtype=np.int64), "m > 0"),
        (np.zeros((3, 3)), np.array([[0, 1, 2]]), "degenerate"),
        (V0, np.zeros((2, 3, 3), dtype=np.int64), "2D array"),
    ],
)
def test_bad_arrays_raise_mesh_error(V, F, what):
    with pytest.raises(ecc.MeshError, match=what):
        ecc.parameterize(V, F)


def test_bad_deform_arguments_raise():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    T = np.array([[0, 1, 2, 3]])
    with pytest.raises(ecc.MeshError, match="handle"):
        ecc.deform(V, T, handles=[7], targets=[[0, 0, 0]])
    with pytest.raises(ecc.MeshError, match="targets"):
        ecc.deform(V, T, handles=[0, 1], targets=[[0, 0, 0]])
    with pytest.raises(ecc.MeshError, match="degenerate|volume|invert|orient"):
        ecc.deform(V, T[:, [1, 0, 2, 3]], handles=[0], targets=[[0, 0, 0]])
    with pytest.raises(ecc.EnergyError, match="3D"):
        ecc.deform(V, T, "mips", handles=[0], targets=[[0, 0, 0]])
