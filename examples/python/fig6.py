"""Fig. 6 of Shi & Dimitrakopoulos (2017), redrawn with matplotlib from a sweep: the peak deck
rotation against the transverse PGA, with pounding and without, for mu = 0.3, 0.5, 0.7
(scenes/sweeps/fig6.toml, 36 runs of Moreau-Jean; docs/python.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/fig6.py [--out DIR] [--end-time S]
"""
import argparse
import pathlib

import matplotlib
matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt
import numpy as np

import nsbridge

ROOT = pathlib.Path(__file__).resolve().parents[2]
args = argparse.ArgumentParser(description="Fig. 6 from nsbridge.sweep")
args.add_argument("--out", type=pathlib.Path, default=pathlib.Path("out/fig6-python"))
args.add_argument("--end-time", type=float, help="shorten every run to S seconds (a quick check)")
args.add_argument("--jobs", type=int, help="threads (default: all cores)")
a = args.parse_args()

sets = [f"solver.end_time={a.end_time}"] if a.end_time else []
runs = a.out / (f"sweep-{a.end_time:g}s" if a.end_time else "sweep")  # kept for the next time
r = nsbridge.sweep(ROOT / "scenes/sweeps/fig6.toml", runs, jobs=a.jobs, overrides=sets)
# A pandas DataFrame, or numpy arrays without pandas: either way, plain arrays here.
pga, mu, theta = (np.asarray(r[c], dtype=float)
                  for c in ("model.excitation.target_pga", "model.seats.friction", "peak_theta"))
pounding = np.asarray(r["pounding"], dtype=str)
fig, ax = plt.subplots(figsize=(8, 5))
for mu_i, color in zip(np.unique(mu), ("C0", "C1", "C2")):
    for level, style, what in (("yes", "o-", "with"), ("no", "s--", "without")):
        run = (mu == mu_i) & (pounding == level)
        order = np.argsort(pga[run])
        ax.plot(pga[run][order], theta[run][order], style, color=color,
                label=f"{what} pounding, mu = {mu_i:g}")
ax.set(xlabel="transverse PGA of the input [g]", ylabel="peak |theta_d| [rad]",
       title="Fig. 6: peak deck rotation against the transverse PGA (Moreau-Jean)")
ax.legend(loc="upper left")
fig.savefig(a.out / "fig6.png", dpi=120)
print(f"{a.out / 'fig6.png'}: {len(theta)} runs, {sum(s != 'completed' for s in r['status'])} failed")
