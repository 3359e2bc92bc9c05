"""Energy evaluation agrees with `ecc eval --json` (the same code path) on
hard cases, and bad input raises EnergyError."""

import json
import os
import subprocess

import numpy as np
import pytest

import ecc

# (psi file, builtin name, params, F) — rest, uniform scale, repeated σ,
# σi+σj≈0, tiny σ, inversion, huge stretch, outside a barrier's domain.
R = np.array([[0.6, -0.8], [0.8, 0.6]])
CASES = [
    ("snh.psi", "snh", {"mu": 1.0, "lambda": 10.0}, np.eye(3)),
    ("snh.psi", "snh", {"mu": 2.0, "lambda": 7.0}, 1.7 * np.eye(3)),
    ("snh.psi", "snh", {}, np.diag([1.2, 1.2, 0.8])),
    ("snh.psi", "snh", {}, np.diag([1.0, 1.0, -1e-3])),
    ("snh.psi", "snh", {}, np.diag([0.9, 1.1, -0.7])),
    ("snh.psi", "snh", {}, np.diag([1e3, 1.0, 1e-3])),
    ("arap.psi", "arap", {}, R @ np.diag([1.3, 0.5])),
    ("arap.psi", "arap", {}, np.diag([1.0, -1.0 + 1e-9])),
    ("arap.psi", "arap", {}, np.array([[0.3, 1.2, 0.1], [-0.4, 0.9, 0.2], [0.05, -0.1, 1.4]])),
    ("sd2.psi", "sd", {}, np.diag([1.0, 1.0])),
    ("sd2.psi", "sd", {}, np.diag([1e-4, 2.0])),
    ("sd2.psi", "sd", {}, np.diag([1.0, -0.5])),
    ("sd3.psi", "sd", {}, np.diag([1.5, 1.5, 1.5])),
    ("neohookean.psi", "neohookean", {}, np.diag([1.0, 1.0, -0.2])),
    ("ogden.psi", "ogden", {}, np.diag([2.0, 0.5, 1.0])),
    ("hencky2.psi", "hencky", {}, np.diag([3.0, 0.25])),
]


