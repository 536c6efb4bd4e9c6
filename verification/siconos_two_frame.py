#!/usr/bin/python3
"""Peer check: nsbridge's Moreau-Jean against Siconos's MoreauJeanOSI on the two-frame bridge.

Both sides integrate the same model at the same step h and theta (docs/verification.md,
"Siconos peer check"): data/siconos-two-frame/scene.toml, two rigid frames (x, y, theta
each, 6 DOF) on linear bents, Rayleigh damping, a transverse sine burst, and six frictionless
corner contacts (two at each fixed seat, two at the hinge between the frames).

nsbridge runs the scene (`nsbridge run`). The Siconos model is built here from the scene
file with the formulas of docs/bridge.md ("Bridges in parts"), not exported from nsbridge:
  M   = diag(m, m, I) per frame;
  K0  = sum over the frame's bents of k_x e_x e_x^T + k_y b b^T, b = (0, 1, s);
  C   = a0 M + a1 K0, a0 and a1 from the modal ratios of modes i and j of (M, K0)
        (Chopra, Dynamics of Structures, sec. 11.4.1);
  f   = -K0 (q - e_y u_g(t)) - C (u - e_y v_g(t)): with all bents on one ground motion the
        quasi-static support motion is e_y u_g (y of both frames), so Siconos's
        LagrangianLinearTIDS gets F_ext(t) = K0 e_y u_g(t) + C e_y v_g(t);
  u_g, v_g: the natural cubic spline through the record's samples and its exact integrals
        from the first sample (models/ground_motion.hpp), here NaturalSpline below.
Contacts are LagrangianScleronomousR relations computing the exact (nonlinear) gap
g_N(q) = n . (p - a) of a frame corner p against a face (a, n) and its exact Jacobian
(models/contact_geometry.hpp, models/parts.hpp): a seat face is fixed; the hinge face is the
right end face of frame 1, so g_N and W_N span both frames. Newton's impact law per contact
(NewtonImpactNSL), one LCP per step (Lemke), MoreauJeanOSI(theta).

The check compares x, y, theta of both frames and the six gaps at nsbridge's sample times
(Siconos's history interpolated linearly; both sample every step, so the times coincide):
max |difference| / peak |nsbridge| over the run, per column; it passes when the largest is at
most --tolerance (default 1e-3, 0.1 % of the peak).

Usage: siconos_two_frame.py --nsbridge build/app/nsbridge [--scene ...] [--tolerance 1e-3]
       [--perturb-stiffness 1.01]   (scales frame 2's first bent on the Siconos side only:
                                     the deliberate break the check must catch)
       [--jacobian-at-start]        (diagnostic: Siconos's W_N at q_k, see StepStart)
Exit status 0 pass, 1 fail, 77 Siconos not importable (CTest SKIP_RETURN_CODE).
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
import tomllib

try:  # the check needs Siconos (python3-siconos, with numpy); nothing else does
    import numpy as np
    import siconos.kernel as sk
    import siconos.numerics as sn
except ImportError as error:
    print(f"siconos_two_frame: skipped, Siconos not importable ({error})")
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SCENE = os.path.join(HERE, "..", "data", "siconos-two-frame", "scene.toml")
COLUMNS = ["x1", "y1", "theta1", "x2", "y2", "theta2"] + [f"gN{i}" for i in range(1, 7)]


def read_record(path):
    """Two-column record 't a' per line, '#' comments skipped (scene/records.cpp)."""
    rows = [line.split() for line in open(path) if line.strip() and not line.startswith("#")]
    return np.array([float(r[0]) for r in rows]), np.array([float(r[1]) for r in rows])


class NaturalSpline:
    """The natural cubic spline through (t_i, a_i) (second derivative 0 at both ends) and its
    first and second integrals from t_0, exact: on [t_i, t_i+1], with s = t - t_i,
    a = a_i + b_i s + c_i s^2 + e_i s^3, c_i = m_i / 2, e_i = (m_i+1 - m_i) / (6 h_i),
    b_i = (a_i+1 - a_i) / h_i - h_i (2 m_i + m_i+1) / 6, where the second derivatives m_i
    solve the tridiagonal system h_i-1 m_i-1 + 2 (h_i-1 + h_i) m_i + h_i m_i+1 =
    6 ((a_i+1 - a_i) / h_i - (a_i - a_i-1) / h_i-1), m_0 = m_n = 0."""

    def __init__(self, t, a):
        n, h = len(t), np.diff(t)
        slope = np.diff(a) / h
        A, r = np.zeros((n, n)), np.zeros(n)
        A[0, 0] = A[-1, -1] = 1.0
        for i in range(1, n - 1):
            A[i, i - 1:i + 2] = h[i - 1], 2.0 * (h[i - 1] + h[i]), h[i]
            r[i] = 6.0 * (slope[i] - slope[i - 1])
        m = np.linalg.solve(A, r)
        self.t, self.h = t, h
        self.c = [a[:-1], slope - h * (2.0 * m[:-1] + m[1:]) / 6.0, m[:-1] / 2.0,
                  (m[1:] - m[:-1]) / (6.0 * h)]
        # v_i, d_i: the integrals at t_i, summed over the intervals before it.
        a0, b, c, e = self.c
        dv = a0 * h + b * h**2 / 2 + c * h**3 / 3 + e * h**4 / 4
        self.v0 = np.concatenate(([0.0], np.cumsum(dv)))
        dd = self.v0[:-1] * h + a0 * h**2 / 2 + b * h**3 / 6 + c * h**4 / 12 + e * h**5 / 20
        self.d0 = np.concatenate(([0.0], np.cumsum(dd)))

    def integrals(self, t):
        """(d, v): the second and first integrals from t_0 at t in [t_0, t_n]."""
        i = min(max(int(np.searchsorted(self.t, t, side="right")) - 1, 0), len(self.h) - 1)
        s = t - self.t[i]
        a0, b, c, e = (x[i] for x in self.c)
        v = self.v0[i] + a0 * s + b * s**2 / 2 + c * s**3 / 3 + e * s**4 / 4
        d = self.d0[i] + self.v0[i] * s + a0 * s**2 / 2 + b * s**3 / 6 + c * s**4 / 12 \
            + e * s**5 / 20
        return float(d), float(v)


class GroundMotion:
    """u_g, v_g of a record: natural cubic spline of a, exact integrals from the first
    sample, zero before it, the displacement held and the velocity zero after the last."""

    def __init__(self, t, a):
        self.t0, self.t1 = t[0], t[-1]
        self.spline = NaturalSpline(t, a)

    def values(self, t):
        if t <= self.t0:
            return 0.0, 0.0
        if t >= self.t1:
            return self.spline.integrals(self.t1)[0], 0.0
        return self.spline.integrals(t)


def rayleigh(M, K, mode_i, zeta_i, mode_j, zeta_j):
    """a0, a1 with zeta_n = a0 / (2 w_n) + a1 w_n / 2 on modes i and j (1-based) of (M, K)."""
    # The generalized problem K x = w^2 M x as the standard one of L^-1 K L^-T, M = L L^T.
    L_inv = np.linalg.inv(np.linalg.cholesky(M))
    w = np.sqrt(np.maximum(np.linalg.eigvalsh(L_inv @ K @ L_inv.T), 0.0))
    wi, wj = w[mode_i - 1], w[mode_j - 1]
    A = np.array([[1.0 / (2.0 * wi), wi / 2.0], [1.0 / (2.0 * wj), wj / 2.0]])
    return np.linalg.solve(A, np.array([zeta_i, zeta_j]))


def matrices(scene, perturb):
    """M, K0, C of the 6 DOF and the rest x of both frames' centres (SegmentedDeck)."""
    segs, bents = scene["model"]["segments"], scene["model"]["bents"]
    M, K = np.zeros((6, 6)), np.zeros((6, 6))
    for i, s in enumerate(segs):
        M[3 * i:3 * i + 3, 3 * i:3 * i + 3] = np.diag([s["mass"], s["mass"], s["inertia"]])
    first_of_frame1 = next(j for j, b in enumerate(bents) if b.get("segment", 0) == 1)
    for j, b in enumerate(bents):
        o, s = 3 * b.get("segment", 0), b["position"]
        scale = perturb if j == first_of_frame1 else 1.0
        by = np.array([0.0, 1.0, s])
        K[o, o] += scale * b["stiffness_longitudinal"]
        K[o:o + 3, o:o + 3] += scale * b["stiffness_transverse"] * np.outer(by, by)
    d = scene["model"]["damping"]
    a0, a1 = rayleigh(M, K, d["mode_i"], d["ratio_i"], d["mode_j"], d["ratio_j"])
    return M, K, a0 * M + a1 * K


