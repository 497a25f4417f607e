"""Contact laws written in NumPy, for teaching: a law is a function over a
batch of contacts (a dict of NumPy columns) that a scene uses like a
plug-in's model once registered with plab.register_model.

    batch["props"]          the instance's property values, by key
    batch["dt"]             the step, s (0: forces re-evaluated, history kept)
    batch["active"]         bool, rows in the activity range (gap <= range)
    batch["gap"]            surface gap, m (negative: overlap)
    batch["normal"]         M x 3, unit, end 1 to end 2
    batch["rel_velocity"]   M x 3, v(end 2) - v(end 1) at the contact point, m/s
    batch["eff_mass"]       m1 m2 / (m1 + m2), kg
    batch["history"]        M x slots, in and out; a tangential vector arrives
                            turned into the current contact plane
  out (zeros on entry):
    batch["force"]          M x 3, on end 2, N
    batch["stiffness"]      N/m, for the stable step
    batch["strain_energy"], batch["slip_energy"], batch["dashpot_energy"]   J

The arrays are copies, valid after the call too; write the outputs in place
(batch["force"][:] = ...) or assign arrays of the same shape.
"""
import numpy as np


def _dot(a, b):
    # summed in the C++ law's order (x, y, then z), for the same bits
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1] + a[:, 2] * b[:, 2]


def linear(batch):
    """The `linear` model's law (thesis eqs. 21-29, physics/dem/include/plab/
    dem/linear_law.hpp) with both dashpots always on (dp_mode full): a normal
    spring kn * overlap, an incremental shear spring -ks vs dt capped at
    fric * Fn (Coulomb), dashpots 2 beta sqrt(m k) on each. The operations
    are the C++ law's, in its order, so the forces are the same bits."""
    p = batch["props"]
    kn, ks, fric, rgap = p["kn"], p["ks"], p["fric"], p["rgap"]
    cn = 2.0 * p["dp_nratio"] * np.sqrt(kn)
    cs = 2.0 * p["dp_sratio"] * np.sqrt(ks)
    inv_kn, inv_ks = 1.0 / kn, (1.0 / ks if ks > 0.0 else 0.0)
    dt = batch["dt"]
    n, v = batch["normal"], batch["rel_velocity"]

    overlap = rgap - batch["gap"]                            # eq. 21
    active = ~(overlap < 0.0)
    vn = _dot(v, n)
    vs = v - vn[:, None] * n
    fn_lin = kn * overlap                                    # eq. 22
    fs_old = batch["history"][:, 0:3]
    fs_trial = fs_old - (ks * dt) * vs                       # eqs. 23-25
    fs_max = fric * fn_lin                                   # eq. 26
    fs_mag2 = _dot(fs_trial, fs_trial)
    sliding = fs_mag2 > fs_max * fs_max
    with np.errstate(divide="ignore", invalid="ignore"):
        cap = np.where(sliding, fs_max / np.sqrt(fs_mag2), 1.0)
    fs = fs_trial * cap[:, None]
    sqrt_m = np.sqrt(batch["eff_mass"])
    fn_d = (-cn * sqrt_m) * vn                               # eq. 27
    fs_d = ((-cs) * sqrt_m)[:, None] * vs                    # eq. 28

    strain = 0.5 * fn_lin * fn_lin * inv_kn + 0.5 * _dot(fs, fs) * inv_ks
    dashpot = -(fn_d * vn + _dot(fs_d, vs)) * dt
    force = (fn_lin + fn_d)[:, None] * n + fs + fs_d
    slip = np.abs(_dot(0.5 * (fs + fs_old), (fs_trial - fs) * inv_ks))

    on = active[:, None]
    batch["force"][:] = np.where(on, force, 0.0)
    batch["history"][:, 0:3] = np.where(on, fs, 0.0)
    batch["strain_energy"][:] = np.where(active, strain, 0.0)
    batch["dashpot_energy"][:] = np.where(active, dashpot, 0.0)
    batch["slip_energy"][:] = np.where(active & sliding & (ks > 0.0), slip, 0.0)
    batch["stiffness"][:] = np.where(active, max(kn, ks), 0.0)


LINEAR_PROPERTIES = [
    # key, name, unit, default, min, max, doc
    ("kn", "normal stiffness", "N/m", 1e5, 0.0, np.inf, "normal spring kn * overlap (eq. 22)"),
    ("ks", "shear stiffness", "N/m", 0.0, 0.0, np.inf, "incremental shear spring -ks * vs * dt (eqs. 23-25)"),
    ("fric", "friction coefficient", "1", 0.0, 0.0, np.inf, "shear force capped at fric * Fn (eq. 26)"),
    ("dp_nratio", "normal critical damping ratio", "1", 0.0, 0.0, 1.0, "normal dashpot 2 beta sqrt(m kn) (eq. 27)"),
    ("dp_sratio", "shear critical damping ratio", "1", 0.0, 0.0, 1.0, "shear dashpot 2 beta sqrt(m ks) (eq. 28)"),
    ("rgap", "reference gap", "m", 0.0, -np.inf, np.inf, "active while the surface gap <= rgap"),
]
LINEAR_HISTORY = [
    # name, doc, default, negated when the ends swap, first slot of a tangential vector
    ("shear_force_x", "shear force on end 2, x, N", 0.0, True, True),
    ("shear_force_y", "shear force on end 2, y, N", 0.0, True, False),
    ("shear_force_z", "shear force on end 2, z, N", 0.0, True, False),
]
