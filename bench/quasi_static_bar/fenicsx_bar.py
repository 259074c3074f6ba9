#!/usr/bin/python3
"""One step of the benchmark bar in FEniCSx 0.5 (dolfinx, petsc4py), stopped by
ipstep's rule.

  fenicsx_bar.py MESH.msh --mode quasi_static|backward_euler --solver cholmod|gamg
                 [--tolerance 1e-5] [--dt 0.01] [--json] [--positions OUT.csv]
                 [--ksp-view]

Run it with Debian's /usr/bin/python3 (python3-dolfinx), on one MPI rank.

The problem is ipstep's scene from bar_scene.py: P1 tetrahedra, neo-Hookean
  Psi = mu/2 (tr F^T F - 3) - mu ln J + lambda/2 (ln J)^2,
gravity (0, -9.81, 0), rho = 1000, clamped on x = 0. F is constant on a P1
tetrahedron, so the one-point rule (degree 1) integrates the energy, its
gradient and its Hessian exactly; the gravity load rho g V/4 per node is the
same as ipstep's lumped one.
  quasi_static:    minimise U(u) = int Psi - rho g.u
  backward_euler:  minimise 1/(2h^2) |u - u~|^2_M + U(u), M lumped (vertex
                   quadrature), u~ = u_n + h v_n = 0 (one step from rest), i.e.
                   ipstep's E / w_U with w_U = h^2 (ipstep folds gravity into
                   its predictor instead: the same gradient).
Newton without line search, as dolfinx's NewtonSolver: assemble the gradient
f and the Hessian, solve, u -= du. Initial guess: ipstep's (u = 0; backward
Euler u = h^2 g on the free nodes, its predictor). Stopping rule, ipstep's:
  residual = h * max_i |f_i| / m_i  [m/s]  over the free nodes,
f_i the node's 3-vector of the gradient (above: already divided by w_U), m_i
the lumped node mass (rho V / 4 from each tetrahedron); stop when residual <=
tolerance (checked before every iteration, as ipstep does).
Linear solvers: cholmod = preonly + Cholesky through PETSc's CHOLMOD
interface (symbolic factorisation once, numeric every iteration: PETSc's
default when the matrix keeps its nonzero pattern; the counts are reported);
gamg = CG + GAMG, rtol 1e-8, the 6 rigid body modes as near-nullspace.

Times: setup_seconds = mesh read + function space + form compilation (JIT,
cached in ~/.cache/fenics after the first run) + matrix/vector/KSP creation;
solve_seconds = the Newton loop (assembly, factorisation or AMG setup, solves,
the stopping measure). Output: a summary on stdout, or one JSON object with
--json.
"""
import argparse
import json
import os
import sys
import time

START = time.perf_counter()
# Single-threaded: set before numpy / PETSc load their BLAS.
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import numpy as np

from bar_scene import DENSITY, GRAVITY, POISSON_RATIO, YOUNGS_MODULUS
from results import LENGTH, read_msh_nodes

try:
    import gmsh
    import ufl
    from mpi4py import MPI
    from petsc4py import PETSc
    import dolfinx
    import dolfinx.fem.petsc
    import dolfinx.io.gmshio
except ImportError as error:
    sys.exit("fenicsx_bar.py: FEniCSx is not importable (%s); install Debian's "
             "python3-dolfinx and run with /usr/bin/python3" % error)



def read_mesh(path):
    """The .msh file as a dolfinx mesh. dolfinx 0.5.2's
    gmshio.read_from_msh finalises Gmsh and then returns an undefined name
    (NameError), so this does what it means to: Gmsh reads the file, gmshio's
    model_to_mesh converts the physical group "domain"."""
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.merge(path)
        mesh, _, _ = dolfinx.io.gmshio.model_to_mesh(gmsh.model, MPI.COMM_WORLD, 0, gdim=3)
    finally:
        gmsh.finalize()
    return mesh


def rigid_body_modes(V, template):
    """The 6 rigid body modes on V's dofs (node-major, 3 per node), orthonormalised."""
    x = V.tabulate_dof_coordinates()
    x = x - x.mean(axis=0)
    n = x.shape[0]
    modes = np.zeros((3 * n, 6))
    for c in range(3):
        modes[c::3, c] = 1.0
    modes[0::3, 3], modes[1::3, 3] = -x[:, 1], x[:, 0]
    modes[1::3, 4], modes[2::3, 4] = -x[:, 2], x[:, 1]
    modes[2::3, 5], modes[0::3, 5] = -x[:, 0], x[:, 2]
    q, _ = np.linalg.qr(modes)
    vectors = []
    for k in range(6):
        vec = template.duplicate()
        vec.array[:] = q[:, k]
        vectors.append(vec)
    return PETSc.NullSpace().create(vectors=vectors)


