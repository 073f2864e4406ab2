#!/usr/bin/env python3
"""Independent SciPy implementation of the evhi contact solver (see README.md and
shared/MODEL.md): P1 triangles, plane strain Kelvin-Voigt, backward Euler, frictionless
contact on Gamma_3 with a piecewise-linear normal compliance law and the unilateral limit g.

One factorisation of K = A + kB before the loop, the Schur complement on the contact
normal dofs, a projected semismooth Newton method with line search for each step's
m = n + 1 dimensional problem, one sparse solve per step."""
import argparse
import csv
import os
import statistics
import sys
import time
import tomllib

import numpy as np
import scipy
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

SCEN_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "scenarios")


def load_scenario(name):
    path = name if name.endswith(".toml") else os.path.join(SCEN_DIR, name + ".toml")
    with open(path, "rb") as fh:
        sc = tomllib.load(fh)
    if sc.get("geometry", {}).get("supports", "paper") != "paper":
        sys.exit("only the paper's supports are implemented")
    if sc["loads"].get("f0_modulation", 0.0) != 0.0 or "history" in sc["loads"]:
        sys.exit("only constant, unmodulated loads are implemented")
    law = sc["law"]
    if any(j != 0.0 for j in law.get("jumps", [])) or law.get("p_left", 0.0) != 0.0:
        sys.exit("only continuous laws with p = 0 left of the first breakpoint are implemented")
    return sc


class Law:
    """p(s) continuous, piecewise linear: 0 left of bp[0], slope c[b] on branch b."""

    def __init__(self, breakpoints, slopes):
        self.bp = np.asarray(breakpoints, float)
        self.c = np.asarray(slopes, float)
        assert len(self.c) == len(self.bp) + 1 and self.c[0] == 0.0
        # value of p and of j at each breakpoint
        self.p_at = np.zeros(len(self.bp))
        self.j_at = np.zeros(len(self.bp))
        for i in range(1, len(self.bp)):
            d = self.bp[i] - self.bp[i - 1]
            self.p_at[i] = self.p_at[i - 1] + self.c[i] * d
            self.j_at[i] = self.j_at[i - 1] + self.p_at[i - 1] * d + 0.5 * self.c[i] * d * d

    def branch(self, s):
        return np.searchsorted(self.bp, s, side="left")  # s == bp[i] -> branch i (left)

    def eval(self, s, b=None):
        """p(s), j(s) and the slope of the branch b (default: the branch holding s)."""
        if b is None:
            b = self.branch(s)
        i = np.maximum(b - 1, 0)
        d = np.where(b == 0, 0.0, s - self.bp[i])
        p0, j0 = np.where(b == 0, 0.0, self.p_at[i]), np.where(b == 0, 0.0, self.j_at[i])
        c = self.c[b]
        return p0 + c * d, j0 + p0 * d + 0.5 * c * d * d, c


def mesh(n):
    """Nodes on the (n+1) x (n/2+1) grid of spacing 2h = 2/n; each square cell cut by its
    lower-left to upper-right diagonal (MODEL.md, Discretisation)."""
    assert n % 4 == 0
    ny = n // 2
    xs, ys = np.linspace(0.0, 2.0, n + 1), np.linspace(0.0, 1.0, ny + 1)
    X, Y = np.meshgrid(xs, ys)  # node (i, j) -> j * (n + 1) + i
    xy = np.column_stack([X.ravel(), Y.ravel()])
    i, j = np.meshgrid(np.arange(n), np.arange(ny))
    ll = (j * (n + 1) + i).ravel()
    lr, ul = ll + 1, ll + n + 1
    ur = ul + 1
    tri = np.vstack([np.column_stack([ll, lr, ur]), np.column_stack([ll, ur, ul])])
    return xy, tri


