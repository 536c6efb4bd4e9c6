"""nsbridge.end_criterion and nsbridge.scene_criterion, eta of each end of a plan
(docs/criterion.md, "Unequal end angles and curved decks"), against the closed forms worked by
hand and against `nsbridge criterion --json`."""
import json
import math
import subprocess

import pytest

import nsbridge

# The closed forms are sums of a few terms of size ~L/W: 1e-12 leaves a margin of ~100 over
# the rounding of the criterion's corners and normals.
TOLERANCE = 1e-12


def test_unequal_end_angles_give_the_hand_worked_eta():
    # W = 2, L = 10, left face at 0 deg, right face at 45 deg, mu = 0.5. The trapezoid's
    # centroid lies at (W^2 (tan^2 45 - tan^2 0) / (24 L), W^2 (tan 45 - tan 0) / (12 L))
    # = (1/60, 1/30) from the axis's midpoint.
    # Right end: corners (6, 1), (4, -1) from the midpoint; from the centroid M = (5 - 1/60,
    # -1/30), h = (1, 1); n = (-1, 1)/sqrt2, t = (-1, -1)/sqrt2, h x (n + k t) = sqrt2, so
    # eta(k) = (M x (n + k t)) / sqrt2 = ((299/60)(1 - k) - (1/30)(1 + k)) / 2
    # = (297 - 301 k) / 120.
    # Left end: corners (-5, 1), (-5, -1); M = (-5 - 1/60, -1/30), h = (0, 1), n = (1, 0),
    # t = (0, 1), h x (n + k t) = -1, so eta(k) = (301 k - 2) / 60.
    c = nsbridge.end_criterion(2.0, 10.0, 0.5, skew_left_deg=0.0, skew_right_deg=45.0)
    left, right = c["ends"]
    assert c["plan"] == "straight"
    assert (left["end"], left["angle_deg"]) == ("left", 0.0)
    assert (right["end"], right["angle_deg"]) == ("right", 45.0)
    assert right["eta_plus"] == pytest.approx((297 + 301 * 0.5) / 120, rel=TOLERANCE)
    assert right["eta_minus"] == pytest.approx((297 - 301 * 0.5) / 120, rel=TOLERANCE)
    assert left["eta_plus"] == pytest.approx((-301 * 0.5 - 2) / 60, rel=TOLERANCE)
    assert left["eta_minus"] == pytest.approx((301 * 0.5 - 2) / 60, rel=TOLERANCE)
    assert left["rotation"] and right["rotation"] and c["rotation"]


def test_a_curved_deck_gives_the_hand_worked_eta():
    # R = 40 m, W = 8 m subtending 60 deg, mu = 0.3. The annular sector's centroid radius is
    # rbar = 4 sin(phi/2) (Ro^3 - Ri^3) / (3 phi (Ro^2 - Ri^2)) = 120.4 / pi (Ro = 44, Ri = 36).
    # At the right end (psi = phi/2): M = (R sin psi, R cos psi - rbar), h = (W/2)(sin psi,
    # cos psi), n = (-cos psi, sin psi), t = (-sin psi, -cos psi), so h x n = W/2,
    # M x n = R - rbar cos psi, M x t = -rbar sin psi and
    # eta(k) = (R - rbar cos psi - k rbar sin psi) / (W/2). The left end is its mirror image:
    # eta(k) = (R - rbar cos psi + k rbar sin psi) / (W/2).
    radius, width, phi, mu = 40.0, 8.0, math.pi / 3, 0.3
    rbar = 120.4 / math.pi
    psi = phi / 2
    base = radius - rbar * math.cos(psi)
    arm = rbar * math.sin(psi)
    c = nsbridge.end_criterion(width, radius * phi, mu, radius=radius)
    left, right = c["ends"]
    assert c["plan"] == "curved" and c["radius"] == radius
    assert left["angle_deg"] == pytest.approx(-30.0, rel=TOLERANCE)
    assert right["eta_plus"] == pytest.approx((base + mu * arm) / (width / 2), rel=TOLERANCE)
    assert right["eta_minus"] == pytest.approx((base - mu * arm) / (width / 2), rel=TOLERANCE)
    assert left["eta_plus"] == pytest.approx((base - mu * arm) / (width / 2), rel=TOLERANCE)
    assert left["eta_minus"] == pytest.approx((base + mu * arm) / (width / 2), rel=TOLERANCE)
    # eta+ = 3.13967, eta- = 0.265331 at the right end: an end impact turns this deck.
    assert right["rotation"] and c["rotation"]


def test_the_criterion_of_a_plan_and_of_a_scene_equal_the_command_line(nsbridge_exe, source):
    cli = subprocess.run([str(nsbridge_exe), "criterion", "--width", "2", "--length", "10",
                          "--friction", "0.5", "--skew-left", "15", "--skew-right", "45",
                          "--json"], capture_output=True, text=True, check=True)
    assert nsbridge.end_criterion(2.0, 10.0, 0.5, skew_left_deg=15.0,
                                  skew_right_deg=45.0) == json.loads(cli.stdout)
    scene = source / "scenes" / "bridge-curved-three-span.toml"
    cli = subprocess.run([str(nsbridge_exe), "criterion", "--scene", str(scene), "--json"],
                         capture_output=True, text=True, check=True)
    from_cli = json.loads(cli.stdout)
    assert nsbridge.scene_criterion(scene) == from_cli
    assert nsbridge.scene_criterion(nsbridge.load_scene(scene)) == from_cli
    # The scene's seats' mu = 0.5 unless another is given.
    assert from_cli["friction"] == 0.5
    assert nsbridge.scene_criterion(scene, friction=0.0)["ends"][1]["eta_plus"] == \
        pytest.approx(nsbridge.scene_criterion(scene, friction=0.0)["ends"][1]["eta_minus"],
                      rel=TOLERANCE)


def test_bad_plans_are_input_errors():
    with pytest.raises(nsbridge.InputError, match="radius: must exceed half the width"):
        nsbridge.end_criterion(8.0, 10.0, 0.0, radius=3.0)
    with pytest.raises(nsbridge.InputError, match="friction"):
        nsbridge.end_criterion(2.0, 10.0, -0.1, skew_right_deg=45.0)
    with pytest.raises(nsbridge.InputError, match="make eta non-finite"):
        nsbridge.end_criterion(1e-300, 1e300, 0.5, skew_right_deg=10.0)