def make_ksp(A, solver, V):
    ksp = PETSc.KSP().create(MPI.COMM_WORLD)
    ksp.setOptionsPrefix("bar_")
    opts = PETSc.Options()
    if solver == "cholmod":
        opts["bar_ksp_type"] = "preonly"
        opts["bar_pc_type"] = "cholesky"
        opts["bar_pc_factor_mat_solver_type"] = "cholmod"
    else:
        opts["bar_ksp_type"] = "cg"
        opts["bar_ksp_rtol"] = 1e-8
        opts["bar_pc_type"] = "gamg"
        A.setNearNullSpace(rigid_body_modes(V, A.createVecRight()))
    ksp.setOperators(A)
    ksp.setFromOptions()
    return ksp


def solve(args):
    import_seconds = time.perf_counter() - START
    t_setup = time.perf_counter()
    mesh = read_mesh(args.mesh)
    t_mesh = time.perf_counter() - t_setup

    t_forms = time.perf_counter()
    V = dolfinx.fem.VectorFunctionSpace(mesh, ("Lagrange", 1))
    u, v, du = dolfinx.fem.Function(V), ufl.TestFunction(V), ufl.TrialFunction(V)
    mu = YOUNGS_MODULUS / (2.0 * (1.0 + POISSON_RATIO))
    lmbda = YOUNGS_MODULUS * POISSON_RATIO / ((1.0 + POISSON_RATIO) * (1.0 - 2.0 * POISSON_RATIO))
    mu, lmbda = dolfinx.fem.Constant(mesh, mu), dolfinx.fem.Constant(mesh, lmbda)
    rho = dolfinx.fem.Constant(mesh, DENSITY)
    g = dolfinx.fem.Constant(mesh, np.array(GRAVITY))
    h = args.dt

    F = ufl.Identity(3) + ufl.grad(u)
    J = ufl.det(F)
    psi = mu / 2 * (ufl.tr(F.T * F) - 3) - mu * ufl.ln(J) + lmbda / 2 * ufl.ln(J) ** 2
    dx = ufl.dx(metadata={"quadrature_degree": 1})  # exact for P1 (see above)
    energy = psi * dx - rho * ufl.dot(g, u) * dx
    if args.mode == "backward_euler":
        # u~ = 0: 1/(2h^2) |u|^2_M with the lumped mass of the vertex rule.
        dx_lumped = ufl.dx(metadata={"quadrature_rule": "vertex", "quadrature_degree": 1})
        energy += rho / (2 * h * h) * ufl.dot(u, u) * dx_lumped
    gradient = ufl.derivative(energy, u, v)
    hessian = ufl.derivative(gradient, u, du)
    gradient_form = dolfinx.fem.form(gradient)
    hessian_form = dolfinx.fem.form(hessian)
    ones = dolfinx.fem.Constant(mesh, np.ones(3))
    mass_form = dolfinx.fem.form(rho * ufl.dot(ones, v) * dx)
    t_forms = time.perf_counter() - t_forms

    clamped = dolfinx.fem.locate_dofs_geometrical(V, lambda x: np.isclose(x[0], 0.0))
    bc = dolfinx.fem.dirichletbc(np.zeros(3), clamped, V)
    free = np.ones(V.dofmap.index_map.size_local, dtype=bool)
    free[clamped] = False

    mass = dolfinx.fem.petsc.assemble_vector(mass_form).array.reshape(-1, 3)[:, 0]
    b = dolfinx.fem.petsc.create_vector(gradient_form)
    A = dolfinx.fem.petsc.create_matrix(hessian_form)
    ksp = make_ksp(A, args.solver, V)
    step = A.createVecRight()
    setup_seconds = time.perf_counter() - t_setup

    if args.mode == "backward_euler":  # ipstep's initial guess: its predictor x_n + h^2 g
        u.x.array.reshape(-1, 3)[free] = h * h * np.array(GRAVITY)

    events = {name: PETSc.Log.Event(name)
              for name in ("MatCholFctrSym", "MatCholFctrNum", "PCSetUp")}
    counts0 = {name: e.getPerfInfo()["count"] for name, e in events.items()}

    def measure():
        with b.localForm() as local:
            local.set(0.0)
        dolfinx.fem.petsc.assemble_vector(b, gradient_form)
        f = b.array.reshape(-1, 3)
        return h * np.max(np.linalg.norm(f[free], axis=1) / mass[free])

    history, linear_iterations = [], []
    converged, failure = False, ""
    t_matrix = t_linear = 0.0
    t_solve = time.perf_counter()
    iterations = 0
    while True:
        residual = measure()
        history.append(residual)
        if residual <= args.tolerance:
            converged = True
            break
        if iterations == args.max_iterations or not np.isfinite(residual):
            failure = "iteration limit" if np.isfinite(residual) else "non-finite residual"
            break
        t = time.perf_counter()
        A.zeroEntries()
        dolfinx.fem.petsc.assemble_matrix(A, hessian_form, bcs=[bc])
        A.assemble()
        dolfinx.fem.petsc.set_bc(b, [bc], x0=u.vector, scale=-1.0)  # 0 on the clamp
        t_matrix += time.perf_counter() - t
        t = time.perf_counter()
        ksp.solve(b, step)
        t_linear += time.perf_counter() - t
        if ksp.getConvergedReason() < 0:
            failure = "linear solver failed (KSP reason %d)" % ksp.getConvergedReason()
            break
        linear_iterations.append(ksp.getIterationNumber())
        if args.ksp_view and iterations == 0:
            ksp.view()
        u.vector.axpy(-1.0, step)
        iterations += 1
    solve_seconds = time.perf_counter() - t_solve
    counts = {name: e.getPerfInfo()["count"] - counts0[name] for name, e in events.items()}

    x = V.tabulate_dof_coordinates()
    disp = u.x.array.reshape(-1, 3)
    tip = np.isclose(x[:, 0], LENGTH)
    result = {
        "code": "fenicsx", "config": args.solver, "mode": args.mode,
        "mesh": args.mesh, "free_dofs": int(3 * free.sum()),
        "iterations": iterations, "converged": converged, "failure": failure,
        "residual": history[-1],
        "residual_history": history, "linear_iterations": linear_iterations,
        "solve_seconds": solve_seconds, "setup_seconds": setup_seconds,
        "matrix_seconds": t_matrix, "linear_solve_seconds": t_linear,
        "import_seconds": import_seconds, "mesh_seconds": t_mesh, "forms_seconds": t_forms,
        "symbolic_factorisations": counts["MatCholFctrSym"],
        "numeric_factorisations": counts["MatCholFctrNum"],
        "pc_setups": counts["PCSetUp"],
        "tip_uy": float(disp[tip, 1].mean()),
        "max_u": float(np.linalg.norm(disp, axis=1).max()),
        "tolerance": args.tolerance, "dt": h,
        "petsc": "%d.%d.%d" % PETSc.Sys.getVersion(), "dolfinx": dolfinx.__version__,
    }
    if args.positions:  # in the file's node order (ipstep's), rest + displacement
        rest = np.array(read_msh_nodes(args.mesh))
        def key(p):
            return tuple(np.round(p, 9))
        where = {key(p): i for i, p in enumerate(x)}
        final = rest + disp[[where[key(p)] for p in rest]]
        with open(args.positions, "w") as f:
            f.write("node,x,y,z\n")
            for i, p in enumerate(final):
                f.write("%d,%.17g,%.17g,%.17g\n" % (i, p[0], p[1], p[2]))
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("mesh", help="Gmsh .msh file from make_mesh.py")
    parser.add_argument("--mode", choices=["quasi_static", "backward_euler"], required=True)
    parser.add_argument("--solver", choices=["cholmod", "gamg"], required=True)
    parser.add_argument("--tolerance", type=float, default=1e-5,
                        help="stopping rule [m/s] (default 1e-5)")
    parser.add_argument("--dt", type=float, default=0.01, help="time step h [s] (default 0.01)")
    parser.add_argument("--max-iterations", type=int, default=100,
                        help="Newton limit (default 100, ipstep's)")
    parser.add_argument("--json", action="store_true",
                        help="print one JSON object instead of a summary")
    parser.add_argument("--positions",
                        help="write the final positions as CSV node,x,y,z (file node order)")
    parser.add_argument("--ksp-view", action="store_true",
                        help="print PETSc's KSP view after the first solve")
    args = parser.parse_args()
    if MPI.COMM_WORLD.size != 1:
        sys.exit("fenicsx_bar.py: run on one MPI rank")

    PETSc.Log.begin()  # event counts: symbolic / numeric factorisations
    r = solve(args)
    if args.json:
        print(json.dumps(r))
        return
    print("FEniCSx %s (PETSc %s), %s, %s: %d free DOFs"
          % (r["dolfinx"], r["petsc"], r["mode"], r["config"], r["free_dofs"]))
    print("  %s after %d Newton iterations, residual %.3e m/s (tolerance %g)"
          % ("converged" if r["converged"] else "NOT converged (%s)" % r["failure"],
             r["iterations"], r["residual"], r["tolerance"]))
    print("  residuals: " + " ".join("%.2e" % v for v in r["residual_history"]))
    if r["config"] == "gamg":
        print("  CG iterations: %s" % r["linear_iterations"])
    else:
        print("  factorisations: %d symbolic, %d numeric"
              % (r["symbolic_factorisations"], r["numeric_factorisations"]))
    print("  Newton loop %.3f s (Hessian assembly %.3f s, linear solves %.3f s)"
          % (r["solve_seconds"], r["matrix_seconds"], r["linear_solve_seconds"]))
    print("  setup %.3f s (mesh %.3f s, forms %.3f s); Python imports %.3f s"
          % (r["setup_seconds"], r["mesh_seconds"], r["forms_seconds"], r["import_seconds"]))
    print("  tip u_y %.12e m, max |u| %.12e m" % (r["tip_uy"], r["max_u"]))


if __name__ == "__main__":
    main()
