"""The body of the GetFEM script (``job.py``) that :func:`threepart.getfem.write_script` writes.

Not imported by threepart to run: :data:`BODY` is the script's text below its
header and its ``PARAMS`` line, run by the interpreter that imports ``getfem``
(GetFEM 5.4's Python interface). It reads everything it needs from ``PARAMS``.
"""
from __future__ import annotations

__all__ = ["BODY"]

BODY = r'''
import json
import math
import os
import sys
import time

import numpy as np
import getfem as gf

gf.util_trace_level(0)
T0 = time.time()
E, NU, F = PARAMS["E"], PARAMS["nu"], PARAMS["f"]
H, L, D = PARAMS["h"], PARAMS["half_width"], PARAMS["depth"]
X_LO, X_HI = PARAMS["zone"]
CONTACT, BOTTOM, TOP, LEFT, RIGHT = 1, 2, 3, 4, 5


def graded(lo, hi, h, growth, far):
    """Grid lines: uniform ``h`` over [lo, hi], growing by ``growth`` outwards to -far and far."""
    core = list(np.linspace(lo, hi, max(1, int(math.ceil((hi - lo) / h))) + 1))
    left, right = [], []
    x, d = lo, h
    while x > -far:
        d *= growth
        x = max(x - d, -far)
        left.append(x)
    x, d = hi, h
    while x < far:
        d *= growth
        x = min(x + d, far)
        right.append(x)
    return np.array(left[::-1] + core + right)


def depths(h, growth, depth, layer):
    """Grid lines 0 .. depth: uniform ``h`` over ``layer``, then growing by ``growth``."""
    ys, d, y = [0.0], h, 0.0
    while y < depth:
        y = min(y + (h if y < layer else d), depth)
        if y >= layer:
            d *= growth
        ys.append(y)
    return np.array(ys)


def build():
    """The two bodies, their unknowns and every term of the model."""
    xs = graded(X_LO, X_HI, H, PARAMS["growth"], L)
    ys = depths(H, PARAMS["growth"], D, PARAMS["layer"])
    m1 = gf.Mesh("triangles grid", xs, -ys[::-1])      # the substrate, y <= 0
    m2 = gf.Mesh("triangles grid", xs, ys)             # the punch body, its mirror image, y >= 0
    tol = 1e-9 * L
    m1.set_region(CONTACT, m1.outer_faces_in_box([X_LO - tol, -tol], [X_HI + tol, tol]))
    m1.set_region(BOTTOM, m1.outer_faces_in_box([-L - tol, -D - tol], [L + tol, -D + tol]))
    m1.set_region(LEFT, m1.outer_faces_in_box([-L - tol, -D - tol], [-L + tol, tol]))
    m1.set_region(RIGHT, m1.outer_faces_in_box([L - tol, -D - tol], [L + tol, tol]))
    m2.set_region(TOP, m2.outer_faces_in_box([-L - tol, D - tol], [L + tol, D + tol]))
    mfu1, mfu2, mfl, mfm = (gf.MeshFem(m, 2) for m in (m1, m2, m1, m2))
    mfu1.set_classical_fem(2)                          # P2 displacements
    mfu2.set_classical_fem(2)
    mfl.set_classical_fem(PARAMS["lambda_degree"])     # the contact traction on the substrate
    mfm.set_classical_fem(1)                           # the cap's multiplier
    mim1, mim2, mimc = gf.MeshIm(m1, 4), gf.MeshIm(m2, 4), gf.MeshIm(m1, 6)
    md = gf.Model("real")
    md.add_fem_variable("u1", mfu1)
    md.add_fem_variable("u2", mfu2)
    md.add_filtered_fem_variable("lambda", mfl, CONTACT)
    md.add_filtered_fem_variable("mu", mfm, TOP)
    md.add_variable("U", 3)                            # the cap: U_x, U_y, its rotation
    md.add_fem_data("u1_prev", mfu1)
    md.add_fem_data("u2_prev", mfu2)
    md.add_initialized_data("lam_L", [E * NU / ((1 + NU) * (1 - 2 * NU))])   # plane strain
    md.add_initialized_data("mu_L", [E / (2 * (1 + NU))])
    md.add_isotropic_linearized_elasticity_brick(mim1, "u1", "lam_L", "mu_L")
    md.add_isotropic_linearized_elasticity_brick(mim2, "u2", "lam_L", "mu_L")
    # the substrate's base moves with the bulk strain of sigma_bulk (its uniform plane-strain field,
    # exact in the block with sigma_bulk on its sides): the base restrains the contact's
    # displacements only, as the clamped base does without a bulk stress
    md.add_fem_data("u1_base", mfu1)
    md.add_Dirichlet_condition_with_simplification("u1", BOTTOM, "u1_base")
    rigid = "[{0}(1) - {0}(3)*X(2); {0}(2) + {0}(3)*X(1)]"
    md.add_linear_term(mim2, "mu.(Test_u2 - " + rigid.format("Test_U") + ") + (u2 - "
                       + rigid.format("U") + ").Test_mu", TOP)
    for name, value in (("Pd", 0.0), ("Qd", 0.0), ("Md", 0.0), ("sbd", 0.0), ("ktheta", PARAMS["ktheta"]),
                        ("r", PARAMS["r"]), ("f", F)):
        md.add_initialized_data(name, [value])
    md.add_linear_term(mim2, "(-(Qd*Test_U(1) - Pd*Test_U(2) + Md*Test_U(3)) + ktheta*U(3)*Test_U(3))/%r"
                       % (2.0 * L), TOP)
    md.add_linear_term(mim1, "-sbd*Test_u1(1)", RIGHT)     # sigma_bulk on the substrate's sides
    md.add_linear_term(mim1, "sbd*Test_u1(1)", LEFT)
    md.add_interpolate_transformation_from_expression("T", m1, m2, "X")
    gap = "(" + PARAMS["gap"] + " + Interpolate(u2,T)(2) - u1(2))"
    slip = "(u1 - Interpolate(u2,T) - u1_prev + Interpolate(u2_prev,T))"
    md.add_linear_term(mimc, "-lambda.Test_u1 + lambda.Interpolate(Test_u2,T)", CONTACT)
    md.add_nonlinear_term(mimc, "-lambda.Test_lambda + Coulomb_friction_coupled_projection(lambda, [0;1], "
                          + slip + ", " + gap + ", f, r).Test_lambda", CONTACT)
    u2 = np.zeros(mfu2.nbdof())
    u2[1::2] = -PARAMS["delta0"]                       # start in contact: the body lowered
    md.set_variable("u2", u2)
    md.set_variable("U", np.array([0.0, -PARAMS["delta0"], 0.0]))
    return md, mfu1, mfu2, mfl, mimc, (len(xs), len(ys))


MD, MFU1, MFU2, MFL, MIMC, GRID = build()
_XY = MFU1.basic_dof_nodes()
#: the uniform field of a unit bulk stress (plane strain, sigma_yy = 0) at the substrate's dofs
BULK_FIELD = np.where(np.arange(MFU1.nbdof()) % 2 == 0, (1 - NU * NU) / E * _XY[0],
                      -NU * (1 + NU) / E * _XY[1])
SURF = MFL.basic_dof_on_region(CONTACT)
XS = MFL.basic_dof_nodes(SURF[::2])[0]
ORDER = np.argsort(XS)
NAMES = ("u1", "u2", "lambda", "mu", "U")


def solve_state(P, s, Q, sb):
    """Newton at the loads (P at x = s: the moment -P s about the origin; Q; sigma_bulk sb);
    (iterations, converged)."""
    MD.set_variable("Pd", [P])
    MD.set_variable("Qd", [Q])
    MD.set_variable("Md", [-P * s])
    MD.set_variable("sbd", [sb])
    MD.set_variable("u1_base", sb * BULK_FIELD)
    it, conv = MD.solve("max_iter", PARAMS["max_iter"], "max_res", PARAMS["max_res"] * PARAMS["P"],
                        "lsearch", "simplest", "lsolver", PARAMS["lsolver"])
    return int(it), bool(conv)


def advance(start, end, log, label):
    """From the loads ``start`` to ``end`` (each (P, s, Q, sigma_bulk), moving linearly together),
    halving a step whose Newton fails."""
    step, done = 1.0, 0.0
    while done < 1.0 - 1e-12:
        step = min(step, 1.0 - done)
        t = done + step
        P, s, Q, sb = (start[i] + t * (end[i] - start[i]) for i in range(4))
        saved = {k: MD.variable(k).copy() for k in NAMES}
        t0 = time.time()
        it, conv = solve_state(P, s, Q, sb)
        log.append({"leg": label, "P": P, "s": s, "Q": Q, "sigma_bulk": sb, "fraction": step,
                    "iterations": it, "converged": conv, "time": time.time() - t0})
        if conv:
            done = t
            MD.set_variable("u1_prev", MD.variable("u1"))
            MD.set_variable("u2_prev", MD.variable("u2"))
        else:
            for k, v in saved.items():
                MD.set_variable(k, v)
            step /= 2
            if step < PARAMS["min_step"]:
                sys.stderr.write("GETFEM-FAILED: Newton did not converge from P = %.6g, Q = %.6g, "
                                 "sigma_bulk = %.6g with a step of %.3g of the leg '%s' (%d iterations)\n"
                                 % (P, Q, sb, step * 2, label, it))
                sys.exit(3)


def surface():
    """x, p, q and the relative tangential displacement u2_x - u1_x at the substrate's surface nodes."""
    lam = MD.variable("lambda")
    x = XS[ORDER]
    pts = np.vstack([x, np.zeros_like(x)])
    u1 = gf.compute_interpolate_on(MFU1, MD.variable("u1"), pts)
    u2 = gf.compute_interpolate_on(MFU2, MD.variable("u2"), pts)
    return x, -lam[1::2][ORDER], lam[0::2][ORDER], u2[0] - u1[0]


def resultant():
    """[P, Q, moment of p about the origin] integrated from the multiplier itself."""
    return [float(gf.asm("generic", MIMC, 0, e, CONTACT, MD))
            for e in ("-lambda(2)", "lambda(1)", "-X(1)*lambda(2)")]


def write_vtu(path, x, fields):
    """The surface nodes as a polyline in a VTU file (ASCII), with point fields."""
    n = len(x)
    out = ['<?xml version="1.0"?>',
           '<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">',
           "<UnstructuredGrid>", '<Piece NumberOfPoints="%d" NumberOfCells="%d">' % (n, n - 1),
           '<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">',
           " ".join("%.17g 0 0" % v for v in x), "</DataArray></Points>", "<Cells>",
           '<DataArray type="Int64" Name="connectivity" format="ascii">',
           " ".join("%d %d" % (i, i + 1) for i in range(n - 1)), "</DataArray>",
           '<DataArray type="Int64" Name="offsets" format="ascii">',
           " ".join(str(2 * (i + 1)) for i in range(n - 1)), "</DataArray>",
           '<DataArray type="UInt8" Name="types" format="ascii">', " ".join(["3"] * (n - 1)),
           "</DataArray>", "</Cells>", "<PointData>"]
    for name, v in fields.items():
        out += ['<DataArray type="Float64" Name="%s" format="ascii">' % name,
                " ".join("%.17g" % t for t in v), "</DataArray>"]
    out += ["</PointData>", "</Piece>", "</UnstructuredGrid>", "</VTKFile>", ""]
    with open(path + ".part", "w") as fh:
        fh.write("\n".join(out))
    os.replace(path + ".part", path)


def main():
    name, log, states = PARAMS["name"], [], []
    load = (PARAMS["P"], PARAMS["s"], 0.0, 0.0)
    advance((0.0,) + load[1:], load, log, "normal")
    w0 = surface()[3]
    U0 = MD.variable("U").copy()
    for leg in PARAMS["legs"]:
        start, end = load, (leg["P"], leg["s"], leg["Q"], leg["sigma_bulk"])
        for k in range(leg["steps"]):
            t = (k + 1.0) / leg["steps"]
            nxt = end if k + 1 == leg["steps"] else tuple(a + t * (b - a) for a, b in zip(start, end))
            advance(load, nxt, log, leg["branch"])
            load = nxt
            x, p, q, w = surface()
            U = MD.variable("U")
            fname = "%s_%03d.vtu" % (name, len(states) + 1)
            write_vtu(fname, x, {"contact_pressure": p, "contact_shear": q, "slip": w - w0})
            states.append({"file": fname, "branch": leg["branch"], "P": load[0], "s": load[1],
                           "Q": load[2], "sigma_bulk": load[3],
                           "delta": float(U[0] - U0[0]), "approach": float(-U[1]),
                           "rotation": float(U[2]), "resultant": resultant(),
                           "x": x.tolist(), "p": p.tolist(), "q": q.tolist(), "slip": (w - w0).tolist()})
    last = states[-1]
    write_vtu(name + ".vtu", np.array(last["x"]), {"contact_pressure": last["p"],
                                                   "contact_shear": last["q"], "slip": last["slip"]})
    record = {"format": "threepart-getfem-1", "model": HEADER, "params": PARAMS, "states": states,
              "steps": log, "grid": list(GRID), "dofs": int(MD.nbdof()), "time": time.time() - T0,
              "getfem": gf.__version__ if hasattr(gf, "__version__") else "5.4"}
    with open(name + ".getfem.json.part", "w") as fh:
        json.dump(record, fh)
    os.replace(name + ".getfem.json.part", name + ".getfem.json")


if __name__ == "__main__":
    main()
'''
