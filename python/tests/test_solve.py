"""Parameterisation (vs libigl's harmonic map), deformation, scenes, the
progress callback and Ctrl-C."""

import os
import signal
import subprocess
import time

import igl
import numpy as np
import pytest

import ecc
from conftest import bumpy_grid


def sd_mean(V, F, uv):
    """Area-weighted mean symmetric Dirichlet ½(‖J‖² + ‖J⁻¹‖²) of the map
    surface → uv, computed here independently of ecc."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    e1, e2 = b - a, c - a
    l1 = np.linalg.norm(e1, axis=1)
    x = e1 / l1[:, None]
    n = np.cross(e1, e2)
    area = 0.5 * np.linalg.norm(n, axis=1)
    y = np.cross(n / (2 * area)[:, None], x)
    Dm = np.stack(
        [np.stack([l1, np.zeros_like(l1)], 1), np.stack([(e2 * x).sum(1), (e2 * y).sum(1)], 1)], 2
    )
    Ds = np.stack([uv[F[:, 1]] - uv[F[:, 0]], uv[F[:, 2]] - uv[F[:, 0]]], 2)
    J = Ds @ np.linalg.inv(Dm)
    Ji = np.linalg.inv(J)
    sd = 0.5 * ((J**2).sum((1, 2)) + (Ji**2).sum((1, 2)))
    return float((area * sd).sum() / area.sum()), area.sum()


def igl_harmonic(V, F):
    bnd = igl.boundary_loop(F)
    bnd_uv = igl.map_vertices_to_circle(V, bnd)
    return igl.harmonic(V, F, bnd, bnd_uv, 1)


@pytest.mark.parametrize("mesh", ["bumpy", "camelhead"])
def test_sd_is_not_worse_than_libigl_harmonic(root, mesh):
    if mesh == "bumpy":
        V, F = bumpy_grid(16, amp=0.5, seed=3)
    else:
        m = ecc.read_mesh(os.path.join(root, "data", "camelhead.off"))
        V, F = m["vertices"], m["triangles"]
    out = ecc.parameterize(V, F, "sd", max_iters=200)
    assert out["flipped"] == 0 and out["converged"], out["status"]
    Vn = V * out["position_scale"]  # ecc's unit-area normalisation
    mine, area = sd_mean(Vn, F, out["uv"])
    assert abs(mine - out["final_energy"]) < 1e-9 * mine
    uv = igl_harmonic(Vn, F)
    # the same scale rule as ecc's start: uv area = rest area
    e1, e2 = uv[F[:, 1]] - uv[F[:, 0]], uv[F[:, 2]] - uv[F[:, 0]]
    a2 = 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]).sum()
    uv *= np.sqrt(area / abs(a2))
    theirs, _ = sd_mean(Vn, F, uv)
    assert out["final_energy"] <= theirs, (out["final_energy"], theirs)
    assert out["final_energy"] >= 2.0 - 1e-12  # an isometry gives 2


def test_records_and_the_progress_callback(grid):
    V, F = grid
    seen = []
    out = ecc.parameterize(np.asfortranarray(V), F, "sd", progress=seen.append)
    assert out["iterations"] == len(out["records"]) == len(seen) > 0
    assert [r["iter"] for r in seen] == list(range(len(seen)))
    energies = [r["energy"] for r in seen]
    assert all(b <= a for a, b in zip(energies, energies[1:]))
    assert out["final_energy"] <= energies[-1]


def test_returning_false_stops_the_solve(grid):
    V, F = grid
    calls = []
    out = ecc.parameterize(V, F, "sd", progress=lambda r: calls.append(r) or len(calls) < 2)
    assert out["status"] == "Interrupted" and len(calls) == 2 and not out["converged"]


def test_an_exception_in_the_callback_propagates(grid):
    V, F = grid

    def boom(rec):
        raise ValueError("stop here")

    with pytest.raises(ValueError, match="stop here"):
        ecc.parameterize(V, F, "sd", progress=boom)


def test_ctrl_c_interrupts_a_long_solve(grid):
    V, F = bumpy_grid(40, amp=0.8, seed=5)
    steps = []
    # Python raises KeyboardInterrupt only if SIGINT was not ignored when it
    # started; a runner started as a background job (`cmd &` without job
    # control, nohup) ignores it, so install Python's handler for this test.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    # Ctrl-C from outside the process, as a terminal sends it.
    kill = subprocess.Popen(["sh", "-c", f"sleep 0.2; kill -INT {os.getpid()}"])
    try:
        with pytest.raises(KeyboardInterrupt):
            # tol = 0 never converges: only the interrupt ends it early
            ecc.parameterize(V, F, "sd", max_iters=3000, tol=0.0, progress=steps.append)
    finally:
        kill.kill()
        kill.wait()
        signal.signal(signal.SIGINT, previous)
    assert 0 < len(steps) < 3000
    # the interpreter is fine afterwards
    assert ecc.parameterize(*grid, "sd")["converged"]


def _bar(n=4):
    """A 1 x 0.25 x 0.25 bar of n cubes (6 positive tets each), its left and
    right end vertices as handles, the right end's targets moved by +0.3 in x."""
    xs = np.linspace(0, 1, n + 1)
    ys = np.linspace(0, 0.25, 2)
    P = np.array([[x, y, z] for z in ys for y in ys for x in xs])
    idx = lambda i, j, k: k * 2 * (n + 1) + j * (n + 1) + i
    T = []
    for i in range(n):
        c = [idx(i + a, b, d) for d in (0, 1) for b in (0, 1) for a in (0, 1)]
        # 6 positively oriented tets of a cube (Kuhn split)
        for p in ([0, 1, 3, 7], [0, 1, 7, 5], [0, 4, 5, 7], [0, 2, 6, 7], [0, 3, 2, 7], [0, 6, 4, 7]):
            t = [c[q] for q in p]
            a, b, cc, d = P[t]
            if np.dot(np.cross(b - a, cc - a), d - a) < 0:
                t[0], t[1] = t[1], t[0]
            T.append(t)
    T = np.array(T)
    left = np.where(P[:, 0] == 0)[0]
    right = np.where(P[:, 0] == 1)[0]
    handles = np.concatenate([left, right])
    targets = P[handles].copy()
    targets[len(left):, 0] += 0.3
    return P, T, handles, targets


