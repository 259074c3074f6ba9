"""ctest example_tether (check.cmake): the tether from Python, through the
module of this project (ipstep_tether: ipstep's module with the tether).

  check_python.py SCENE.json POSITIONS.csv BAD.json

POSITIONS.csv: tether_ipstep's --positions after 20 Newmark steps of SCENE.
BAD.json: SCENE with a negative stiffness.
"""
import sys

import numpy as np

import ipstep_tether as ipstep


def main():
    scene, positions_csv, bad = sys.argv[1:]
    sim = ipstep.Simulation(scene, integrator="newmark")
    assert "tether: 25 terms" in "\n".join(sim.effects), sim.effects
    summary = sim.run(20)
    assert summary.steps_done == 20 and summary.failed == 0, summary
    program = np.loadtxt(positions_csv, delimiter=",", skiprows=1)[:, 1:]
    gap = np.abs(sim.positions - program).max()
    assert gap < 1e-12, f"Python and tether_ipstep differ by {gap} m"
    try:
        ipstep.Simulation(bad)
    except ValueError as error:
        assert "tether.stiffness" in str(error), error
    else:
        raise AssertionError("a negative tether stiffness was accepted")
    print(f"same trajectory as tether_ipstep (20 steps, {gap:.1e} m)")


if __name__ == "__main__":
    main()