def assemble(n, sc):
    """Viscosity A, elasticity B, load vector f over the free dofs; contact data."""
    xy, tri = mesh(n)
    nn = len(xy)
    m = sc["material"]
    E, nu = m["E"], m["kappa"]
    lam_g, mu2_g = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (1 + nu)  # (G t)_ij = a tr t d_ij + b t_ij
    # element geometry (vectorised): gradients of the barycentric functions
    P = xy[tri]  # (ne, 3, 2)
    x, y = P[:, :, 0], P[:, :, 1]
    bx = np.stack([y[:, 1] - y[:, 2], y[:, 2] - y[:, 0], y[:, 0] - y[:, 1]], 1)
    cy = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], 1)
    det = x[:, 0] * bx[:, 0] + x[:, 1] * bx[:, 1] + x[:, 2] * bx[:, 2]  # = 2 * area
    area = 0.5 * det
    dx, dy = bx / det[:, None], cy / det[:, None]
    # strain-displacement matrix, element dofs (ux0, uy0, ux1, uy1, ux2, uy2), Voigt with gamma_xy
    ne = len(tri)
    Bm = np.zeros((ne, 3, 6))
    Bm[:, 0, 0::2] = dx
    Bm[:, 1, 1::2] = dy
    Bm[:, 2, 0::2] = dy
    Bm[:, 2, 1::2] = dx

    def stiffness(a, b):
        D = np.array([[a + b, a, 0.0], [a, a + b, 0.0], [0.0, 0.0, 0.5 * b]])
        return np.matmul(Bm.transpose(0, 2, 1), D @ Bm) * area[:, None, None]

    edof = np.empty((ne, 6), dtype=np.int64)
    edof[:, 0::2], edof[:, 1::2] = 2 * tri, 2 * tri + 1
    rows = np.repeat(edof, 6, axis=1).ravel()
    cols = np.tile(edof, (1, 6)).ravel()
    nd = 2 * nn
    Bfull = sp.csr_matrix((stiffness(lam_g, mu2_g).ravel(), (rows, cols)), shape=(nd, nd))
    Afull = sp.csr_matrix((stiffness(m["alpha"], m["beta"]).ravel(), (rows, cols)), shape=(nd, nd))
    # consistent P1 loads for constant f0 (area/3 per vertex) and f2 on the top edges
    f = np.zeros(nd)
    f0, f2 = np.asarray(sc["loads"]["f0"], float), np.asarray(sc["loads"]["f2"], float)
    for c in range(2):
        np.add.at(f, 2 * tri.ravel() + c, np.repeat(area / 3.0, 3) * f0[c])
    top = np.flatnonzero(np.isclose(xy[:, 1], 1.0))
    top = top[np.argsort(xy[top, 0])]
    elen = np.diff(xy[top, 0])
    for c in range(2):
        np.add.at(f, 2 * top[:-1] + c, 0.5 * elen * f2[c])
        np.add.at(f, 2 * top[1:] + c, 0.5 * elen * f2[c])
    # Gamma_1: x in {0, 2} and y >= 0.5 clamped (eliminated)
    clamped = (np.isclose(xy[:, 0], 0.0) | np.isclose(xy[:, 0], 2.0)) & (xy[:, 1] >= 0.5 - 1e-12)
    free = np.flatnonzero(~np.repeat(clamped, 2))
    A = Afull[free][:, free].tocsc()
    B = Bfull[free][:, free].tocsc()
    # contact nodes: y == 0, ordered by x; contact dof = u_y (u_nu = -u_y)
    cn = np.flatnonzero(np.isclose(xy[:, 1], 0.0))
    cn = cn[np.argsort(xy[cn, 0])]
    pos = -np.ones(nd, dtype=np.int64)
    pos[free] = np.arange(len(free))
    cdof = pos[2 * cn + 1]
    assert np.all(cdof >= 0)
    h = 1.0 / n
    w = np.full(len(cn), 2 * h)
    w[[0, -1]] = h  # trapezoidal weights, segment length 2h
    return dict(A=A, B=B, f=f[free], free=free, cdof=cdof, cx=xy[cn, 0], w=w, xy=xy)


def factorise(K, method):
    if method == "splu":  # SuperLU, symmetric mode: MMD on A^T + A, diagonal pivots
        lu = spla.splu(K, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options=dict(SymmetricMode=True))
        return lu.solve
    if method == "splu-colamd":  # SuperLU defaults (COLAMD, partial pivoting)
        return spla.splu(K).solve
    if method == "cholmod":  # optional: CHOLMOD via the PyPI wheel sksparse-minimal
        from sksparse_minimal import SparseCholesky
        return SparseCholesky(K).solve_A
    if method == "umfpack":
        return spla.factorized(K)  # UMFPACK if scikit-umfpack is installed, else SuperLU
    raise ValueError(method)


