"""The three methods compared on excitation 5 of the benchmark bridge: the deck rotation theta
of Moreau-Jean, event-driven and compliance overlaid (docs/python.md). The three runs go on
three threads at once: nsbridge.run releases the GIL while it integrates.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/methods.py [--out DIR] [--end-time S]
"""
import argparse
import pathlib
from concurrent.futures import ThreadPoolExecutor

import matplotlib
matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt

import nsbridge

ROOT = pathlib.Path(__file__).resolve().parents[2]
METHODS = ("moreau", "event_driven", "compliance")
args = argparse.ArgumentParser(description="theta of the three methods on excitation 5")
args.add_argument("--out", type=pathlib.Path, default=pathlib.Path("out/methods-python"))
args.add_argument("--end-time", type=float, help="shorten the runs to S seconds (a quick check)")
a = args.parse_args()

scene = nsbridge.load_scene(ROOT / "scenes/bridge-exc5.toml",
                            [f"solver.end_time={a.end_time}"] if a.end_time else [])
with ThreadPoolExecutor(len(METHODS)) as pool:
    results = list(pool.map(lambda m: nsbridge.run(scene, method=m), METHODS))
fig, ax = plt.subplots(figsize=(9, 4.5))
for r, style in zip(results, ("-", "--", ":")):
    peak = r.summary["peaks"]["theta"]["abs_max"]
    ax.plot(r.history["t"], r.history["theta"], style, lw=1,
            label=f"{r.method} ({r.status}, peak |theta| {peak:.3g} rad)")
ax.set(xlabel="t [s]", ylabel="theta_d [rad]", title=f"{scene.name}: deck rotation, three methods")
ax.legend(loc="upper right")
a.out.mkdir(parents=True, exist_ok=True)
fig.savefig(a.out / "methods.png", dpi=120)
print(f"{a.out / 'methods.png'}: " + ", ".join(f"{r.method} {r.status}" for r in results))
