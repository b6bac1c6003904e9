"""`fcsolve report DIR`: PNG charts and one self-contained HTML page from the CSV."""
import base64
import datetime
import html
import json
import os

from . import analysis, charts
from .results import FAILURE_CLASSES, csv_path, load_results

MAX_TABLE_ROWS = 5000


def _fmt(x, spec=".3g"):
    return "" if x is None else format(x, spec)


def _img(path, alt):
    with open(path, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    return f'<img alt="{html.escape(alt)}" src="data:image/png;base64,{data}">'


def _table(header, body, cls=""):
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    rows = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in r) + "</tr>" for r in body)
    return f'<table class="{cls}"><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>'


def _summary_table(rows):
    header = ["solver", "tol", "runs", "solved", "median time [s]", "geo-mean time [s]"] + [
        c for c in FAILURE_CLASSES if c != "converged"]
    body = []
    for e in analysis.summary(rows):
        body.append([html.escape(e["solver"]), f"{e['tol']:g}", e["runs"],
                     f"{e['solved']} ({e['solved_fraction']:.0%})", _fmt(e["median_seconds"]),
                     _fmt(e["geomean_seconds"])] +
                    [e["failures"].get(c, "") for c in header[6:]])
    return _table(header, body, "summary")


def _family_table(rows, tol):
    table = analysis.by_family(rows, tol)
    solvers = analysis.solver_names([r for r in rows if r["tol"] == tol])
    body = [[html.escape(f)] + [f"{d[s][0]}/{d[s][1]}" for s in solvers] for f, d in table.items()]
    return f"<p>Solved per problem family, tol {tol:g}:</p>" + _table(["family"] + solvers, body)


def _runs_table(rows):
    cols = ["problem", "family", "kind", "nc", "solver", "tol", "failure", "status", "seconds",
            "iterations", "own_error", "error", "message"]
    body = []
    order = {s: k for k, s in enumerate(analysis.solver_names(rows))}
    rows = sorted(rows, key=lambda r: (r["problem"], order[r["solver"]], -r["tol"]))
    for r in rows[:MAX_TABLE_ROWS]:
        cells = []
        for c in cols:
            v = r.get(c)
            text = _fmt(v) if isinstance(v, float) else ("" if v is None else str(v))
            if c == "failure":
                colour = charts.FAILURE_COLOURS.get(text, "#fff")
                text = f'<span class="dot" style="background:{colour}"></span>{html.escape(text)}'
            else:
                text = html.escape(text)
            cells.append(text)
        body.append(cells)
    note = (f"<p>First {MAX_TABLE_ROWS} of {len(rows)} runs; all are in the CSV.</p>"
            if len(rows) > MAX_TABLE_ROWS else "")
    return note + _table(cols, body, "runs")


def _invocations(out_dir):
    """What campaign.json recorded of each `fcsolve bench` (may be absent)."""
    path = os.path.join(out_dir, "campaign.json")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return json.load(f).get("invocations", [])


def _registration_order(rows, out_dir):
    """Rows with solvers in the order the campaign named them (catalogue order)."""
    order = {}
    for inv in _invocations(out_dir):
        for s in inv.get("solvers", []):
            order.setdefault(s["name"], len(order))
    return sorted(rows, key=lambda r: order.get(r["solver"], len(order)))


def _solver_families(out_dir):
    """{solver: family} as campaign.json recorded it (fcsolve solvers --json)."""
    return {s["name"]: s.get("family") or "" for inv in _invocations(out_dir)
            for s in inv.get("solvers", [])}


def _peer_families(out_dir):
    return {s.get("family") for inv in _invocations(out_dir) for s in inv.get("solvers", [])
            if s.get("peer")}


def _family_view(rows, out_dir, png):
    """The family view's charts and its HTML: auto against each family's best
    member (analysis.best_members, analysis.family_lines)."""
    families = _solver_families(out_dir)
    lines, left_out = analysis.family_lines(rows, families)
    if not lines:
        return ""
    solvers = [s for _, s in lines]
    styles = charts.family_styles(lines, _peer_families(out_dir))
    note = f" (left out: {', '.join(left_out)})" if left_out else ""
    tols = analysis.tolerances(rows)
    tight = min(tols)
    profile_tols = [t for t in (1e-4, 1e-8) if t in tols] or [tight]
    profile = charts.family_profiles(rows, profile_tols, png("family_profile.png"), styles,
                                     solvers, note)
    wp = charts.work_precision(rows, png("family_work_precision.png"), styles, solvers, note)
    labels = {s: styles[s]["label"] for s in solvers}
    maps = [charts.failure_map(rows, t, png(f"family_failure_map_tol{t:g}.png"), solvers, labels,
                               note) for t in analysis.ordered([t for t in (1e-8,) if t in tols]
                                                               + [tight])]
    members = {}
    for s in analysis.solver_names(rows):
        members.setdefault(analysis.family_of_solver(s, families), []).append(s)
    best = analysis.best_members(rows, families)
    shown = dict(lines)
    body = []
    for family, names in members.items():
        count, total = analysis.solved_and_time(rows, best[family], tight)
        colour = charts.family_colour(family)
        body.append([f'<span class="dot" style="background:{colour}"></span>{html.escape(family)}',
                     html.escape(best[family]), count, _fmt(total),
                     html.escape(", ".join(n for n in names if n != best[family])),
                     "yes" if family in shown else "<b>left out</b>"])
    table = _table(["family", "best member", f"solved at {tight:g}", "total time [s] (solved)",
                    "other members", "drawn"], body)
    return ("<h2>Family view: auto against each family's best member</h2><p class='note'>"
            f"One line per solver family: its best member on this campaign, the one that solved "
            f"the most problems at the tightest tolerance ({tight:g}), ties broken by the total "
            f"time on the problems it solved; peers reduced the same way; at most "
            f"{analysis.MAX_FAMILY_LINES} lines, auto always kept, the others ranked by problems "
            f"solved at {tight:g}" + (f"; left out: {html.escape(', '.join(left_out))}"
                                       if left_out else "")
            + ". One colour per family in every chart; auto bold black; dashed: peers. The "
            "profiles' ratios are to the best of these lines, over every problem of the "
            "campaign.</p>" + table + _img(wp, "family work-precision diagram")
            + _img(profile, "family performance profiles")
            + "".join(_img(m, "family failure map") for m in maps))


