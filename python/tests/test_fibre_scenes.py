"""Scenes with fibre energies through ``ecc.simulate`` (#16): ``[fibers]
energy`` by library name or as the fibre part of a ``.psi``, ``[energy] psi``
with ``fiber a`` (isotropic part on the body, fibre part on the ``[fibers]``
directions), the same numbers as ``ecc sim``, and the refusals."""

import json
import os
import subprocess

import pytest

import ecc

MUSCLE = """fiber a
param mu = 1.0
param lambda = 10.0
param k = 1.0
let alpha = 1 + mu/lambda - mu/((d+1)*lambda)
psi = mu/2*(IC - d) + lambda/2*(J - alpha)^2 - mu/2*log(IC + 1) + k/2*(I5 - 1)^2
"""


def bar(energy, fibres):
    return f"""
frames = 2
[mesh]
generate = "bar"
resolution = 2
[energy]
{energy}
{fibres}
[effects]
gravity = [0, -0.05, 0]
[[effects.handles]]
plane = {{ point = [-1.99, 0, 0], normal = [-1, 0, 0] }}
[[effects.handles]]
plane = {{ point = [1.99, 0, 0], normal = [1, 0, 0] }}
keys = [ {{ frame = 2, translate = [0.3, 0, 0.2] }} ]
"""


def lib(root, stem):
    return os.path.join(root, "energies", "psi", f"{stem}.psi")


def run(tmp_path, name, text):
    p = tmp_path / f"{name}.toml"
    p.write_text(text)
    return ecc.simulate(str(p), out=str(tmp_path / f"out-{name}"), pictures=False)


def frames(s):
    return [(f["iterations"], f["elastic_energy"], f["total_energy"]) for f in s["frames"]]


def assert_same_run(a, b, rel=1e-9):
    fa, fb = frames(a), frames(b)
    assert len(fa) == 3 and a["converged_frames"] == 2
    assert [t["name"] for t in a["terms"]] == ["elastic", "fibre", "gravity"]
    for x, y in zip(fa, fb):
        assert x[0] == y[0], (fa, fb)
        for u, v in zip(x[1:], y[1:]):
            assert abs(u - v) <= rel * max(abs(u), 1.0), (fa, fb)


def test_a_psi_fibre_energy_equals_the_library_one(root, tmp_path):
    snh = 'name = "snh"\nparams = { mu = 1.0, lambda = 10.0 }'
    fibres = '[fibers]\nenergy = "{}"\nparams = {{ mu = 50.0 }}\ndirection = [1, 0, 1]'
    by_name = run(tmp_path, "name", bar(snh, fibres.format("fibre-stvk")))
    by_psi = run(tmp_path, "psi", bar(snh, fibres.format(lib(root, "fibre_stvk"))))
    assert_same_run(by_name, by_psi)
    plain = run(tmp_path, "plain", bar(snh, ""))
    assert frames(plain) != frames(by_name)


def test_energy_psi_with_a_fibre_part_is_both_parts_as_in_the_cli(root, tmp_path, ecc_bin):
    (tmp_path / "muscle.psi").write_text(MUSCLE)
    text = bar('psi = "muscle.psi"\nparams = { mu = 1.5, k = 20.0 }', "[fibers]\ndirection = [1, 0, 1]")
    whole = run(tmp_path, "whole", text)
    split = run(tmp_path, "split", bar(
        f'psi = "{lib(root, "snh")}"\nparams = {{ mu = 1.5 }}',
        '[fibers]\nenergy = "fibre-stvk"\nparams = { mu = 20.0 }\ndirection = [1, 0, 1]',
    ))
    assert_same_run(whole, split)
    assert whole["fibre_energy"]["params"]["k"] == 20.0 and whole["energy"]["params"]["mu"] == 1.5
    # the CLI runs the same scene through the same interpreter: same numbers
    cli = subprocess.run(
        [ecc_bin, "sim", str(tmp_path / "whole.toml"), "-q", "--json", "--no-pictures",
         "-o", str(tmp_path / "out-cli")],
        capture_output=True, text=True,
    )
    assert cli.returncode == 0, cli.stderr
    assert_same_run(whole, json.loads(cli.stdout), rel=1e-12)


def test_fibre_parts_are_never_dropped(tmp_path):
    (tmp_path / "muscle.psi").write_text(MUSCLE)
    cases = [
        (bar('psi = "muscle.psi"', ""), "add a `[fibers]` section"),
        (bar('name = "snh"', '[fibers]\nenergy = "muscle.psi"\ndirection = [1, 0, 0]'),
         "has an isotropic part besides its fibre part"),
        (bar('psi = "muscle.psi"', '[fibers]\nenergy = "fibre-arap"\ndirection = [1, 0, 0]'),
         "conflicts with energy.psi"),
        (bar('name = "snh"', '[fibers]\nenergy = "snh"\ndirection = [1, 0, 0]'),
         "is an isotropic energy"),
    ]
    for k, (text, want) in enumerate(cases):
        with pytest.raises(ecc.SceneError) as e:
            run(tmp_path, f"bad{k}", text)
        assert want in str(e.value), str(e.value)
