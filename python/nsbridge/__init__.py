"""nsbridge: the nonsmooth seismic response of bridges whose decks pound against their
abutments, from Python.

The engine is the C++ one; this package converts its inputs and outputs (docs/python.md):

    import nsbridge
    result = nsbridge.run("scenes/bridge-exc5.toml", method="event_driven")
    result.status                 # "completed", ... as in summary.json
    result.history["theta"]       # numpy float64 array, a column of history.csv
    result.summary["peaks"]       # summary.json as a dict
    table = nsbridge.sweep("scenes/sweeps/fig6.toml", "out/fig6")   # results.csv, typed

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


# `import nsbridge.lcp` as well as `nsbridge.lcp`.
_sys.modules[__name__ + ".lcp"] = lcp

__all__ = ["InputError", "Result", "Scene", "build_info", "criterion", "lcp", "load_scene",
           "run", "sweep", "__version__"]
