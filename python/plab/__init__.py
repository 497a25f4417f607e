"""ParticleLab from Python: load a JSON scene (a file or a dict), cycle it,
read and write its state through NumPy arrays over the kernel's own columns.

    import plab
    sim = plab.load("examples/dry_column_collapse.json", set={"timestep.safety_factor": 0.5})
    sim.cycle(1000, every=100, callback=lambda s: print(s.time, s.positions[:, 1].max()))
    print(sim.summary()["state_hash"])

The API and the rules of the views are in docs/python.md.
"""
import json as _json
import os as _os

import numpy as _np
from numpy.lib.mixins import NDArrayOperatorsMixin as _OperatorsMixin

from . import _install
from . import _plab

_plab.set_installed_plugin_dir(
    _os.path.normpath(_os.path.join(_os.path.dirname(__file__), _install.PLUGINS_FROM_PACKAGE)))

Error = _plab.Error                      # every plab error
InputError = _plab.InputError            # bad scene or value: the message names the JSON path; .path
PluginError = _plab.PluginError          # a plug-in library refused (an InputError)
RunError = _plab.RunError                # the run stopped (instability...); .quantity
CheckpointError = _plab.CheckpointError  # a checkpoint that cannot be written or read


class StaleViewError(Error):
    """A view used after a cycle that moved the storage it showed."""


__all__ = ["load", "restart", "register_model", "Simulation", "View", "Error", "InputError", "PluginError",
           "RunError", "CheckpointError", "StaleViewError"]

for _cls in (Error, InputError, PluginError, RunError, CheckpointError):
    _cls.__module__ = "plab"


def register_model(name, law, properties, history=(), doc="", range=None,
                   timestep_rule="per ball sqrt(m / sum k) over its contacts, k the batch's stiffness"):
    """A contact model whose law is a Python function over a batch of contacts
    (NumPy columns, plab.laws), for the scenes loaded from now on: a scene
    names it as any plug-in's model ("model": name), without a "plugins" entry.
    properties: (key, name, unit, default, min, max, doc) tuples, numbers;
    history: (name, doc, default, negate_on_swap, tangential) tuples;
    range: the key of the property that is the activity range (a surface
    gap, m), or None for 0 (active while touching).
    It is slow (one Python call per batch of 512 contacts; docs/python.md),
    and a checkpoint of a scene that uses it restarts only in a Python session
    that has registered the law under the same name.
    Example: plab.register_model("py_linear", plab.laws.linear,
    plab.laws.LINEAR_PROPERTIES, plab.laws.LINEAR_HISTORY, range="rgap")."""
    _plab.register_law(name, doc or ("a contact law in Python: " + getattr(law, "__name__", "law")), timestep_rule,
                       law, [tuple(p) for p in properties], [tuple(h) for h in history], range or "")


from . import laws  # noqa: E402  (the NumPy laws, plab.laws.linear)
from . import contract  # noqa: E402  (the contact-law contract, on a Python law)


def _assignments(set, overrides):
    """--set PATH=VALUE strings from a dict and from keyword arguments (`__` for `.`)."""
    pairs = dict(set or {})
    pairs.update({k.replace("__", "."): v for k, v in overrides.items()})
    return ["%s=%s" % (path, _json.dumps(value)) for path, value in pairs.items()]


def load(scene, set=None, out=None, base_dir=None, **overrides):
    """A simulation of `scene`: a path to a JSON scene file, or a dict with the
    same schema. `set` and keyword arguments override values by JSON path, as
    `plab run --set` does: set={"contact_models.0.properties.kn": 2e6}, or
    contact_models__0__properties__kn=2e6. `out`: an output folder (history.csv,
    VTK, summary.json as the scene asks); None writes nothing unless the scene
    names output.dir. `base_dir`: where a dict's relative paths (plug-ins,
    meshes) resolve; the current folder by default.
    Bad input raises InputError with the CLI's message (the JSON path, the
    value, the valid range)."""
    sets = _assignments(set, overrides)
    if isinstance(scene, dict):
        core = _plab.load_text(_json.dumps(scene, allow_nan=False), sets, base_dir or _os.getcwd(), out or "")
    else:
        core = _plab.load_file(_os.fspath(scene), sets, out or "")
    return Simulation(core)


