"""The contract a contact law keeps, checked on a law written in Python, as
tests/contact_models/contract_test.cpp checks every plug-in's model:

- its description is well formed (every property has a unit and a default
  inside its range; history slot names are unique);
- no force, energy or stiffness outside the activity range;
- the opposite force when the two ends swap (normal and relative velocity
  reversed, the history slots that say so negated);
- objectivity: the contact turned by a rotation gives the force turned by it;
- the same rows from a batch of one and from a batch of many;
- no NaN or infinity at extreme inputs (overlaps of a radius, speeds of
  1e3 m/s, masses from 1e-12 to 1e6 kg);
- a positive stiffness on an active row (the stable timestep needs it).

    failures = plab.contract.check(law, properties, history, range="rgap", values={"kn": 1e5, ...})

returns the list of failures (empty when the law keeps the contract); each
names the rule and the first row that breaks it. It calls the law directly on
batches it makes, as the host would hand them over (plab.laws documents the
columns), so it needs no scene.
"""
import numpy as np

_OUTPUTS = ("strain_energy", "slip_energy", "dashpot_energy")


def _props(properties, overrides=None):
    p = {key: float(default) for key, _name, _unit, default, _lo, _hi, _doc in properties}
    p.update(overrides or {})
    return p


def _batch(props, gap, normal, rel_velocity, eff_mass, history, dt=1e-5, dim=3):
    rows = len(gap)
    rng = props.get("_range", 0.0)
    batch = {
        "props": {k: v for k, v in props.items() if not k.startswith("_")},
        "dt": dt, "dim": dim, "with_wall": False,
        "active": np.asarray(gap, dtype=float) <= rng,
        "gap": np.array(gap, dtype=float),
        "normal": np.array(normal, dtype=float).reshape(rows, 3),
        "rel_velocity": np.array(rel_velocity, dtype=float).reshape(rows, 3),
        "eff_mass": np.array(eff_mass, dtype=float),
        "history": np.array(history, dtype=float).reshape(rows, -1).copy(),
        "force": np.zeros((rows, 3)),
        "stiffness": np.zeros(rows),
    }
    for key in _OUTPUTS:
        batch[key] = np.zeros(rows)
    return batch


def _random_contacts(rows, slots, rng, props, overlap_scale=1e-4, speed=0.1, dim=3):
    normal = rng.normal(size=(rows, 3))
    if dim == 2:
        normal[:, 2] = 0.0
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    velocity = rng.normal(scale=speed, size=(rows, 3))
    history = rng.normal(scale=1e-2, size=(rows, slots))
    gap = props.get("_range", 0.0) - rng.uniform(0.0, overlap_scale, size=rows)
    mass = rng.uniform(1e-4, 1e-2, size=rows)
    return gap, normal, velocity, mass, history


def _turned(history, tangential, rotation):
    out = history.copy()
    for first in tangential:
        out[:, first:first + 3] = history[:, first:first + 3] @ rotation.T
    return out


def _run(law, batch):
    law(batch)
    return batch


def _first_bad(mask):
    rows = np.flatnonzero(mask)
    return int(rows[0]) if len(rows) else None


def check(law, properties, history=(), range=None, values=None, seed=7):
    """The contract on `law` (a function over a batch) with its description
    (plab.register_model's `properties` and `history`); `range` names the
    property that is the activity range (a gap), as for register_model;
    `values` sets properties away from their defaults (a default of 0, a
    stiffness say, would make most rules hold trivially)."""
    failures = []
    keys = [p[0] for p in properties]
    for key, _name, unit, default, lo, hi, _doc in properties:
        if not unit:
            failures.append(f"description: property {key} has no unit")
        if not (lo <= default <= hi):
            failures.append(f"description: property {key}'s default {default} is outside [{lo}, {hi}]")
    names = [h[0] for h in history]
    if len(set(names)) != len(names) or len(set(keys)) != len(keys):
        failures.append("description: repeated property or history names")
    if range is not None and range not in keys:
        failures.append(f"description: the range property {range} is not a property")
    negated = np.array([bool(h[3]) for h in history], dtype=bool)
    tangential = [i for i, h in enumerate(history) if len(h) > 4 and h[4]]
    slots = max(len(history), 1)

    unknown = sorted(set(values or {}) - set(keys))
    if unknown:
        raise ValueError(f"values: no property {', '.join(unknown)}; properties: {', '.join(keys)}")
    props = _props(properties, values)
    props["_range"] = props[range] if range is not None else 0.0
    rng = np.random.default_rng(seed)
    gap, normal, velocity, mass, hist = _random_contacts(64, slots, rng, props)
    hist = hist[:, :len(history)] if history else np.zeros((64, 0))
    base = _run(law, _batch(props, gap, normal, velocity, mass, hist))
    failures += _outside_range(law, props, normal, velocity, mass, hist)
    failures += _swapped(law, props, base, gap, normal, velocity, mass, hist, negated)
    failures += _objective(law, props, base, gap, normal, velocity, mass, hist, tangential, rng)
    failures += _batch_size(law, props, base, gap, normal, velocity, mass, hist)
    failures += _extremes(law, props, slots if history else 0, rng)
    bad = _first_bad(~(base["stiffness"] > 0))
    if bad is not None:
        failures.append(f"stable step: row {bad} is active with stiffness {base['stiffness'][bad]}")
    return failures


