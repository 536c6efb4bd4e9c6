"""One row per skew angle of the skew sweep's results.csv (scenes/sweeps/skew.toml), for
skew-study.gp: peak |theta| and the smallest seat overlap with and without shear keys, the
residual rotation without keys, and the frictionless rotation criterion eta0 of eq. (1)
(docs/criterion.md) for the scene's W/L = 12 / 90."""
import csv
import math
import sys

WIDTH_OVER_LENGTH = 12.0 / 90.0  # scenes/bridge-full-scale-skew.toml

rows = {}
with open(sys.argv[1], newline="") as f:
    for r in csv.DictReader(f):
        keys = float(r["model.shear_keys.gap"]) < 1.0  # 10 m: a gap the deck never closes
        rows.setdefault(float(r["model.deck.skew_deg"]), {})[keys] = r


def overlap(r):
    return min(float(r["unseating_left_margin"]), float(r["unseating_right_margin"]))


print("skew_deg,theta_keys,theta_no_keys,seat_margin_keys,seat_margin_no_keys,"
      "residual_theta_no_keys,eta0")
for a in sorted(rows):
    k, n = rows[a][True], rows[a][False]
    eta0 = math.sin(2.0 * math.radians(a)) / (2.0 * WIDTH_OVER_LENGTH)
    print("%g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g" % (
        a, float(k["peak_theta"]), float(n["peak_theta"]), overlap(k), overlap(n),
        float(n["residual_theta"]), eta0))
