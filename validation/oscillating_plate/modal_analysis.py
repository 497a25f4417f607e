#!/usr/bin/env python3
"""The oscillating plate's first-mode period from the linearised SPH solid.

    python3 modal_analysis.py [--rows 5] [--order 1] [--force-order N]
                              [--hourglass A] [--h-over-dp 1.3]

Small deformations about the square lattice of scene.json (L 0.2 m, H 0.02 m,
E 2 MPa, nu 0.3975, rho 1000, 4 clamp columns, Wendland C2, h 1.3 dp), with
no artificial viscosity or stress: the sph_solid pass and model reduce to

    l_i = sum_j (u_j - u_i) (x) g_ij                      (Islam eq. 19)
    sigma_i = lambda tr(eps_i) I + 2 G eps_i             (plane strain, Islam sec. 3.1 and eq. 17 linearised)
    f_i = sum_j V_i sigma_i g_ij - V_j sigma_j g_ji      (Islam eq. 15 as the model writes it)

so f = -K u, K = Df^T (V C) Dl, and the period is that of the lowest
eigenpair of K u = omega^2 m u (inverse iteration). g_ij is the pair's
gradient weight, by --order:
  0  V_j grad_i W_ij                                  (kernel_correction none)
  1  V_j B_i grad_i W_ij, B_i = A_i^-1                 (Chen 1999, Islam eq. 20: the code's `all`)
  2  the quadratic (second-order) correction: l exact for a quadratic
     velocity field, e.g. pure bending, at every particle (not in the code)
--force-order takes another g for the momentum equation (default: --order).
--hourglass A adds a linearised pair penalty on the part of u_j - u_i that
the mean of the two particles' gradients does not predict,
  delta_ij = ((l_i + l_j)/2 d_ij - (u_j - u_i)) . n_ij,
  f_j = -f_i = A E V_i V_j W_ij / r_ij^2 delta_ij n_ij
(the form of Ganzenmueller 2015's hourglass control, with the gradients in
place of his deformation gradients; not in the code).

Printed: the period error against the plane-strain plate theory of the case
(omega^2 = E H^2 k^4 / (12 rho (1 - nu^2)), kL = 1.875104); the error of the
Rayleigh quotient of the exact mode (Euler-Bernoulli shape, plane-strain
Poisson term), which is the scheme's consistency error alone, the eigen
error being lower still where the discrete mode relaxes; and the part of the
discrete mode that alternates from column to column (odd-even, zig-zag),
per row, in units of the largest u_x. At --rows 5 --order 1 this reproduces
the code's small-amplitude period (plab run with Vf 0.001, epsilon 0) to
0.01 %. 10 rows takes about a minute. numpy only.
"""
import argparse

import numpy as np

L, H, E, NU, RHO, CLAMP_COLUMNS, KL = 0.2, 0.02, 2e6, 0.3975, 1000.0, 4, 1.875104


def wendland_c2(r, h):
    """W and dW/dr of the 2D Wendland C2 kernel (support 2h)."""
    q = r / h
    c = 7 / (4 * np.pi * h * h)
    w = np.where(q < 2, c * (1 - q / 2) ** 4 * (2 * q + 1), 0.0)
    dw = np.where(q < 2, c * (-5 * q * (1 - q / 2) ** 3) / h, 0.0)
    return w, dw


def lattice(rows):
    dp = H / rows
    nx = int(round(L / dp)) + CLAMP_COLUMNS
    xs = -CLAMP_COLUMNS * dp + (np.arange(nx) + 0.5) * dp
    ys = (np.arange(rows) + 0.5) * dp
    x, y = np.meshgrid(xs, ys, indexing="ij")  # column-major: particle c * rows + r
    return np.c_[x.ravel(), y.ravel()], dp


def neighbours(p, h):
    """Per particle: its neighbours' indices, d = x_j - x_i, r."""
    out = []
    for i in range(len(p)):
        d = p - p[i]
        r = np.hypot(d[:, 0], d[:, 1])
        js = np.nonzero((r > 0) & (r < 2 * h))[0]
        out.append((js, d[js], r[js]))
    return out