def test_deform_a_bar():
    P, T, handles, targets = _bar()
    seen = []
    out = ecc.deform(P, T, ecc.Energy.builtin("snh", mu=1, lambda_=10), handles=handles,
                     targets=targets, substeps=2, progress=seen.append)
    assert out["converged"] and out["inverted"] == 0
    np.testing.assert_allclose(out["x"][handles], targets)
    mid = out["x"][np.isclose(P[:, 0], 0.5)]
    assert np.all(mid[:, 0] > 0.5)  # the middle moved along
    # the callback saw every Newton step of both substeps
    assert len(seen) == out["iterations"] and all("grad_inf" in r for r in seen)


def test_returning_false_stops_a_deformation():
    P, T, handles, targets = _bar()
    calls = []
    out = ecc.deform(P, T, "snh", handles=handles, targets=targets, substeps=3,
                     progress=lambda r: calls.append(r) or False)
    assert len(calls) == 1  # stopped at the first step: no further substep ran
    assert out["status"] == "Interrupted" and not out["converged"] and out["substeps"] == 1


def test_simulate_a_scene(root, tmp_path):
    scene = os.path.join(root, "scenes", "camelhead_sd.toml")
    if not os.path.exists(scene):
        scenes = sorted(f for f in os.listdir(os.path.join(root, "scenes")) if f.endswith(".toml"))
        pytest.fail(f"no camelhead_sd.toml; scenes: {scenes}")
    s = ecc.simulate(scene, out=str(tmp_path / "out"), pictures=False)
    assert s["newton_iterations"] > 0 and os.path.exists(tmp_path / "out" / "summary.json")


def test_returning_false_stops_a_scene(root, tmp_path):
    scene = os.path.join(root, "scenes", "camelhead_sd.toml")
    calls = []
    s = ecc.simulate(scene, out=str(tmp_path / "out"), pictures=False,
                     progress=lambda r: calls.append(r) or False)
    assert len(calls) == 1  # the solve stopped at its first step
    assert s["status"] == "stopped" and "interrupted" in s["stopped"]
    assert os.path.exists(tmp_path / "out" / "summary.json")


def test_a_bad_scene_raises_scene_error(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text("[mesh]\nfile = 3\n")
    with pytest.raises(ecc.SceneError):
        ecc.simulate(str(p), out=str(tmp_path / "o"))
    with pytest.raises(ecc.SceneError):
        ecc.simulate(str(tmp_path / "missing.toml"))