def _outside_range(law, props, normal, velocity, mass, hist):
    gap = np.full(len(mass), props["_range"]) + np.geomspace(1e-9, 1e-2, len(mass))
    out = _run(law, _batch(props, gap, normal, velocity, mass, hist))
    moved = np.any(out["force"] != 0, axis=1) | (out["stiffness"] != 0)
    for key in _OUTPUTS:
        moved |= out[key] != 0
    bad = _first_bad(moved)
    return [] if bad is None else [f"outside the range: row {bad} (gap {gap[bad]:.3g} m) has a force, energy or stiffness"]


def _close(a, b, scale):
    return np.abs(a - b) <= 1e-12 * scale + 1e-9 * np.abs(b)


def _swapped(law, props, base, gap, normal, velocity, mass, hist, negated):
    turned_history = np.where(negated[None, :], -hist, hist) if hist.size else hist
    out = _run(law, _batch(props, gap, -normal, -velocity, mass, turned_history))
    scale = np.abs(base["force"]).max() + 1e-300
    bad = _first_bad(~np.all(_close(out["force"], -base["force"], scale), axis=1))
    return [] if bad is None else [f"ends swapped: row {bad} gives {out['force'][bad]} against -{base['force'][bad]}"]


def _rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q @ np.diag(np.sign(np.diag(r)))
    return q if np.linalg.det(q) > 0 else -q


def _objective(law, props, base, gap, normal, velocity, mass, hist, tangential, rng):
    rotation = _rotation(rng)
    out = _run(law, _batch(props, gap, normal @ rotation.T, velocity @ rotation.T, mass,
                           _turned(hist, tangential, rotation) if hist.size else hist))
    expected = base["force"] @ rotation.T
    scale = np.abs(base["force"]).max() + 1e-300
    bad = _first_bad(~np.all(_close(out["force"], expected, scale), axis=1))
    return [] if bad is None else [f"objectivity: row {bad} turned gives {out['force'][bad]} against {expected[bad]}"]


def _batch_size(law, props, base, gap, normal, velocity, mass, hist):
    for k in (0, len(gap) // 2, len(gap) - 1):
        one = _run(law, _batch(props, gap[k:k + 1], normal[k:k + 1], velocity[k:k + 1], mass[k:k + 1],
                               hist[k:k + 1]))
        if not np.array_equal(one["force"][0], base["force"][k]):
            return [f"batch size: row {k} alone gives {one['force'][0]} against {base['force'][k]} in the batch"]
    return []


def _extremes(law, props, slots, rng):
    rows = 12
    gap, normal, velocity, mass, hist = _random_contacts(rows, max(slots, 1), rng, props, overlap_scale=1e-2, speed=1e3)
    hist = hist[:, :slots] * 1e6 if slots else np.zeros((rows, 0))
    mass = np.geomspace(1e-12, 1e6, rows)
    out = _run(law, _batch(props, gap, normal, velocity, mass, hist))
    finite = np.all(np.isfinite(out["force"]), axis=1) & np.isfinite(out["stiffness"])
    for key in _OUTPUTS:
        finite &= np.isfinite(out[key])
    bad = _first_bad(~finite)
    return [] if bad is None else [f"extreme inputs: row {bad} (mass {mass[bad]:.3g} kg) gives a NaN or infinity"]