def gradient_weights(nbrs, volume, h, order):
    """g_ij for every particle i, an array (len(js), 2)."""
    g = []
    for js, d, r in nbrs:
        _, dw = wendland_c2(r, h)
        w = -volume * dw / r  # V_j grad_i W_ij = w d
        if order == 0:
            g.append(w[:, None] * d)
        elif order == 1:
            a = (w[:, None, None] * d[:, :, None] * d[:, None, :]).sum(0)
            g.append((w[:, None] * d) @ np.linalg.inv(a))
        else:
            p = np.c_[d, d[:, 0] ** 2, d[:, 0] * d[:, 1], d[:, 1] ** 2]
            m = (w[:, None, None] * p[:, :, None] * p[:, None, :]).sum(0)
            g.append((w[:, None] * p) @ np.linalg.inv(m)[:, :2])
    return g


def local_d(i, js, gi):
    """The 4 x 2k block of D for particle i: l_i (xx, xy, yx, yy) from u of [i, js]."""
    cols = np.r_[i, js]
    d = np.zeros((4, 2, len(cols)))
    for a in range(2):
        for b in range(2):
            d[2 * a + b, a, 1:] = gi[:, b]
            d[2 * a + b, a, 0] = -gi[:, b].sum()
    dofs = (2 * cols[None, :] + np.arange(2)[:, None]).ravel(order="F")
    return d.transpose(0, 2, 1).reshape(4, -1), dofs


def elasticity(volume):
    g = E / (2 * (1 + NU))
    lam = E / (3 * (1 - 2 * NU)) - 2 * g / 3
    c = np.zeros((4, 4))
    for a in range(2):
        for b in range(2):
            for e in range(2):
                for f in range(2):
                    c[2 * a + b, 2 * e + f] = lam * (a == b) * (e == f) + g * ((a == e) * (b == f) + (a == f) * (b == e))
    return volume * c


def stiffness(p, dp, h, order, force_order, hourglass):
    nbrs = neighbours(p, h)
    volume = dp * dp
    gl = gradient_weights(nbrs, volume, h, order)
    gf = gl if force_order == order else gradient_weights(nbrs, volume, h, force_order)
    c = elasticity(volume)
    n = 2 * len(p)
    k = np.zeros((n, n))
    blocks = []
    for i, (js, _, _) in enumerate(nbrs):
        dl, dofs = local_d(i, js, gl[i])
        df, _ = local_d(i, js, gf[i])
        k[np.ix_(dofs, dofs)] += df.T @ c @ dl
        blocks.append((dl, dofs))
    if hourglass > 0:
        for i, (js, d, r) in enumerate(nbrs):
            w, _ = wendland_c2(r, h)
            for j, dij, rij, wij in zip(js, d, r, w):
                if j < i:
                    continue
                nij = dij / rij
                row = np.zeros(n)
                for end in (i, j):  # (l_end d) . n / 2 = sum_ab n_a l_ab d_b / 2
                    dl, dofs = blocks[end]
                    coef = np.array([nij[0] * dij[0], nij[0] * dij[1], nij[1] * dij[0], nij[1] * dij[1]]) / 2
                    row[dofs] += coef @ dl
                row[2 * j:2 * j + 2] -= nij
                row[2 * i:2 * i + 2] += nij
                stiff = hourglass * E * volume * volume * wij / rij ** 2
                nz = np.nonzero(row)[0]
                k[np.ix_(2 * j + np.arange(2), nz)] -= stiff * np.outer(nij, row[nz])
                k[np.ix_(2 * i + np.arange(2), nz)] += stiff * np.outer(nij, row[nz])
    return k


