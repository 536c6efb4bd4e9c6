"""nsbridge.lcp against the C++ solvers of the command line, on Siconos's LCP collection, and
against hand-solved problems."""
import json
import subprocess

import numpy as np
import pytest

import nsbridge

SOLVERS = ["lemke", "pgs", "nfb", "enum"]


def test_a_two_by_two_problem_solved_by_hand():
    # M = [[2, 1], [1, 2]], q = [-5, -6]: both z > 0 so w = 0, M z = -q gives
    # z = [4/3, 7/3] (Cramer: det 3, z1 = (10 - 6)/3, z2 = (12 - 5)/3).
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    q = np.array([-5.0, -6.0])
    # The solvers stop at a residual of `tolerance`: PGS's z is then ~4e-12 off at the default
    # 1e-12, so the comparison to 1e-12 asks for a residual of 1e-14.
    for solver in SOLVERS:
        r = nsbridge.lcp.solve(M, q, solver=solver, tolerance=1e-14)
        assert r.status == "solved", solver
        np.testing.assert_allclose(r.z, [4.0 / 3.0, 7.0 / 3.0], rtol=0, atol=1e-12)
        np.testing.assert_allclose(r.w, [0.0, 0.0], rtol=0, atol=1e-12)
        assert isinstance(r.z, np.ndarray) and r.z.dtype == np.float64


@pytest.mark.parametrize("solver", SOLVERS)
def test_the_collection_gives_what_the_command_line_gives(source, nsbridge_exe, solver):
    # The same C++ solver on the same file: z, status and iterations equal bit for bit
    # (the command line prints shortest round-trip numbers).
    files = sorted((source / "data" / "siconos-lcp").glob("*.dat"))
    assert len(files) >= 20
    for f in files:
        cli = subprocess.run([str(nsbridge_exe), "lcp", str(f), "--solver", solver, "--json"],
                             capture_output=True, text=True)
        if cli.returncode == 2:
            continue  # a problem this solver refuses as input (e.g. enumeration size)
        expected = json.loads(cli.stdout)
        M, q = nsbridge.lcp.read_dat(str(f))
        r = nsbridge.lcp.solve(M, q, solver=solver, tolerance=expected["tolerance"])
        assert r.status == expected["status"], f.name
        assert r.iterations == expected["iterations"], f.name
        if expected["z"]:
            assert list(r.z) == expected["z"], f.name


def test_a_solver_failure_is_a_status_not_an_exception():
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    q = np.array([-5.0, -6.0])
    r = nsbridge.lcp.solve(M, q, solver="pgs", max_iterations=1)
    assert r.status == "max_iterations"


def test_bad_input_raises_input_error_with_the_message():
    with pytest.raises(nsbridge.InputError, match="solver"):
        nsbridge.lcp.solve(np.eye(2), np.zeros(2), solver="simplex")
    with pytest.raises(nsbridge.InputError, match="unknown option 'tol'"):
        nsbridge.lcp.solve(np.eye(2), np.zeros(2), tol=1e-3)
    with pytest.raises(nsbridge.InputError):
        nsbridge.lcp.solve(np.eye(2), np.array([np.nan, 0.0]))
    assert issubclass(nsbridge.InputError, ValueError)


def test_frictional_problem_builds_eq6_of_one_frictionless_contact():
    # One contact, mu = 0: the LCP is G_NN Lambda_N + gdot_N,free + eps gdot_N- (size m = 1).
    M, q = nsbridge.lcp.frictional_problem(np.array([[0.5]]), np.array([-2.0]),
                                            np.array([-2.0]), np.array([0.5]), np.array([0.0]))
    np.testing.assert_array_equal(M, [[0.5]])
    np.testing.assert_array_equal(q, [-2.0 + 0.5 * -2.0])


def test_criterion_equals_the_command_line(nsbridge_exe):
    cli = subprocess.run([str(nsbridge_exe), "criterion", "--skew", "30", "--width", "10",
                          "--length", "30", "--friction", "0.2", "--json"],
                         capture_output=True, text=True, check=True)
    assert nsbridge.criterion(30.0, 10.0, 30.0, 0.2) == json.loads(cli.stdout)
    with pytest.raises(nsbridge.InputError, match="width"):
        nsbridge.criterion(30.0, -1.0, 30.0, 0.2)


def test_criterion_refuses_a_non_finite_result_as_the_command_line_does(nsbridge_exe):
    # W/L = 1e-300 / 1e300 underflows to 0, so eta = sin(2a) / (2 W/L) is infinite: no answer.
    cli = subprocess.run([str(nsbridge_exe), "criterion", "--skew", "30", "--width", "1e-300",
                          "--length", "1e300", "--friction", "0.2"], capture_output=True, text=True)
    assert cli.returncode == 2 and "make eta non-finite" in cli.stderr
    with pytest.raises(nsbridge.InputError, match=r"width: W = 1e-300 m and L = 1e\+300 m "
                                                  r"\(W/L = 0, mu = 0.2\) make eta non-finite"):
        nsbridge.criterion(30.0, 1e-300, 1e300, 0.2)
    with pytest.raises(nsbridge.InputError, match="make eta non-finite"):
        nsbridge.criterion(0.0, 4.9e-324, 1.0, 0.5)
