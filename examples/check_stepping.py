#!/usr/bin/env python3
"""Run a time-stepping example (mbs_pile, fem_contact) and check what it did.

    check_stepping.py --tol 1e-8 [--dump-step K --workdir DIR [--cli FCSOLVE]
                      [--fcref FCREF.py --ref-python PYTHON]] [--compare-cold]
                      -- EXAMPLE [ARGS...]

Checks, from the example's own output (stepping/step_log.hpp's format):
  - it exits with 0 and prints one line per step of the header's steps=K;
  - every step's error is <= --tol (read from the table, not from the exit
    code), and some step had contacts;
  - the summary line agrees (converged == steps).
With --dump-step K it also runs the example with --dump K FILE --dump-local
FILE2, then checks both files independently:
  - `fcsolve info` reads them (kind, number of contacts = the step's);
  - `fcsolve error FILE FILE` and shared/tools/fcref.py (when present and
    its Python has numpy, scipy, h5py; skipped otherwise) measure the stored
    solution's error <= --tol (up to rounding: the example measured the same
    quantity on its own arrays).
With --compare-cold it runs the example again with --no-warm-start and
checks that the warm start did not cost iterations over the trajectory.
Standard library only. Exit status: 0 all checks passed, 1 otherwise.
"""
import argparse
import os
import re
import subprocess
import sys

ROUNDING = 1e-3  # relative slack on a re-measured error (different summation order)


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return p.returncode, p.stdout, p.stderr


def parse_table(out):
    """(header parameters, step rows, summary dict) from an example's stdout."""
    header, rows, summary = {}, [], {}
    for line in out.splitlines():
        if line.startswith("# summary"):
            summary = dict(kv.split("=", 1) for kv in line.split()[2:])
        elif line.startswith("#"):
            header.update(kv.split("=", 1) for kv in line.split()[2:] if "=" in kv)
        elif line.strip():
            f = line.split()
            rows.append(dict(step=int(f[0]), contacts=int(f[1]), iterations=int(f[2]),
                             error=float(f[3]), time=float(f[4]), setup=float(f[5]), status=f[6]))
    return header, rows, summary


class Checks:
    def __init__(self):
        self.failed = 0

    def expect(self, ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            self.failed += 1
        return ok


def check_run(c, rc, out, err, tol, label):
    c.expect(rc == 0, f"{label}: exit status {rc} (0: every step reached the tolerance)" +
             (f"; stderr: {err.strip()}" if err.strip() else ""))
    header, rows, summary = parse_table(out)
    steps = int(header.get("steps", -1))
    c.expect(len(rows) == steps and [r["step"] for r in rows] == list(range(1, steps + 1)),
             f"{label}: {len(rows)} step lines for steps={steps}")
    bad = [r for r in rows if not r["error"] <= tol]
    c.expect(not bad, f"{label}: every step's error <= {tol:g}" +
             (f" (first failure: step {bad[0]['step']}, error {bad[0]['error']:g}, {bad[0]['status']})" if bad else ""))
    worst = max((r["error"] for r in rows), default=0.0)
    with_contacts = sum(1 for r in rows if r["contacts"] > 0)
    c.expect(with_contacts > 0, f"{label}: {with_contacts} steps with contacts, worst error {worst:.3g}")
    c.expect(summary.get("converged") == summary.get("steps") == str(steps),
             f"{label}: summary converged={summary.get('converged')} steps={summary.get('steps')}")
    return header, rows, summary


def key_values(text):
    return dict(kv.split("=", 1) for kv in re.findall(r"(\w+=\S+)", text))


def check_dump(c, path, kind, contacts, tol, cli, fcref, ref_python):
    c.expect(os.path.isfile(path), f"dump {os.path.basename(path)} written")
    if not os.path.isfile(path):
        return
    if cli:
        rc, out, err = run([cli, "info", path])
        info = key_values(out)
        c.expect(rc == 0 and info.get("kind") == kind and info.get("nc") == str(contacts),
                 f"fcsolve info: kind={info.get('kind')} nc={info.get('nc')} (expected {kind}, {contacts})"
                 + (f"; {err.strip()}" if rc else ""))
        rc, out, err = run([cli, "error", path, path])
        e = float(key_values(out).get("error", "inf"))
        c.expect(rc == 0 and e <= tol * (1 + ROUNDING), f"fcsolve error: {e:.3g} <= {tol:g}" + (f"; {err.strip()}" if rc else ""))
    else:
        print("skip  fcsolve info/error: no --cli")
    if fcref and os.path.isfile(fcref) and ref_python:
        rc, _, _ = run([ref_python, "-c", "import numpy, scipy, h5py"])
        if rc != 0:
            print(f"skip  fcref.py: {ref_python} lacks numpy/scipy/h5py")
            return
        rc, out, err = run([ref_python, fcref, path, path])
        m = re.search(r"^error (\S+)", out, re.M)
        e = float(m.group(1)) if m else float("inf")
        c.expect(rc == 0 and out.startswith(kind) and f"nc={contacts} " in out and e <= tol * (1 + ROUNDING),
                 f"fcref.py: {out.splitlines()[0] if out else err.strip()}; error {e:.3g} <= {tol:g}")
    else:
        print("skip  fcref.py: not present")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tol", type=float, required=True)
    ap.add_argument("--dump-step", type=int)
    ap.add_argument("--workdir", default=".")
    ap.add_argument("--cli")
    ap.add_argument("--fcref")
    ap.add_argument("--ref-python")
    ap.add_argument("--compare-cold", action="store_true")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    if not cmd:
        ap.error("no example command after --")
    name = os.path.basename(cmd[0])
    cmd = cmd + ["--tol", repr(a.tol)]
    c = Checks()

    dump = dump_local = None
    if a.dump_step is not None:
        os.makedirs(a.workdir, exist_ok=True)
        dump = os.path.join(a.workdir, f"{name}_step{a.dump_step}.hdf5")
        dump_local = os.path.join(a.workdir, f"{name}_step{a.dump_step}_local.hdf5")
        for p in (dump, dump_local):
            if os.path.exists(p):
                os.remove(p)
        warm_cmd = cmd + ["--dump", str(a.dump_step), dump, "--dump-local", dump_local]
    else:
        warm_cmd = cmd
    print("run   " + " ".join(warm_cmd))
    _, rows, summary = check_run(c, *run(warm_cmd), a.tol, name)

    if dump:
        at = [r for r in rows if r["step"] == a.dump_step]
        contacts = at[0]["contacts"] if at else -1
        c.expect(contacts > 0, f"step {a.dump_step} has {contacts} contacts to dump")
        check_dump(c, dump, "global", contacts, a.tol, a.cli, a.fcref, a.ref_python)
        check_dump(c, dump_local, "local", contacts, a.tol, a.cli, a.fcref, a.ref_python)

    if a.compare_cold:
        cold_cmd = cmd + ["--no-warm-start"]
        print("run   " + " ".join(cold_cmd))
        _, _, cold = check_run(c, *run(cold_cmd), a.tol, name + " --no-warm-start")
        warm_it, cold_it = int(summary.get("iterations", -1)), int(cold.get("iterations", -1))
        c.expect(0 <= warm_it <= cold_it, f"iterations: warm start {warm_it} <= cold {cold_it}")

    print(f"{c.failed} check(s) failed" if c.failed else "all checks passed")
    return 1 if c.failed else 0


if __name__ == "__main__":
    sys.exit(main())
