#!/usr/bin/python3
"""Fault injection: Ctrl-C (SIGINT) during a run and a sweep, on the command line and in
Python (docs/cli.md, "Ctrl-C"; docs/python.md). Each case sends SIGINT to a child process in
the middle of its work and checks the answer: the command line exits 130, says
"interrupted", and writes nothing of the interrupted runs (a sweep resumes afterwards);
Python raises KeyboardInterrupt within 0.5 s of the signal and leaves no output either.

    interrupts_faults.py NSBRIDGE SOURCE_DIR [PYTHONPATH]

Without PYTHONPATH (the module is not built) the Python cases are skipped, and say so.
"""
import os
import pathlib
import signal
import subprocess
import sys
import tempfile
import time

NSB, ROOT = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
PYTHONPATH = sys.argv[3] if len(sys.argv) > 3 else ""
failures = []
passed = 0

# Ctrl-C must raise KeyboardInterrupt this soon in Python (wall time from the signal).
LATENCY_LIMIT = 0.5  # [s]
# How long a child may take to exit after SIGINT on the command line: the runs read the
# request every 4096 steps (measured below), the rest is process exit.
CLI_EXIT_LIMIT = 0.5  # [s]
# Excitation 7 at this step runs at about 1 us per step on the build machine: 8e6 steps for
# its 40 s, some 8 s of wall time, long enough to be interrupted in the middle.
STEP = 5e-6  # [s]


def check(what, condition, detail=""):
    global passed
    if condition:
        passed += 1
    else:
        failures.append(f"{what} {detail}".strip())
        print(f"FAILED: {what} {detail}", file=sys.stderr)


def leftovers(folder):
    """Hidden staging or temporary entries anywhere under folder."""
    return [str(p) for p in pathlib.Path(folder).rglob(".*") if "tmp" in p.name or "old" in p.name]


def default_sigint():
    # A test runner started in the background hands its children SIGINT ignored; these cases
    # need the disposition a terminal gives.
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def wait_for_line(proc, text, timeout=60.0):
    """Reads the child's stdout until a line containing text; returns that line."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        line = proc.stdout.readline()
        if not line:
            return None
        if text in line:
            return line
    return None


def cli_interrupt(tmp, args, delay):
    """Starts nsbridge ARGS, sends SIGINT after delay s; returns (exit code, output, seconds
    from the signal to the exit)."""
    proc = subprocess.Popen([str(NSB), *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, cwd=tmp, preexec_fn=default_sigint)
    time.sleep(delay)
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=60)
    return proc.returncode, out, time.monotonic() - sent


def main():
    exc7 = str(ROOT / "scenes" / "bridge-exc7.toml")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)

        # 1. nsbridge run: excitation 7 at 5e-6 s steps takes about 8 s; Ctrl-C after 1 s.
        rc, out, took = cli_interrupt(tmp, ["run", exc7, "--out", str(tmp / "run"), "--quiet",
                                            "--set", f"solver.step={STEP}",
                                            "--dump-lcp", str(tmp / "lcp")], 1.0)
        check("run, SIGINT: exit 130", rc == 130, f"(got {rc}: {out.strip()})")
        check("run, SIGINT: says interrupted", "nsbridge: interrupted at t = " in out, out)
        check("run, SIGINT: nothing written", not (tmp / "run").exists() and
              not (tmp / "lcp").exists() and not leftovers(tmp), str(list(tmp.iterdir())))
        check("run, SIGINT: exits within the limit", took < CLI_EXIT_LIMIT, f"({took:.3f} s)")
        print(f"nsbridge run: exit {took:.3f} s after SIGINT")

        # 2. nsbridge sweep: two short runs complete, the long ones are interrupted; the same
        #    command resumes. The runs are excitation 7 at 5e-6 s steps for 0.2 s and 0.3 s
        #    (0.1 s of wall time together) and for 30 s and 40 s (about 6 s each).
        design = tmp / "design.toml"
        design.write_text(f'scene = "{exc7}"\nset = ["solver.step={STEP}"]\nmode = "grid"\n'
                          '[[factor]]\nkey = "solver.end_time"\nvalues = [0.2, 0.3, 30.0, 40.0]\n')
        sweep_args = ["sweep", str(design), "--out", str(tmp / "sweep"), "--jobs", "1"]
        rc, out, took = cli_interrupt(tmp, sweep_args, 1.5)
        check("sweep, SIGINT: exit 130", rc == 130, f"(got {rc}: {out.strip()})")
        check("sweep, SIGINT: says interrupted and how to resume",
              "interrupted: 2 of 4 runs complete" in out and "resumes" in out, out)
        runs = sorted((tmp / "sweep" / "runs").iterdir())
        written = [r.name for r in runs if (r / "row.csv").exists()]
        check("sweep, SIGINT: the two short runs are written, the interrupted one is not",
              len(written) == 2 and all(not any(r.iterdir()) for r in runs
                                        if r.name not in written), str(written))
        check("sweep, SIGINT: no results.csv, no staging",
              not (tmp / "sweep" / "results.csv").exists() and not leftovers(tmp / "sweep"))
        check("sweep, SIGINT: exits within the limit", took < CLI_EXIT_LIMIT, f"({took:.3f} s)")
        print(f"nsbridge sweep: exit {took:.3f} s after SIGINT")
        # The same command resumes: it finds the two complete runs (and is interrupted again in
        # the first long one, to keep this test short).
        rc, out, took = cli_interrupt(tmp, sweep_args, 1.0)
        check("sweep resumed after SIGINT: the two complete runs are kept",
              rc == 130 and "interrupted: 2 of 4 runs complete" in out, out)

        if not PYTHONPATH or not list(pathlib.Path(PYTHONPATH).glob("nsbridge/_nsbridge*.so")):
            print("SKIPPED: Python cases: the module is not built (NSB_PYTHON off)")
            return

        # 3. Python: nsbridge.run and nsbridge.sweep, each in a child /usr/bin/python3 that
        #    prints when it starts and when KeyboardInterrupt arrives (time.monotonic is the
        #    system's CLOCK_MONOTONIC, the same in both processes).
        child = f"""