def restart(path, set=None, **overrides):
    """The run saved by Simulation.checkpoint() (or `plab run --checkpoint-every`),
    ready to continue: the same bits as the run that was not stopped."""
    return Simulation(_plab.restart(_os.fspath(path), _assignments(set, overrides)))


class View(_OperatorsMixin):
    """A NumPy view of one column of the world's state, without a copy.

    Valid until a cycle moves the column's storage (balls added or removed by
    inlets or outlets); any use after that raises StaleViewError. An array
    taken from a view (np.asarray(v), v[:, 0]) is a plain NumPy array: it never
    points to freed memory (it keeps the storage it shows alive), but after
    such a cycle it shows the old storage; take it from the simulation again."""

    __slots__ = ("_core", "_name", "_array", "_generation", "_step")

    def __init__(self, core, name):
        self._core = core
        self._name = name
        self._array = core.column(name)
        self._generation = core.generation
        self._step = core.step_count

    @property
    def array(self):
        """The NumPy array itself, after the check that it is still valid."""
        if self._core.generation != self._generation:
            raise StaleViewError(
                "the view of '%s' was taken at step %d; a cycle since (now step %d) added or removed balls, "
                "which moved the storage it showed: take sim.%s again" %
                (self._name, self._step, self._core.step_count, self._name))
        return self._array

    def __array__(self, dtype=None):
        a = self.array
        return a if dtype is None else a.astype(dtype, copy=False)

    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        inputs = tuple(x.array if isinstance(x, View) else x for x in inputs)
        if "out" in kwargs:
            kwargs["out"] = tuple(x.array if isinstance(x, View) else x for x in kwargs["out"])
        return getattr(ufunc, method)(*inputs, **kwargs)

    def __getitem__(self, index):
        return self.array[index]

    def __setitem__(self, index, value):
        self.array[index] = value

    def __len__(self):
        return len(self.array)

    def __iter__(self):
        return iter(self.array)

    @property
    def shape(self):
        return self.array.shape

    @property
    def dtype(self):
        return self.array.dtype

    @property
    def ndim(self):
        return self.array.ndim

    @property
    def writeable(self):
        return self.array.flags.writeable

    def __repr__(self):
        return "plab.View(%r, %r)" % (self._name, self.array)


