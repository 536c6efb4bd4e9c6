"""nsbridge: the nonsmooth seismic response of bridges whose decks pound against their
abutments, from Python.

The engine is the C++ one; this package converts its inputs and outputs (docs/python.md):

    import nsbridge
    result = nsbridge.run("scenes/bridge-exc5.toml", method="event_driven")
    result.status                 # "completed", ... as in summary.json
    result.history["theta"]       # numpy float64 array, a column of history.csv
    result.summary["peaks"]       # summary.json as a dict

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
    sweep,
)

# `import nsbridge.lcp` as well as `nsbridge.lcp`.
_sys.modules[__name__ + ".lcp"] = lcp

__all__ = ["InputError", "Result", "Scene", "build_info", "criterion", "lcp", "load_scene",
           "run", "sweep", "__version__"]
