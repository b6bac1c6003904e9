"""The solvers a campaign runs: fcsolve's catalogue and the peers.

fcsolve's solvers are discovered with `fcsolve solvers --json`, so every
solver registered in the binary takes part without any change here. Peers are
named PEER:SOLVER (siconos:nsgs) and run through a runner script with the
same interface as `fcsolve solve`.
"""
import dataclasses
import functools
import json
import os
import shutil
import subprocess

PEER_RUNNERS = {"siconos": "siconos_runner.py"}
DEFAULT_PEER_PYTHON = "/usr/bin/python3"


@dataclasses.dataclass
class CampaignSolver:
    """One solver a campaign runs, as a command line: an fcsolve catalogue
    entry or a peer's solver (not fcsolve.SolverSpec, which describes a
    catalogue entry's settings for the Python API)."""

    name: str                # as in the CSV
    family: str              # "vi", "nsgs", ... or the peer ("siconos")
    prefix: list             # the command before FILE
    local: bool = True       # can solve FC/II
    global_: bool = True     # can solve FC/I (natively or by reduction)
    peer: bool = False

    def supports(self, kind):
        return self.local if kind == "local" else self.global_

    def command(self, file, tol, max_time, out, max_iter=None):
        argv = self.prefix + [file, "--solver", self.name.split(":", 1)[-1], "--tol", repr(float(tol)),
                              "--max-time", repr(float(max_time)), "--json", "--out", out]
        if max_iter:
            argv += ["--max-iter", str(int(max_iter))]
        return argv


def find_fcsolve(explicit=None):
    """The fcsolve binary: --fcsolve, $FCSOLVE_CLI (set by `fcsolve bench`), PATH, ./build."""
    for candidate in (explicit, os.environ.get("FCSOLVE_CLI"), shutil.which("fcsolve"),
                      os.path.join("build", "fcsolve")):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return os.path.abspath(candidate)
    return None


def _json_command(argv, what):
    try:
        done = subprocess.run(argv, capture_output=True, text=True, timeout=120)
    except OSError as e:
        raise RuntimeError(f"cannot run {what}: {e}") from e
    if done.returncode != 0:
        raise RuntimeError(f"{what} failed (exit code {done.returncode}): {done.stderr.strip()}")
    return json.loads(done.stdout)


def fcsolve_solvers(fcsolve):
    """Every solver registered in the binary, as CampaignSolver."""
    entries = _json_command([fcsolve, "solvers", "--json"], f"{fcsolve} solvers --json")
    return [CampaignSolver(name=e["name"], family=e.get("family", ""), prefix=[fcsolve, "solve"],
                       local=bool(e.get("local", True)),
                       # a local solver solves FC/I by reduction (registry::solve)
                       global_=bool(e.get("local", True) or e.get("global_native", False)))
            for e in entries]


def runner_path(peer):
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), PEER_RUNNERS[peer])


@functools.lru_cache(maxsize=None)
def peer_solvers(peer, python=DEFAULT_PEER_PYTHON):
    """The peer's solvers as CampaignSolver; RuntimeError saying why when it cannot run."""
    if peer not in PEER_RUNNERS:
        raise RuntimeError(f"unknown peer '{peer}' (known: {', '.join(PEER_RUNNERS)})")
    runner = runner_path(peer)
    try:
        done = subprocess.run([python, runner, "--list"], capture_output=True, text=True, timeout=120)
    except OSError as e:
        raise RuntimeError(f"peer '{peer}': cannot run {python}: {e}") from e
    if done.returncode != 0:
        raise RuntimeError(f"peer '{peer}' skipped: {done.stderr.strip() or 'runner failed'}")
    return [CampaignSolver(name=f"{peer}:{e['name']}", family=peer, prefix=[python, runner],
                       local=e["local"], global_=e["global_native"], peer=True)
            for e in json.loads(done.stdout)]


def resolve(spec, fcsolve=None, peer_python=DEFAULT_PEER_PYTHON, warn=print):
    """The CampaignSolver list for a --solvers list: names, `all` (every fcsolve solver),
    `PEER:all` (every solver of a peer). A peer that cannot run is skipped with
    a message; an unknown name is an error."""
    names = [s.strip() for s in spec.split(",") if s.strip()] if isinstance(spec, str) else list(spec)
    wanted_fcsolve = [n for n in names if ":" not in n]
    catalogue = {}
    if wanted_fcsolve:
        if not fcsolve:
            raise RuntimeError("no fcsolve binary found: build it (build/fcsolve) or pass --fcsolve")
        catalogue = {s.name: s for s in fcsolve_solvers(fcsolve)}
    out, failed_peers = [], set()
    for n in names:
        if ":" not in n:
            if n == "all":
                out += list(catalogue.values())
            elif n in catalogue:
                out.append(catalogue[n])
            else:
                raise RuntimeError(f"unknown solver '{n}' (registered: {', '.join(catalogue)})")
            continue
        peer, solver = n.split(":", 1)
        if peer in failed_peers:
            continue
        try:
            available = {s.name: s for s in peer_solvers(peer, peer_python)}
        except RuntimeError as e:
            warn(f"fcsolve bench: {e}")
            failed_peers.add(peer)
            continue
        if solver == "all":
            out += list(available.values())
        elif n in available:
            out.append(available[n])
        else:
            raise RuntimeError(f"unknown solver '{n}' (peer solvers: {', '.join(available)})")
    unique = list({s.name: s for s in out}.values())
    if not unique:
        raise RuntimeError("no solver to run")
    return unique