class Simulation:
    """A loaded scene: its world, its histories, its commands."""

    def __init__(self, core):
        self._core = core

    # ---- running ----
    def cycle(self, n, every=None, callback=None, on_bond_break=None, on_instability=None):
        """Runs n cycles (histories and outputs as the scene says). With
        `callback`, calls callback(sim) after every `every` cycles (and after
        the last); a callback that returns False (not None) stops the run
        there. Events: on_bond_break(sim, breaks) after each cycle in which
        bonds broke (`breaks`: a dict per bond: step, time, ids, point, mode,
        model); on_instability(sim, error) when the run goes unstable, with
        the world back at its last good state, before the RunError is
        raised; an on_bond_break that returns False stops the run after that
        cycle. Returns the number of cycles run."""
        n = int(n)
        if callback is None and on_bond_break is None and on_instability is None:
            self._core.cycle(n)
            return n
        every = int(every or n)
        if every < 1:
            raise ValueError("every: expected a positive number of cycles, got %d" % every)
        done = 0
        while done < n:
            k, stopped = self._cycle_watching(min(every, n - done), on_bond_break, on_instability)
            done += k
            if stopped:
                break
            if callback is not None:
                stop = callback(self)
                if stop is not None and not stop:  # False, or NumPy's False
                    break
        return done

    def _cycle_watching(self, k, on_bond_break, on_instability):
        """k cycles, calling the event handlers; (cycles run, stopped by a handler)."""
        done = 0
        try:
            while done < k:
                if on_bond_break is None:
                    self._core.cycle(k - done)
                    return k, False
                before = self._core.bond_break_count
                done += self._core.cycle_to_bond_break(k - done)
                if self._core.bond_break_count > before:
                    stop = on_bond_break(self, self._core.bond_breaks(before))
                    if stop is not None and not stop:
                        return done, True
            return done, False
        except RunError as error:
            if on_instability is not None:
                on_instability(self, error)
            raise

    def solve(self, time, max_cycles=10**9):
        """Cycles for `time` seconds of simulated time, as the scene's
        {"solve": {"time": T}} does."""
        self._core.solve_until(self._core.time + float(time), int(max_cycles))

    def run(self):
        """Runs the scene's commands (those not run yet), as `plab run` does."""
        self._core.run()

    # ---- state ----
    @property
    def dim(self):
        return self._core.dim

    def __len__(self):
        return self._core.size

    @property
    def time(self):
        return self._core.time

    @property
    def step(self):
        return self._core.step_count

    @property
    def dt(self):
        return self._core.last_dt

    @property
    def positions(self):
        """N × dim, m (read-only)."""
        return View(self._core, "positions")

    @property
    def velocities(self):
        """N × dim, m/s (writable)."""
        return View(self._core, "velocities")

    @property
    def spins(self):
        """Angular velocities, rad/s: N × 3, or N (about z) in 2D (writable)."""
        return View(self._core, "spins")

    @property
    def forces(self):
        """N × dim, N: the total force of the last force pass (read-only)."""
        return View(self._core, "forces")

    @property
    def moments(self):
        """N × 3, or N in 2D, N m (read-only)."""
        return View(self._core, "moments")

    @property
    def radii(self):
        return View(self._core, "radii")

    @property
    def masses(self):
        return View(self._core, "masses")

    @property
    def groups(self):
        """Group index of each ball (names: group_names)."""
        return View(self._core, "groups")

    @property
    def ids(self):
        return View(self._core, "ids")

    @property
    def fixity(self):
        """Fixed degrees of freedom as bits (x 1, y 2, z 4, rx 8, ry 16, rz 32; writable)."""
        return View(self._core, "fixity")

    def field(self, name):
        """A per-body field a plug-in registered (field_names), e.g. "density"."""
        return View(self._core, name)

    @property
    def field_names(self):
        return self._core.field_names()

    @property
    def group_names(self):
        return self._core.group_names()

    @property
    def model_names(self):
        return self._core.model_names()

    def contacts(self):
        """The active contacts, as columns (copies: the kernel's contact tables
        are not contiguous columns): model (instance index into model_names),
        end1, end2 (ball indices; end2 a wall facet's when with_wall), id1, id2,
        with_wall, bonded, normal (M × 3, end 1 to end 2), overlap (m, > 0 when
        touching), force (M × 3, on end 2, N)."""
        return self._core.contacts()

    # ---- measurements and files ----
    def summary(self):
        """The run summary (summary.json of `plab run`) as a dict."""
        return _json.loads(self._core.summary_json())

    def state_hash(self):
        """FNV-1a over positions, velocities and spins: equal hashes, equal states."""
        return self._core.state_hash()

    def history(self, as_dict=False):
        """The scene's histories: a pandas DataFrame when pandas is importable
        (and as_dict is False), else a dict of NumPy columns."""
        names = self._core.history_columns()
        rows = self._core.history_rows()
        columns = {name: _np.ascontiguousarray(rows[:, c]) for c, name in enumerate(names)}
        if not as_dict:
            try:
                import pandas
            except ImportError:
                return columns
            return pandas.DataFrame(columns)
        return columns

    def checkpoint(self, path):
        """The complete state of the run, to continue with plab.restart(path)."""
        self._core.checkpoint(_os.fspath(path))

    @property
    def scene(self):
        """The scene as loaded (variables resolved, overrides applied)."""
        return _json.loads(self._core.scene_json())