def solve_step(S, r0, kw, g, law, r, tol=1e-15, maxit=100):
    """Minimise q(r) = 1/2 (r - r0)^T S (r - r0) + sum kw_i j(r_i) over r <= g by a projected
    semismooth Newton method (Bertsekas' two-metric projection) with Armijo line search."""
    dS = np.diag(S)

    def q_grad(r):
        p, j, _ = law.eval(r)
        Sr = S @ (r - r0)
        return 0.5 * (r - r0) @ Sr + kw @ j, Sr + kw * p, p

    r = np.minimum(r, g)
    q, gr, p = q_grad(r)
    scale = max(np.max(np.abs(r)), np.max(np.abs(r0)), 1e-300)
    full, prev = False, None
    for it in range(1, maxit + 1):
        res = np.max(np.abs(r - np.minimum(g, r - gr / dS)))
        eps = min(res, 1e-3 * g)
        act = (r >= g - eps) & (gr <= 0.0)
        inn = ~act
        # branch of each free node; at a breakpoint, the side the gradient points to
        b = law.branch(r)
        onbp = np.isin(r, law.bp) & (gr < 0.0)
        b = np.where(onbp, b + 1, b)
        # done: below tolerance, or a full Newton step kept every node on its piece (q is
        # quadratic there, so that step landed exactly on the minimiser)
        if res <= tol * scale or (full and np.array_equal(act, prev[0])
                                  and np.array_equal(b[inn], prev[1][inn])):
            return r, it - 1, res / scale
        prev = (act, b)
        _, _, c = law.eval(r, b)
        H = S + np.diag(kw * c)
        d = np.zeros_like(r)
        d[act] = g - r[act]
        if inn.any():
            rhs = -gr[inn] - H[np.ix_(inn, act)] @ d[act]
            try:
                d[inn] = sla.solve(H[np.ix_(inn, inn)], rhs, assume_a="pos")
            except (sla.LinAlgError, ValueError):
                d[inn] = -gr[inn] / dS[inn]  # not positive definite: gradient step
        t = 1.0
        while True:
            rt = np.minimum(g, r + t * d)
            qt, grt, pt = q_grad(rt)
            if qt <= q + 1e-4 * gr @ (rt - r) or t < 1e-12:
                break
            t *= 0.5
        if t < 1e-12:  # fall back to a projected gradient step
            rt = np.minimum(g, r - gr / np.max(np.linalg.eigvalsh(S)))
            qt, grt, pt = q_grad(rt)
        full = t == 1.0
        r, q, gr, p = rt, qt, grt, pt
    raise RuntimeError(f"Newton did not converge: residual {res / scale:.3e}")


def run(n, steps, sc, method, recovery):
    t0 = time.perf_counter()
    d = assemble(n, sc)
    A, B, f, cdof, w = d["A"], d["B"], d["f"], d["cdof"], d["w"]
    T, g = sc["T"], sc["g"]
    k = T / steps
    law = Law(sc["law"]["breakpoints"], sc["law"]["slopes"])
    K = (A + k * B).tocsc()
    t1 = time.perf_counter()
    solve = factorise(K, method)
    t2 = time.perf_counter()
    N, m = K.shape[0], len(cdof)
    EC = np.zeros((N, m))
    EC[cdof, np.arange(m)] = 1.0
    W = solve(EC)  # K^{-1} E_C^T, N x m
    Sinv = W[cdof]
    Sinv = 0.5 * (Sinv + Sinv.T)
    S = sla.inv(Sinv, overwrite_a=False)
    S = 0.5 * (S + S.T)
    kw = k * w
    lam_min = np.min(np.linalg.eigvalsh(S + np.diag(kw * law.c.min())))
    t3 = time.perf_counter()
    u = np.zeros(N)
    r = np.zeros(m)
    its = 0
    for step in range(1, steps + 1):
        bvec = A @ u + k * f
        ufree = solve(bvec)
        r0 = -ufree[cdof]
        r, it, _ = solve_step(S, r0, kw, g, law, r)
        its += it
        z = S @ (r0 - r)  # contact reaction, added at the contact y-dofs
        if recovery == "dense":
            u = ufree + W @ z
        else:
            bz = bvec.copy()
            bz[cdof] += z
            u = solve(bz)
    t4 = time.perf_counter()
    return dict(d=d, u=u, r=r, z=z, kw=kw, law=law, g=g, B=B, N=N, its=its, lam_min=lam_min,
                assembly_s=t1 - t0, factorisation_s=t2 - t1, condensation_s=t3 - t2,
                steps_s=t4 - t3, total_s=t4 - t0)


def read_csv(path):
    with open(path) as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    return list(csv.DictReader(lines))


