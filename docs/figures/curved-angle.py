"""Draws docs/figures/curved-angle.png from a sweep of scenes/sweeps/curved-angle.toml
(docs/curved.md): the peak deck rotation against the subtended angle, beside the rotation
criterion eta of a radial end impact (docs/criterion.md, "Unequal end angles and curved
decks") for the same plans.

    /usr/bin/python3 docs/figures/curved-angle.py out/curved-angle/results.csv docs/figures
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ARC = 64.0 * math.pi / 6.0  # the scene's centreline arc length [m]
WIDTH = 2.44                # [m]
FRICTION = 0.5              # the seats' mu


def eta(phi, k):
    """eta(k) of the right end of an annular sector (docs/criterion.md): (M x d) / (h x d)."""
    r = ARC / phi
    ro, ri = r + WIDTH / 2, r - WIDTH / 2
    rbar = 4 * math.sin(phi / 2) * (ro**3 - ri**3) / (3 * phi * (ro**2 - ri**2))
    psi = phi / 2
    m = (r * math.sin(psi), r * math.cos(psi) - rbar)
    h = (WIDTH / 2 * math.sin(psi), WIDTH / 2 * math.cos(psi))
    n = (-math.cos(psi), math.sin(psi))
    t = (-n[1], n[0])
    d = (n[0] + k * t[0], n[1] + k * t[1])
    cross = lambda a, b: a[0] * b[1] - a[1] * b[0]  # noqa: E731
    return cross(m, d) / cross(h, d)


def main(results, out):
    rows = [r for r in csv.DictReader(open(results)) if r["status"] == "completed"]
    angle = [float(r["angle"]) for r in rows]
    theta = [float(r["peak_theta"]) for r in rows]
    with open(f"{out}/curved-angle.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["angle_deg", "peak_theta", "peak_y", "eta0", "eta_plus", "eta_minus"])
        for r in rows:
            phi = math.radians(float(r["angle"]))
            w.writerow([r["angle"], r["peak_theta"], r["peak_y"], f"{eta(phi, 0.0):.6g}",
                        f"{eta(phi, -FRICTION):.6g}", f"{eta(phi, FRICTION):.6g}"])
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].plot(angle, [1e3 * t for t in theta], "o-", color="C0")
    ax[0].set_xlabel("subtended angle φ [deg] (arc length 33.5 m)")
    ax[0].set_ylabel("peak |θ| [mrad]")
    ax[0].set_title("curved three-span deck, excitation 5 (Moreau–Jean)")
    ax[0].grid(True, alpha=0.3)
    fine = [math.radians(a) for a in range(1, 91)]
    ax[1].plot([math.degrees(p) for p in fine], [eta(p, 0.0) for p in fine], label="η₀ (μ = 0)")
    ax[1].plot([math.degrees(p) for p in fine], [eta(p, -FRICTION) for p in fine], "--",
               label="η₊ (μ = 0.5)")
    ax[1].plot([math.degrees(p) for p in fine], [eta(p, FRICTION) for p in fine], ":",
               label="η₋ (μ = 0.5)")
    ax[1].axhline(1.0, color="k", lw=0.8)
    ax[1].axhline(-1.0, color="k", lw=0.8)
    ax[1].set_xlabel("subtended angle φ [deg]")
    ax[1].set_ylabel("η of a radial end impact")
    ax[1].set_title("rotation criterion: |η| > 1 turns the deck")
    ax[1].legend()
    ax[1].grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{out}/curved-angle.png", dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