import sys, time, nsbridge
what = sys.argv[1]
print("ready", flush=True)
try:
    if what == "run":
        nsbridge.run({exc7!r}, overrides={{"solver.step": {STEP}}})
    else:
        nsbridge.sweep({str(design)!r}, {str(tmp / 'py-sweep')!r}, jobs=1)
    print("finished", time.monotonic(), flush=True)
except KeyboardInterrupt:
    print("interrupted", time.monotonic(), flush=True)
"""
        env = dict(os.environ, PYTHONPATH=PYTHONPATH)
        for what in ("run", "sweep"):
            proc = subprocess.Popen(["/usr/bin/python3", "-c", child, what], env=env, cwd=tmp,
                                    stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                    preexec_fn=default_sigint)
            check(f"python {what}: started", wait_for_line(proc, "ready") is not None)
            # The sweep's two short runs end within 0.2 s; the signal comes in a long run.
            time.sleep(1.5)
            sent = time.monotonic()
            proc.send_signal(signal.SIGINT)
            line = wait_for_line(proc, "interrupted", timeout=30) or ""
            proc.communicate(timeout=60)
            ok = line.startswith("interrupted")
            check(f"python {what}: KeyboardInterrupt", ok, f"(got {line!r})")
            if ok:
                latency = float(line.split()[1]) - sent
                # Measured on the 2-core build machine, with a build running beside: 0.053 s
                # for run, 0.069 s for sweep (its calling thread polls every 50 ms). The base
                # commit raised it only when the work ended: 21 s and 44 s later.
                check(f"python {what}: KeyboardInterrupt within {LATENCY_LIMIT} s",
                      latency < LATENCY_LIMIT, f"({latency:.3f} s)")
                print(f"nsbridge.{what}: KeyboardInterrupt {latency:.3f} s after SIGINT")
        check("python sweep: no staging left", not leftovers(tmp / "py-sweep"))
        check("python sweep: no results.csv", not (tmp / "py-sweep" / "results.csv").exists())


main()
print(f"interrupts faults: {passed} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