def layout(scene):
    """Rest centre x of each frame and the total length (the deck centred on x = 0)."""
    segs, gap = scene["model"]["segments"], scene["model"]["hinges"][0]["gap"]
    total = segs[0]["length"] + gap + segs[1]["length"]
    left = -0.5 * total
    return [left + 0.5 * segs[0]["length"], left + segs[0]["length"] + gap
            + 0.5 * segs[1]["length"]], total


def rotation(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def cross(r, n):
    return r[0] * n[1] - r[1] * n[0]


class CornerOnFace(sk.LagrangianScleronomousR):
    """g_N(q) = n . (p - a) of corner r_b of frame `body` (pose rest + q) against a face
    through a with normal n: a fixed face (`face_body` None), or the face (a_o, n_o) of
    frame `face_body` in that frame's coordinates. Jacobian: (n, r x n) on the corner's frame
    and (-n, -d x n), d = p - centre, on the face's frame (models/parts.hpp)."""

    def __init__(self, body, r_b, rest, face_body, a_o, n_o):
        sk.LagrangianScleronomousR.__init__(self)
        self.body, self.r_b, self.rest = body, np.array(r_b), rest
        self.face_body, self.a_o, self.n_o = face_body, np.array(a_o), np.array(n_o)
        # A SimpleMatrix owned here: Siconos keeps a pointer to it between calls.
        self.jac = sk.SimpleMatrix(1, 6)
        self.setJachqPtr(self.jac)
        self.step = None  # a StepStart: W_N at q_k in place of Siconos's prediction
        self.partner, self.half_face = None, np.inf  # the other pair of a hinge side

    def pose(self, q, i):
        return np.array([self.rest[i] + q[3 * i], q[3 * i + 1]]), q[3 * i + 2]

    def kinematics(self, q):
        centre, angle = self.pose(q, self.body)
        r = rotation(angle) @ self.r_b
        p = centre + r
        if self.face_body is None:
            return p - self.a_o, self.n_o, r, None
        c_b, angle_b = self.pose(q, self.face_body)
        a, n = c_b + rotation(angle_b) @ self.a_o, rotation(angle_b) @ self.n_o
        return p - a, n, r, p - c_b

    def gap(self, q):
        rel, n, _, _ = self.kinematics(q)
        return float(n @ rel)

    def recorded_gap(self, q):
        """The gap nsbridge records for this contact (docs/bridge.md, "Contacts with edges"):
        at a hinge, of the side's two corner-against-face pairs the one whose corner lies
        further inside the other frame's end face (faces of half length W/2 at skew 0), the
        first within 1e-9 m (parts::kEdgeTie). The two gaps differ by O(g theta) while the
        joint is open and coincide at contact, so the motion is that of this relation."""
        if self.partner is None:
            return self.gap(q)
        beyond = []
        for r in (self, self.partner):
            rel, n, _, _ = r.kinematics(q)
            beyond.append(abs(n[0] * rel[1] - n[1] * rel[0]) - self.half_face)
        return self.partner.gap(q) if beyond[1] < beyond[0] - 1e-9 else self.gap(q)

    def computeh(self, q, z, y):
        y[0] = self.gap(q)

    def computeJachq(self, q, z):
        if self.step is not None and self.step.predicted(q):
            q = self.step.q_start
        _, n, r, d = self.kinematics(q)
        row = np.zeros(6)
        o = 3 * self.body
        row[o:o + 3] = [n[0], n[1], cross(r, n)]
        if d is not None:
            o = 3 * self.face_body
            row[o:o + 3] = [-n[0], -n[1], -cross(d, n)]
        for k in range(6):
            self.jac.setValue(0, k, row[k])

    def computeDotJachq(self, q, z, qdot):
        pass  # scleronomic: MoreauJeanOSI needs no dJ/dt

    def C(self):
        # Without this the Python wrapper hands Siconos a temporary copy of the Jacobian.
        return self.jac


def contacts(scene):
    """The six contacts in nsbridge's order (docs/outputs.md): left seat on frame 1's left
    corners, the hinge (frame 2's left corners on frame 1's right end face), right seat on
    frame 2's right corners; corners at y_b = +W/2 first. Skew 0: straight ends."""
    model = scene["model"]
    rest, total = layout(scene)
    half = [0.5 * s["length"] for s in model["segments"]]
    hw = 0.5 * model["segments"][0]["width"]
    seat_e = model["seats"]["restitution"]
    hinge_e = model["hinges"][0]["restitution"]
    left_face = [-0.5 * total - model["gaps"]["left"], 0.0]
    right_face = [0.5 * total + model["gaps"]["right"], 0.0]
    out = []
    for side in (hw, -hw):
        out.append((CornerOnFace(0, [-half[0], side], rest, None, left_face, [1.0, 0.0]), seat_e))
    for side in (hw, -hw):
        hinge = CornerOnFace(1, [-half[1], side], rest, 0, [half[0], 0.0], [1.0, 0.0])
        hinge.partner = CornerOnFace(0, [half[0], side], rest, 1, [-half[1], 0.0], [-1.0, 0.0])
        hinge.half_face = hw
        out.append((hinge, hinge_e))
    for side in (hw, -hw):
        out.append((CornerOnFace(1, [half[1], side], rest, None, right_face, [-1.0, 0.0]), seat_e))
    return out


class StepStart:
    """The diagnostic --jacobian-at-start: MoreauJeanOSI evaluates the relations at its
    predicted position q_k + h u_k before the step's LCP; this hands them q_k instead, where
    nsbridge takes W_N (docs/moreau-jean.md). A Jacobian asked at the prediction (to round-off)
    is evaluated at q_k; every other call, at the q Siconos gives."""

    def __init__(self, h):
        self.h, self.q_start, self.q_predicted = h, np.zeros(6), np.zeros(6)

    def begin(self, q, u):
        self.q_start, self.q_predicted = q, q + self.h * u

    def predicted(self, q):
        q = np.asarray(q)
        scale = 1e-15 * (1.0 + np.max(np.abs(q)))
        return (np.max(np.abs(q - self.q_predicted)) <= scale
                and np.max(np.abs(q - self.q_start)) > 0.0)


class Frames(sk.LagrangianLinearTIDS):
    """M dv + C v + K0 q = F_ext(t) + p, F_ext = K0 e_y u_g(t) + C e_y v_g(t)."""

    def __init__(self, M, K, C, motion):
        sk.LagrangianLinearTIDS.__init__(self, np.zeros(6), np.zeros(6), M, K, C)
        e_y = np.array([0.0, 1.0, 0.0, 0.0, 1.0, 0.0])
        self.k_e, self.c_e, self.motion = K @ e_y, C @ e_y, motion
        self.force = np.zeros(6)
        self.setFExtPtr(self.force)

    def computeFExt(self, t):
        d, v = self.motion.values(t)
        f = self.fExt()
        f[:] = self.k_e * d + self.c_e * v


def run_siconos(scene, scene_dir, perturb, jacobian_at_start=False):
    """Siconos's history: t, the 6 coordinates and the 6 gaps after every step.
    MoreauJeanOSI evaluates the relations' W_N at its prediction q_k + h u_k, nsbridge at q_k
    (docs/moreau-jean.md): the difference the check measures (docs/verification.md), unless
    jacobian_at_start hands Siconos's relations q_k there (StepStart)."""
    M, K, C = matrices(scene, perturb)
    t_rec, a_rec = read_record(os.path.join(scene_dir,
                                            scene["model"]["excitation"]["transverse_record"]))
    solver = scene["solver"]
    h, end = solver["step"], solver["end_time"]
    frames = Frames(M, K, C, GroundMotion(t_rec, a_rec))
    nsds = sk.NonSmoothDynamicalSystem(0.0, end)
    nsds.insertDynamicalSystem(frames)
    keep = []  # the relations, laws and interactions must outlive the simulation
    step = StepStart(h) if jacobian_at_start else None
    for relation, e in contacts(scene):
        relation.step = step
        law = sk.NewtonImpactNSL(e)
        inter = sk.Interaction(law, relation)
        nsds.link(inter, frames)
        keep.append((relation, law, inter))
    td = sk.TimeDiscretisation(0.0, h)
    osi = sk.MoreauJeanOSI(solver["theta"])
    lcp = sk.LCP(sn.SICONOS_LCP_LEMKE)
    sim = sk.TimeStepping(nsds, td, osi, lcp)
    rows = [[0.0] + [0.0] * 6 + [r.recorded_gap(np.zeros(6)) for r, _, _ in keep]]
    steps = round(end / h)
    for k in range(1, steps + 1):
        if step is not None:
            step.begin(np.array(frames.q()), np.array(frames.velocity()))
        sim.computeOneStep()
        q = np.array(frames.q())
        rows.append([k * h] + list(q) + [r.recorded_gap(q) for r, _, _ in keep])
        sim.nextStep()
    return np.array(rows)


def run_nsbridge(nsbridge, scene_path, out_dir):
    """nsbridge's history.csv of the scene as a dict of columns."""
    subprocess.run([nsbridge, "run", scene_path, "--out", out_dir], check=True,
                   stdout=subprocess.DEVNULL)
    data = np.genfromtxt(os.path.join(out_dir, "history.csv"), delimiter=",", names=True)
    return {name: np.asarray(data[name]) for name in data.dtype.names}


def compare(ours, theirs):
    """Per column: max |nsbridge - Siconos| / peak |nsbridge| (the absolute difference of a
    column that stays 0), Siconos interpolated at nsbridge's times."""
    result = {}
    for j, name in enumerate(COLUMNS):
        other = np.interp(ours["t"], theirs[:, 0], theirs[:, j + 1])
        peak = np.max(np.abs(ours[name]))
        diff = np.max(np.abs(ours[name] - other))
        result[name] = (diff / peak if peak > 0.0 else diff, peak)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--nsbridge", required=True, help="the nsbridge executable")
    parser.add_argument("--scene", default=DEFAULT_SCENE)
    parser.add_argument("--tolerance", type=float, default=1e-3,
                        help="largest allowed max |difference| / peak, per column")
    parser.add_argument("--perturb-stiffness", type=float, default=1.0,
                        help="factor on frame 2's first bent, Siconos side only")
    parser.add_argument("--jacobian-at-start", action="store_true",
                        help="diagnostic: Siconos's W_N at q_k, not at its prediction")
    args = parser.parse_args()
    with open(args.scene, "rb") as f:
        scene = tomllib.load(f)
    with tempfile.TemporaryDirectory() as out_dir:
        start = time.perf_counter()
        ours = run_nsbridge(args.nsbridge, args.scene, out_dir)
        middle = time.perf_counter()
    theirs = run_siconos(scene, os.path.dirname(os.path.abspath(args.scene)),
                         args.perturb_stiffness, args.jacobian_at_start)
    end = time.perf_counter()
    result = compare(ours, theirs)
    print(f"siconos_two_frame: h = {scene['solver']['step']} s, theta = "
          f"{scene['solver']['theta']}, {len(theirs) - 1} steps; nsbridge {middle - start:.2f} s,"
          f" Siconos {sk.__name__} {end - middle:.2f} s")
    for name, (rel, peak) in result.items():
        print(f"  {name:7s} peak {peak:.6e}  max |diff| / peak {rel:.3e}")
    worst = max(result, key=lambda n: result[n][0])
    ok = result[worst][0] <= args.tolerance
    print(f"siconos_two_frame: largest {result[worst][0]:.3e} ({worst}), tolerance "
          f"{args.tolerance:.1e}: {'pass' if ok else 'FAIL'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