def cli_eval(ecc_bin, root, psi, params, F):
    rows = "; ".join(" ".join(repr(float(x)) for x in row) for row in F)
    cmd = [ecc_bin, "eval", os.path.join(root, "energies", "psi", psi), "--F", rows, "--json"]
    for k, v in params.items():
        cmd += ["--param", f"{k}={v!r}"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def as_array(x):
    return np.array(x, dtype=float) if x is not None else np.nan


def same(a, b):
    """Equal, NaN where the CLI wrote null; bit-for-bit up to 1 ulp-ish."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert a.shape == b.shape
    assert np.array_equal(np.isnan(a), np.isnan(b)), (a, b)
    m = ~np.isnan(a)
    assert np.allclose(a[m], b[m], rtol=1e-13, atol=1e-300), np.max(np.abs(a[m] - b[m]))


def nulls(x):
    """JSON null → NaN, recursively."""
    if x is None:
        return float("nan")
    if isinstance(x, list):
        return [nulls(v) for v in x]
    return x


@pytest.mark.parametrize("case", CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_eval_agrees_with_the_cli(ecc_bin, root, case):
    psi, name, params, F = case
    j = cli_eval(ecc_bin, root, psi, params, F)
    kw = {k + ("_" if k == "lambda" else ""): v for k, v in params.items()}
    e = ecc.Energy.builtin(name, **kw)
    f = ecc.Energy.from_file(os.path.join(root, "energies", "psi", psi), **kw)
    for energy in (e, f):
        r = energy.eval(F)
        same(r["sigma"], j["sigma"])
        if j["domain"] == "outside":
            assert r["psi"] == np.inf
            assert np.isnan(r["gradient"]).all() and np.isnan(r["hessian"]).all()
            continue
        same(r["psi"], nulls(j["psi"]))
        same(r["gradient"], nulls(j["gradient"]))
        same(r["hessian"], nulls(j["hessian"]))
        same(r["hessian_projected"], nulls(j["hessian_projected"]))
        same(r["eigenvalues"], nulls(j["eigenvalues"]))


def test_outside_the_domain_is_inf_and_nan():
    r = ecc.Energy.builtin("neohookean").eval(np.diag([1.0, 1.0, -0.2]))
    assert r["psi"] == np.inf and np.isnan(r["hessian"]).all()


def test_a_batch_equals_single_evaluations_in_any_memory_order():
    rng = np.random.default_rng(1)
    Fs = np.eye(3) + 0.3 * rng.standard_normal((7, 3, 3))
    e = ecc.Energy.builtin("snh", mu=1, lambda_=10)
    batch = e.eval(np.asfortranarray(Fs))
    for i, F in enumerate(Fs):
        one = e.eval(F.tolist())
        for k in ("psi", "gradient", "P", "hessian", "hessian_projected", "eigenvalues"):
            np.testing.assert_array_equal(batch[k][i], one[k])
    # P is ∂Ψ/∂F; the gradient is its column-major vec
    np.testing.assert_array_equal(batch["P"][2].T.ravel(), batch["gradient"][2])
    assert batch["hessian"].shape == (7, 9, 9) and batch["psi"].shape == (7,)


def test_the_gradient_is_the_derivative_of_psi():
    e = ecc.Energy("param mu = 1\npsi = mu*(I2 - 2*I1 + d) + (J - 1)^2", mu=3)
    F = np.array([[1.1, 0.2], [-0.1, 0.8]])
    P = e.eval(F)["P"]
    h = 1e-6
    for r in range(2):
        for c in range(2):
            dF = np.zeros((2, 2))
            dF[r, c] = h
            fd = (e.eval(F + dF)["psi"] - e.eval(F - dF)["psi"]) / (2 * h)
            assert abs(fd - P[r, c]) < 1e-6


def test_text_energies_report_and_emit():
    e = ecc.Energy("I2 - 2*I1 + d")
    assert e.eval(np.eye(2))["psi"] == 0.0
    assert e.dims == [2, 3]
    assert e.report().startswith("# Energy")
    rs = ecc.Energy.builtin("arap").emit_rust(type_name="MyArap")
    assert "struct MyArap" in rs and "Energy<2>" in rs
    assert ecc.Energy.builtin("snh", mu=2).params == [("mu", 2.0), ("lambda", 10.0)] or dict(
        ecc.Energy.builtin("snh", mu=2).params
    )["mu"] == 2.0


def test_syntax_errors_carry_line_column_and_diagnostic():
    with pytest.raises(ecc.EnergyError) as info:
        ecc.Energy("param mu = 1\npsi = mu*I2 + nu")
    err = info.value
    assert isinstance(err, ecc.Error)
    assert (err.line, err.column) == (2, 15)
    assert "unknown identifier `nu`" in err.diagnostic and "2:15" in err.diagnostic


@pytest.mark.parametrize(
    "make",
    [
        lambda: ecc.Energy.builtin("no_such_energy"),
        lambda: ecc.Energy.builtin("snh", nu=1),
        lambda: ecc.Energy.builtin("snh", mu=float("nan")),
        lambda: ecc.Energy.from_file("/no/such/file.psi"),
        lambda: ecc.Energy.builtin("mips").eval(np.eye(3)),
        lambda: ecc.Energy.builtin("snh").eval(np.eye(4)),
        lambda: ecc.Energy.builtin("snh").eval(np.ones((2, 3))),
        lambda: ecc.Energy.builtin("snh").eval([[1, 0], [0, float("nan")]]),
        lambda: ecc.Energy.builtin("snh").eval("not a matrix"),
    ],
)
def test_bad_input_raises_energy_error(make):
    with pytest.raises(ecc.EnergyError):
        make()
