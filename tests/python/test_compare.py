"""ipstep.compare against the ipstep_compare program: the same table (iterations,
failed steps, errors), and the same CSV."""
import csv
import math
import os
import subprocess

import pytest

import ipstep

ARGS = dict(integrators=["backward_euler", "newmark"], optimizers=["newton", "projected_newton"])


def test_compare_reproduces_ipstep_compare(tmp_path):
    program = os.environ.get("IPSTEP_COMPARE")
    if not program:
        pytest.skip("IPSTEP_COMPARE (the ipstep_compare binary) not set")
    program_csv = tmp_path / "program.csv"
    # The program runs while Python does (compare releases the GIL).
    process = subprocess.Popen([program, "--scene=cloth", "--steps=20",
                                "--integrators=" + ",".join(ARGS["integrators"]),
                                "--optimizers=" + ",".join(ARGS["optimizers"]),
                                "--compare_output=" + str(program_csv)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    python_csv = tmp_path / "python.csv"
    records = ipstep.compare("cloth", steps=20, csv=python_csv, **ARGS)
    assert process.wait() == 0
    with open(program_csv) as f:
        rows = list(csv.DictReader(f))
    assert len(records) == len(rows) == 4
    for record, row in zip(records, rows):
        assert set(record) == set(row)
        for key in ("integrator", "optimizer", "steps", "failed_steps", "diverged_at",
                    "termination", "reference"):
            assert str(record[key]) == row[key], key
        for key in ("iterations_per_step", "position_error", "max_energy_drift",
                    "reference_error"):
            assert record[key] == pytest.approx(float(row[key]), rel=1e-12, abs=0), key
    with open(python_csv) as f:
        python_rows = list(csv.DictReader(f))
    for a, b in zip(python_rows, rows):
        assert {k: v for k, v in a.items() if k != "ms_per_step"} == \
            {k: v for k, v in b.items() if k != "ms_per_step"}


def test_compare_records_make_a_data_frame_shape():
    records = ipstep.compare("oscillator", integrators=["symplectic_euler", "newmark"],
                             optimizers=["newton"])
    assert [r["integrator"] for r in records] == ["symplectic_euler", "newmark"]
    assert records[0]["optimizer"] == "" and records[1]["optimizer"] == "newton"
    assert records[1]["reference"] == "exact solution" or "exact" in records[1]["reference"]
    assert all(isinstance(r["iterations_per_step"], float) for r in records)
    with pytest.raises(ValueError, match="OptimizerOptions.optimizer"):
        ipstep.compare("oscillator", optimizers=["newtn"])


def test_bench_rows_are_ipstep_bench_csv_rows(tmp_path):
    out = tmp_path / "bench.csv"
    records = ipstep.bench("oscillator", integrators=["newmark"], optimizers=["newton", "lbfgs"],
                           dts=[0.1, 0.05], csv=out)
    assert len(records) == 4
    with open(out) as f:
        rows = list(csv.DictReader(f))
    assert [r["optimizer"] for r in rows] == [r["optimizer"] for r in records]
    for record, row in zip(records, rows):
        assert set(record) == set(row)
        assert record["status"] == row["status"] == "ok"
        assert record["position_error"] == pytest.approx(float(row["position_error"]), rel=1e-12)
    # Second order: halving dt quarters the error (Newmark, exact reference).
    ratio = records[0]["position_error"] / records[2]["position_error"]
    assert 3.5 < ratio < 4.5
