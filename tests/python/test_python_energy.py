"""An energy written in Python (ipstep.register_energy) against its C++ twin,
the built-in Hookean spring: the same trajectory to round-off."""
import copy
import json
import os

import numpy as np
import pytest

import ipstep


def spring_energy(x, p):
    d = x[1] - x[0]
    return 0.5 * p["stiffness"] * (np.linalg.norm(d) - p["rest_length"]) ** 2


def spring_gradient(x, p):
    d = x[1] - x[0]
    length = np.linalg.norm(d)
    f = p["stiffness"] * (length - p["rest_length"]) * d / length
    return np.concatenate([-f, f])


def spring_hessian(x, p):
    d = x[1] - x[0]
    length = np.linalg.norm(d)
    n = d / length
    k, rest = p["stiffness"], p["rest_length"]
    block = k * np.outer(n, n) + k * (1 - rest / length) * (np.eye(len(d)) - np.outer(n, n))
    return np.block([[block, -block], [-block, block]])


ipstep.register_energy("py_spring", spring_energy, spring_gradient, spring_hessian,
                       terms=lambda p, free: p["pairs"], description="a Hookean spring")
ipstep.register_energy("py_spring_no_hessian", spring_energy, spring_gradient,
                       terms=lambda p, free: p["pairs"])


def scenes(source_dir, effect):
    with open(os.path.join(source_dir, "problems", "spring_pendulum.json")) as f:
        cpp = json.load(f)
    twin = copy.deepcopy(cpp)
    spring = twin.pop("springs")[0]
    twin["effects"] = ["gravity", effect]
    twin[effect] = {"pairs": [spring["nodes"]], "stiffness": spring["stiffness"],
                    "rest_length": spring["rest_length"]}
    return cpp, twin


@pytest.mark.parametrize("integrator, optimizer, effect", [
    ("newmark", "newton", "py_spring"),
    ("backward_euler", "projected_newton", "py_spring"),
    ("newmark", "gauss_newton", "py_spring_no_hessian"),
])
def test_python_spring_matches_the_builtin_spring(source_dir, integrator, optimizer, effect):
    cpp, twin = scenes(source_dir, effect)
    runs = []
    for scene in (cpp, twin):
        sim = ipstep.Simulation(scene, integrator=integrator, optimizer=optimizer, steps=150,
                                max_substeps=1)
        iterations = []
        summary = sim.run(on_step=lambda r: iterations.append(r.iterations))
        assert summary.failed == 0
        runs.append((sim.positions, sim.velocities, iterations))
    assert runs[0][2] == runs[1][2]  # the same iterations, step by step
    assert np.abs(runs[0][0] - runs[1][0]).max() < 1e-11
    assert np.abs(runs[0][1] - runs[1][1]).max() < 1e-9
    assert any(line.startswith(effect) for line in ipstep.Simulation(twin).effects)


def test_an_exception_in_the_energy_is_raised():
    def broken(x, p):
        raise RuntimeError("broken energy")

    ipstep.register_energy("py_broken", broken, broken)
    scene = {"dimension": 2, "time_step": 0.01, "steps": 3, "effects": ["py_broken"],
             "nodes": {"positions": [[0, 0]], "masses": [1]}}
    with pytest.raises(RuntimeError, match="broken energy"):
        ipstep.Simulation(scene).step()


def test_registering_a_name_twice_is_a_value_error():
    with pytest.raises(ValueError):
        ipstep.register_energy("py_spring", spring_energy, spring_gradient)