def exact_mode(p):
    """Euler-Bernoulli first mode with the plane-strain Poisson term (sigma_yy = 0)."""
    k = KL / L
    x, yc = p[:, 0], p[:, 1] - H / 2
    s = (np.cos(KL) + np.cosh(KL)) / (np.sin(KL) + np.sinh(KL))
    phi = np.cosh(k * x) - np.cos(k * x) - s * (np.sinh(k * x) - np.sin(k * x))
    dphi = k * (np.sinh(k * x) + np.sin(k * x) - s * (np.cosh(k * x) - np.cos(k * x)))
    d2phi = k * k * (np.cosh(k * x) + np.cos(k * x) - s * (np.sinh(k * x) + np.sin(k * x)))
    u = np.zeros(2 * len(x))
    u[0::2] = -yc * dphi
    u[1::2] = phi + NU / (1 - NU) * d2phi * yc ** 2 / 2
    return u


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rows", type=int, default=5)
    ap.add_argument("--order", type=int, default=1, choices=(0, 1, 2))
    ap.add_argument("--force-order", type=int, choices=(0, 1, 2))
    ap.add_argument("--hourglass", type=float, default=0.0)
    ap.add_argument("--h-over-dp", type=float, default=1.3)
    ap.add_argument("--axial", action="store_true",
                    help="the first axial mode instead (shift-invert about 4L / sqrt(E / ((1 - nu^2) rho)))")
    a = ap.parse_args()
    force_order = a.order if a.force_order is None else a.force_order
    p, dp = lattice(a.rows)
    k = stiffness(p, dp, a.h_over_dp * dp, a.order, force_order, a.hourglass)
    free = p[:, 0] > 0
    dofs = np.repeat(free, 2)
    k = k[np.ix_(dofs, dofs)]
    pf = p[free]
    mass = RHO * dp * dp
    u0 = exact_mode(pf)
    if a.axial:
        omega_axial = np.pi / (2 * L) * np.sqrt(E / ((1 - NU * NU) * RHO))
        u = np.zeros(2 * len(pf))
        u[0::2] = np.sin(np.pi * pf[:, 0] / (2 * L))
        shifted_inv = np.linalg.inv(k - omega_axial ** 2 * mass * np.eye(len(k)))
        for _ in range(200):
            u = shifted_inv @ u
            u /= np.linalg.norm(u)
        lam = (u @ k @ u) / (mass * (u @ u))
        print(f"rows {a.rows}, gradient order {a.order}, hourglass {a.hourglass:g}: axial period error "
              f"{100 * (omega_axial / np.sqrt(lam) - 1):+.2f} % (u_x share of the mode "
              f"{np.linalg.norm(u[0::2]) / np.linalg.norm(u):.3f})")
        return
    k_inv = np.linalg.inv(k)
    u, lam = u0.copy(), 0.0
    for _ in range(500):
        u2 = k_inv @ (mass * u)
        lam_new = (u @ u) / (u @ u2)
        u = u2 / np.linalg.norm(u2)
        if abs(lam_new - lam) < 1e-13 * lam_new:
            break
        lam = lam_new
    omega_theory = np.sqrt(E * H * H * (KL / L) ** 4 / (12 * RHO * (1 - NU * NU)))
    rayleigh = (u0 @ k @ u0) / (mass * (u0 @ u0))
    print(f"rows {a.rows}, gradient order {a.order}, force order {force_order}, hourglass {a.hourglass:g}, "
          f"h/dp {a.h_over_dp:g}")
    print(f"  period error (eigen)              {100 * (omega_theory / np.sqrt(lam_new) - 1):+.2f} %")
    print(f"  period error (exact mode, Rayleigh) {100 * (omega_theory / np.sqrt(rayleigh) - 1):+.2f} %")
    # the odd-even (zig-zag) part of the eigenmode along x at mid-length, per row: the
    # second difference of a column-alternating pattern (-1)^c a is 4a (-1)^c, of a
    # smooth field dp^2 u'' the same in neighbouring columns, so half the difference
    # of two neighbouring second differences / 4 is a
    u *= np.sign(u @ u0)
    columns = len(pf) // a.rows
    mid = columns // 2

    def zigzag(v):
        v = v.reshape(columns, a.rows)
        s2 = (v[mid - 1:mid + 2] - 2 * v[mid:mid + 3] + v[mid + 1:mid + 4]) / 4
        return np.abs(s2[0] - 2 * s2[1] + s2[2]) / 4 / np.abs(v).max()
    print("  zig-zag amplitude at mid-length per row (bottom first), of the largest |u_x| and |u_y|:")
    print("    u_x " + " ".join(f"{z:.4f}" for z in zigzag(u[0::2])))
    print("    u_y " + " ".join(f"{z:.4f}" for z in zigzag(u[1::2])))

if __name__ == "__main__":
    main()
