"""nsbridge: the nonsmooth seismic response of bridges whose decks pound against their
abutments, from Python.

The engine is the C++ one; this package converts its inputs and outputs (docs/python.md):

    import nsbridge
    result = nsbridge.run("scenes/bridge-exc5.toml", method="event_driven")
    result.status                 # "completed", ... as in summary.json
    result.history["theta"]       # numpy float64 array, a column of history.csv
    result.summary["peaks"]       # summary.json as a dict
    table = nsbridge.sweep("scenes/sweeps/fig6.toml", "out/fig6")   # results.csv, typed
    study = nsbridge.open_study("out/fig6/sweep.h5")   # `nsbridge sweep --hdf5`'s one file

    scene = nsbridge.Scene.from_dict({"model": {"kind": "bouncing_ball", "mass": 1.0,
                                                "height": 1.0}})   # a scene without a file
    nsbridge.run(scene.with_overrides({"model.height": 0.5}))

Bad input raises nsbridge.InputError (a ValueError) with the command line's message
(file:line:col: key: what is allowed); a numerical failure is a status, never an exception.
"""
import sys as _sys

from ._nsbridge import (  # noqa: F401
    InputError,
    Result,
    Scene,
    __version__,
    build_info,
    criterion,
    end_criterion,
    lcp,
    load_scene,
    run,
    scene_criterion,
    _sweep_columns,
)

try:
    import pandas as _pandas
except ImportError:  # numpy arrays per column instead
    _pandas = None


def _numpy_column(kind, values, missing):
    import numpy as np
    if kind == "text":
        return np.array(values, dtype=str)
    if kind == "real" or not missing.any():
        return values
    return np.ma.masked_array(values, mask=missing)


def _pandas_column(kind, values, missing):
    # The nullable dtypes keep an integer or boolean column's type where a value is absent.
    if kind == "text":
        return _pandas.array(values, dtype="string")
    if kind == "integer":
        return _pandas.arrays.IntegerArray(values, missing)
    if kind == "boolean":
        return _pandas.arrays.BooleanArray(values, missing)
    return values


def sweep(design_path, out, jobs=None, overrides=(), restart=False):
    """Runs a sweep design (docs/sweep.md) into the folder `out` as `nsbridge sweep` does
    (runs already complete there are kept; a folder of another design is refused unless
    `restart`), on `jobs` threads (None: all cores), the GIL released. Returns results.csv's
    columns typed as the sweep's rows are: a pandas DataFrame when pandas is importable (float64,
    Int64, boolean and string columns), else a dict of numpy arrays (float64 with NaN where a
    value is absent; int64 and bool, masked where a value is absent; str)."""
    columns = _sweep_columns(design_path, out, jobs=jobs, overrides=list(overrides),
                             restart=restart)
    if _pandas is not None:
        return _pandas.DataFrame({name: _pandas_column(kind, values, missing)
                                  for name, kind, values, missing in columns})
    return {name: _numpy_column(kind, values, missing) for name, kind, values, missing in columns}


