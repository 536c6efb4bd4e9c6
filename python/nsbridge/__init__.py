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
    lcp,
    load_scene,
    run,
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


# `import nsbridge.lcp` as well as `nsbridge.lcp`.
_sys.modules[__name__ + ".lcp"] = lcp

__all__ = ["InputError", "Result", "Scene", "Study", "build_info", "criterion", "lcp",
           "load_scene", "open_study", "run", "sweep", "__version__"]