def _campaign_info(out_dir):
    inv = _invocations(out_dir)
    if not inv:
        return ""
    last = inv[-1]
    items = [("machine", f"{last.get('host')} ({last.get('machine')}, {last.get('cpus')} CPUs)"),
             ("fcsolve", f"{last.get('fcsolve_version') or ''} {last.get('fcsolve') or ''}"),
             ("executor", last.get("executor")), ("time limit", f"{last.get('timeout')} s per run"),
             ("runs", f"{len(inv)} invocation(s), the last on {last.get('date')}")]
    return "<ul>" + "".join(f"<li><b>{k}</b>: {html.escape(str(v))}</li>" for k, v in items) + "</ul>"


STYLE = """
body{font-family:sans-serif;max-width:1200px;margin:1em auto;padding:0 1em;color:#222}
h1{font-size:1.5em} h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}
table{border-collapse:collapse;font-size:0.85em;margin:0.5em 0}
th,td{border:1px solid #ddd;padding:2px 6px;text-align:right}
th{background:#f3f3f3} td:first-child{text-align:left}
table.runs td{text-align:left}
img{max-width:100%;display:block;margin:0.5em 0}
.dot{display:inline-block;width:0.8em;height:0.8em;border-radius:50%;margin-right:4px;
border:1px solid #888;vertical-align:middle}
.note{color:#555;font-size:0.9em}
"""


def build_report(out_dir, report_dir=None):
    """Writes the PNGs and report.html into report_dir (default DIR/report); returns the page's path."""
    rows = load_results(csv_path(out_dir))
    if not rows:
        raise RuntimeError(f"{csv_path(out_dir)} has no runs")
    rows = _registration_order(rows, out_dir)
    report_dir = report_dir or os.path.join(out_dir, "report")
    os.makedirs(report_dir, exist_ok=True)
    styles = charts.solver_styles(analysis.solver_names(rows))
    tols = analysis.tolerances(rows)
    sections = []

    def png(name):
        return os.path.join(report_dir, name)

    profiles = [charts.performance_profiles(rows, t, png(f"profile_tol{t:g}.png"), styles)
                for t in tols]
    wp = charts.work_precision(rows, png("work_precision.png"), styles)
    scatter = charts.time_vs_error(rows, png("time_vs_error.png"), styles)
    maps = [charts.failure_map(rows, t, png(f"failure_map_tol{t:g}.png")) for t in tols]

    problems = analysis.ordered(r["problem"] for r in rows)
    solvers = analysis.solver_names(rows)
    sections.append(_family_view(rows, out_dir, png))
    sections.append(f"<h2>Summary per solver</h2><p class='note'>A run is solved iff the error "
                    f"recomputed from its returned solution is &le; tol; times are the solvers' own "
                    f"(setup + solve), medians and geometric means over solved runs only.</p>"
                    + _summary_table(rows))
    sections.append("<h2>Performance profiles (Dolan &amp; Moré 2002)</h2><p class='note'>"
                    "ρ<sub>s</sub>(τ): fraction of the problems that solver s solved within a "
                    "factor τ of the best solver on each problem; ρ(1) is how often s wins, the "
                    "right end how often it solves at all. Dashed: peers. An iteration is each "
                    "solver's own unit (a Gauss-Seidel sweep, a Newton or interior-point step): "
                    "compare iterations within a family, time across families.</p>"
                    + "".join(_img(p, "performance profile") for p in profiles))
    sections.append("<h2>Speed against accuracy</h2>" + _img(wp, "work-precision diagram")
                    + _img(scatter, "time against achieved error"))
    sections.append("<h2>Failure map</h2><p class='note'>Failure classes: converged (solved), "
                    "max-iterations, stalled, diverged, nan, inaccurate (the solver claimed "
                    "convergence, the recomputed error says otherwise), timeout (killed at the "
                    "limit), crash (died or returned no usable solution); white: not run (kind not "
                    "supported).</p>" + "".join(_img(p, "failure map") + _family_table(rows, t)
                                                for p, t in zip(maps, tols)))
    sections.append("<h2>Every run</h2><details><summary>show the table</summary>"
                    + _runs_table(rows) + "</details>")
    page = (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>fcsolve campaign</title>"
            f"<style>{STYLE}</style></head><body><h1>fcsolve benchmark campaign</h1>"
            f"<p>{len(problems)} problems &times; {len(solvers)} solvers &times; {len(tols)} "
            f"tolerance(s) = {len(rows)} runs; report generated "
            f"{datetime.datetime.now().isoformat(timespec='seconds')} from "
            f"<code>{html.escape(os.path.abspath(csv_path(out_dir)))}</code>.</p>"
            + _campaign_info(out_dir) + "".join(sections) + "</body></html>")
    path = os.path.join(report_dir, "report.html")
    with open(path, "w") as f:
        f.write(page)
    return path