class Study:
    """The one file of a sweep, DIR/sweep.h5 (`nsbridge sweep --hdf5`; docs/outputs.md,
    "sweep.h5"), read with h5py. `results` is results.csv's table as a pandas DataFrame (typed
    as nsbridge.sweep types it); `runs` the ids of the runs complete in the file. A sweep still
    under way, or stopped, has no /results yet: `results` is then made from the rows of its
    complete runs. Use as a context manager, or call close()."""

    def __init__(self, path):
        import h5py
        self._file = h5py.File(path, "r")
        self.path = path
        self.design_hash = self._file.attrs["design_hash"]
        self.runs = sorted(name for name, g in self._file["runs"].items()
                           if g.attrs.get("done", 0) == 1)
        self.results = self._results()

    def _results(self):
        import io
        if "results" in self._file and self._file["results"].attrs.get("done", 0) == 1:
            import numpy as np
            g = self._file["results"]
            columns = {}
            for name, kind in zip(g.attrs["columns"], g.attrs["kinds"]):
                data = g[name][()]
                if kind in ("real", "integer"):
                    missing = np.isnan(data)
                    values = np.where(missing, 0, data)
                    columns[name] = (data if kind == "real" else
                                     _pandas_column(kind, values.astype(np.int64), missing))
                else:
                    texts = [v.decode() if isinstance(v, bytes) else str(v) for v in data]
                    if kind == "boolean":
                        missing = np.array([t == "" for t in texts])
                        values = np.array([t in ("true", "1") for t in texts])
                        columns[name] = _pandas_column(kind, values, missing)
                    else:
                        columns[name] = _pandas_column(kind, texts, None)
            return _pandas.DataFrame(columns)
        rows = [_pandas.read_csv(io.StringIO(self._group(r).attrs["row"]), dtype={"run": str},
                                 keep_default_na=False, na_values=[""])
                for r in self.runs]
        return _pandas.concat(rows, ignore_index=True) if rows else _pandas.DataFrame()

    def _group(self, run_id):
        run_id = str(run_id)
        g = self._file["runs"].get(run_id)
        if g is None or g.attrs.get("done", 0) != 1:
            raise KeyError(f"{self.path}: no complete run {run_id!r}")
        return g

    def history(self, run_id):
        """The run's history as a DataFrame: the columns of history.csv that the design keeps
        ([output] hdf5_history), float64; None when it keeps none or the run was rejected."""
        g = self._group(run_id)
        if "history" not in g:
            return None
        d = g["history"]
        return _pandas.DataFrame(d[()], columns=list(d.attrs["columns"]))

    def events(self, run_id):
        """The run's events.csv as a DataFrame; None for a rejected run."""
        g = self._group(run_id)
        if "events" not in g:
            return None
        e = g["events"]
        return _pandas.DataFrame({name: e[name].asstr()[()] if e[name].dtype.kind == "O"
                                  else e[name][()] for name in e.attrs["columns"]})

    def summary(self, run_id):
        """The run's summary.json as a dict; None for a rejected run."""
        import json
        g = self._group(run_id)
        if "summary" not in g:
            return None
        return json.loads(g["summary"].asstr()[()])

    def close(self):
        self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def open_study(path):
    """Opens a sweep's DIR/sweep.h5 (needs h5py and pandas): a Study."""
    return Study(path)


_METHOD_TITLES = {"moreau": "Moreau-Jean time stepping", "event_driven": "event-driven",
                  "compliance": "compliance (penalty)"}
_FAMILY_TITLES = {"abutment": "abutments", "hinge": "hinges", "shear_key": "shear keys",
                  "": "contacts"}
_PLOT_KINDS = ("response", "gaps", "bents", "energy", "events")


def _indexed(name, prefix):
    """The k of a column prefix + k (k >= 1), else None."""
    rest = name[len(prefix):]
    return int(rest) if name.startswith(prefix) and rest.isdigit() else None


def _families(result, n):
    """Contacts 1..n grouped by summary.json "contacts" family, as `nsbridge plot` groups
    them: abutments, hinges, shear keys, other families, then contacts without one."""
    labels = result.summary.get("contacts", [])
    family = {c["contact"]: c["family"] for c in labels}
    name = {c["contact"]: c["name"] for c in labels}
    order = ["abutment", "hinge", "shear_key"]
    order += [f for f in dict.fromkeys(family.get(k, "") for k in range(1, n + 1))
              if f and f not in order]
    order.append("")
    groups = [(f, [k for k in range(1, n + 1) if family.get(k, "") == f]) for f in order]
    return [(f, ks) for f, ks in groups if ks], name


def _plot_panels(result, what):
    """The panels of a figure, as `nsbridge plot` draws them (docs/plots.md): a list of
    (title, xlabel, ylabel, [(x column, y column, label)]); x column None is t."""
    h = result.history
    panels = []

    def contact_panels(prefix, quantity):
        n = max([k for k in (_indexed(c, prefix) for c in h) if k] or [0])
        groups, names = _families(result, n)
        for family, members in groups:
            curves = [(None, f"{prefix}{k}", f"{prefix}{k}" + (f": {names[k]}" if k in names else ""))
                      for k in members if f"{prefix}{k}" in h]
            if curves:
                panels.append((_FAMILY_TITLES.get(family, family), "t [s]", quantity, curves))

    if what == "response":
        disp, rot = [], []
        deck = "theta" in h  # a deck moves along (x) and across (y) the bridge
        for c in h:
            base = c.rstrip("0123456789")
            body = c[len(base):]
            label = c + (f" (body {body})" if body else
                         {"x": " (longitudinal)", "y": " (transverse)"}.get(c, "") if deck else "")
            if base in ("x", "y"):
                disp.append((None, c, label))
            elif base == "theta":
                rot.append((None, c, label))
        if disp:
            panels.append(("displacements", "t [s]", "displacement [m]", disp))
        if rot:
            panels.append(("rotations", "t [s]", "rotation [rad]", rot))
        contact_panels("gN", "normal gap [m]")
    elif what == "gaps":
        contact_panels("gN", "normal gap [m]")
    elif what == "bents":
        bents = sorted({_indexed(c.split("_")[0], "bent") for c in h if c.startswith("bent")} - {None})
        for i in bents:
            for d, label in (("x", "longitudinal"), ("y", "transverse")):
                u, f = f"bent{i}_u{d}", f"bent{i}_f{d}"
                if u in h and f in h:
                    panels.append((f"bent {i}, {label}", f"deformation u_{d} [m]",
                                   f"force f_{d} [kN]", [(u, f, f"{f} against {u}")]))
        if not panels:
            raise ValueError("the history has no bent columns (bent<i>_ux, bent<i>_fx, ...): "
                             "ask the run for them with [output] groups = [\"bents\"]")
    elif what == "energy":
        if "energy_error" in h:
            panels.append(("energy balance error", "t [s]", "relative error [-]",
                           [(None, "energy_error", "energy_error")]))
        terms = [(None, c, c[len("energy_"):]) for c in h
                 if c.startswith("energy_") and c != "energy_error"]
        if terms:
            panels.append(("energy terms", "t [s]", "energy [kJ]", terms))
    return panels