def check(res, ref_dir):
    d = res["d"]
    u = res["u"]
    un = -u[d["cdof"]]
    rows = read_csv(os.path.join(ref_dir, "contact.csv"))
    xr = np.array([float(r_["x"]) for r_ in rows])
    unr = np.array([float(r_["u_nu"]) for r_ in rows])
    assert np.allclose(xr, d["cx"], atol=1e-12), "contact node coordinates differ"
    err_un = np.max(np.abs(un - unr)) / np.max(np.abs(unr))
    p, _, _ = res["law"].eval(un)
    mu = np.where(un >= res["g"] * (1 - 1e-8), res["z"] / res["kw"] - p, 0.0)
    s1r = np.array([float(r_["sigma_nu1"]) for r_ in rows])
    s2r = np.array([float(r_["sigma_nu2"]) for r_ in rows])
    err_s = max(np.max(np.abs(-p - s1r)), np.max(np.abs(-mu - s2r))) / np.max(np.abs(s1r + s2r))
    # nodal field (evhi writes a subset of the nodes)
    full = np.zeros(2 * len(d["xy"]))
    full[d["free"]] = u
    key = {(round(x_, 9), round(y_, 9)): i for i, (x_, y_) in enumerate(d["xy"])}
    nrows = read_csv(os.path.join(ref_dir, "nodes.csv"))
    idx = np.array([key[(round(float(r_["x"]), 9), round(float(r_["y"]), 9))] for r_ in nrows])
    ur = np.array([[float(r_["ux"]), float(r_["uy"])] for r_ in nrows])
    err_nodes = np.max(np.abs(full.reshape(-1, 2)[idx] - ur)) / np.max(np.abs(ur))
    summ = read_csv(os.path.join(ref_dir, "summary.csv"))[0]
    en_ref = float(summ["energy_norm_T"])
    return dict(err_u_nu=err_un, err_sigma=err_s, err_nodes=err_nodes, energy_norm_ref=en_ref,
                dofs_ref=int(summ["dofs"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default="figure")
    ap.add_argument("--n", type=int, default=64)
    ap.add_argument("--steps", type=int, default=None)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--factor", default="splu", choices=["splu", "splu-colamd", "cholmod", "umfpack"])
    ap.add_argument("--recovery", default="dense", choices=["dense", "solve"],
                    help="dense: u = K^-1 b + (K^-1 E_C^T) z (one sparse solve per step); "
                         "solve: a second sparse solve per step")
    ap.add_argument("--check", default=None, help="evhi output directory to compare with")
    ap.add_argument("--out", default=None, help="write contact.csv here")
    a = ap.parse_args()
    steps = a.steps or a.n
    sc = load_scenario(a.scenario)
    cols = ["n", "steps", "dofs", "assembly_s", "factorisation_s", "condensation_s", "steps_s",
            "total_s", "newton_its", "energy_norm_T", "energy_norm_T_sqrtuBu"]
    extra = ["rel_err_u_nu", "rel_err_sigma_nu", "rel_err_nodes", "rel_diff_energy_norm"]
    print(",".join(cols + (extra if a.check else [])))
    runs = []
    for _ in range(a.repeat):
        res = run(a.n, steps, sc, a.factor, a.recovery)
        u = res["u"]
        uBu = float(u @ (res["B"] @ u))
        row = dict(n=a.n, steps=steps, dofs=res["N"], assembly_s=res["assembly_s"],
                   factorisation_s=res["factorisation_s"], condensation_s=res["condensation_s"],
                   steps_s=res["steps_s"], total_s=res["total_s"], newton_its=res["its"],
                   energy_norm_T=np.sqrt(uBu / 2), energy_norm_T_sqrtuBu=np.sqrt(uBu))
        vals = [row[c] for c in cols]
        if a.check:
            ck = check(res, a.check)
            row.update(rel_err_u_nu=ck["err_u_nu"], rel_err_sigma_nu=ck["err_sigma"],
                       rel_err_nodes=ck["err_nodes"],
                       rel_diff_energy_norm=row["energy_norm_T"] / ck["energy_norm_ref"] - 1)
            vals += [row[c] for c in extra]
        print(",".join(f"{v:.6g}" if isinstance(v, float) else str(v) for v in vals), flush=True)
        runs.append(row)
    med = {c: statistics.median(r_[c] for r_ in runs) for c in runs[0]}
    print(f"# median of {a.repeat} run(s); scenario {sc['name']}, factorisation {a.factor} "
          f"(scipy {scipy.__version__}, numpy {np.__version__}), recovery {a.recovery}; "
          f"lambda_min(S + k diag(w) c_min) = {res['lam_min']:.6g}")
    print("median," + ",".join(f"{med[c]:.6g}" if isinstance(med[c], float) else str(med[c])
                               for c in cols + (extra if a.check else [])))
    if a.check:
        print(f"# energy norm ||u||_E = sqrt(u^T B u / 2) = {runs[-1]['energy_norm_T']:.16g}, "
              f"evhi energy_norm_T = {ck['energy_norm_ref']:.16g}; evhi dofs = {ck['dofs_ref']}")
    if a.out:
        os.makedirs(a.out, exist_ok=True)
        un = -res["u"][res["d"]["cdof"]]
        np.savetxt(os.path.join(a.out, "contact.csv"), np.column_stack([res["d"]["cx"], un]),
                   delimiter=",", header="x,u_nu", comments="", fmt="%.17g")


if __name__ == "__main__":
    main()