def _plot(self, what="response", ax=None):
    """Draws the run with matplotlib as `nsbridge plot --what WHAT` does (docs/plots.md):
    "response" (displacements, rotations, normal gaps by contact family), "gaps",
    "bents" (hysteresis loops; needs [output] groups = ["bents"]), "energy" or "events".
    Without `ax` a new matplotlib Figure (no pyplot, so any backend, Agg included) holds one
    axes per panel; with `ax` (an Axes, or a sequence of them) the panels are drawn into those,
    one each. Returns the list of Axes drawn."""
    if what not in _PLOT_KINDS:
        raise ValueError(f"what={what!r}: expected one of {', '.join(_PLOT_KINDS)}")
    title = f"{self.name}: {what}, {_METHOD_TITLES.get(self.method, self.method)}"
    if what == "events":
        panels = [None]
    else:
        panels = _plot_panels(self, what)
        if not panels:
            raise ValueError(f"the history has no columns to draw for what={what!r}")
    if ax is None:
        from matplotlib.figure import Figure
        fig = Figure(figsize=(10, 1.0 + 2.6 * len(panels)), layout="constrained")
        axes = list(fig.subplots(len(panels), 1, squeeze=False)[:, 0])
        fig.suptitle(title)
    else:
        axes = list(ax) if hasattr(ax, "__len__") else [ax]
        if len(axes) < len(panels):
            raise ValueError(f"what={what!r} draws {len(panels)} panels; ax holds {len(axes)}")
        axes[0].figure.suptitle(title)
    if what == "events":
        events = self.events
        n = max([int(c) for c in events["contact"]] + [max([k for k in (_indexed(c, "gN") for c in self.history) if k] or [0])])
        groups, names = _families(self, n)
        row, ticks = {0: 0}, ["run (no contact)"]
        for family, members in groups:
            for k in members:
                row[k] = len(ticks)
                ticks.append(f"{_FAMILY_TITLES.get(family, family)} {k}" + (f": {names[k]}" if k in names else ""))
        a = axes[0]
        for kind, marker in (("impact", "o"), ("close", "^"), ("open", "v"), ("stick", "s"),
                             ("slip", "x"), ("warning", "*")):
            pick = [i for i, k in enumerate(events["kind"]) if k == kind]
            if pick:
                a.plot([events["t"][i] for i in pick], [row[int(events["contact"][i])] for i in pick],
                       linestyle="none", marker=marker, markersize=4, label=kind)
        a.set_yticks(range(len(ticks)), ticks)
        a.set_xlabel("t [s]")
        a.set_title("events per contact")
        if a.lines:
            a.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0))
        return axes[:1]
    t = self.history["t"]
    for a, (panel_title, xlabel, ylabel, curves) in zip(axes, panels):
        for x, y, label in curves:
            a.plot(t if x is None else self.history[x], self.history[y], linewidth=1.0, label=label)
        if ylabel == "normal gap [m]":
            a.axhline(0.0, color="black", linestyle="--", linewidth=0.8)
        a.set_title(panel_title)
        a.set_xlabel(xlabel)
        a.set_ylabel(ylabel)
        a.grid(True)
        a.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small")
    return axes[:len(panels)]


Result.plot = _plot

# `import nsbridge.lcp` as well as `nsbridge.lcp`.
_sys.modules[__name__ + ".lcp"] = lcp

__all__ = ["InputError", "Result", "Scene", "Study", "build_info", "criterion", "end_criterion",
           "lcp", "load_scene", "open_study", "run", "scene_criterion", "sweep", "__version__"]
