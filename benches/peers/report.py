#!/usr/bin/env python3
"""The peer comparison's JSON record, its Markdown tables, and the writer
that puts them into the documentation.

`run.py` calls `markdown` and `as_json` at the end of a run. The tables are
always rendered from the JSON record (`render_table`, `render_summary`), so
a saved `OUT/peers.json` reproduces them exactly, and

    python3 benches/peers/report.py OUT/peers.json --write-docs

rewrites the full table in `docs/performance.md` (between the lines
`<!-- peers:begin ... -->` and `<!-- peers:end -->`) and the short table in
`README.md` (between `<!-- peers-summary:begin ... -->` and
`<!-- peers-summary:end -->`), leaving every other line of both files as it
was. Without `--write-docs` the full table goes to standard output.
"""
import argparse
import json
import os
import sys

TASK_WORDS = {"points": "points", "rays": "first-hit rays", "validate": "import + validate"}

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DOCS_PAGE = os.path.join(ROOT, "docs", "performance.md")
README = os.path.join(ROOT, "README.md")
# The marker names: `<!-- NAME:begin ... -->` and `<!-- NAME:end -->`, each on a line of its own.
FULL_TABLE = "peers"
SHORT_TABLE = "peers-summary"


class MarkerError(Exception):
    """A documentation file lacks a marker pair, or holds it twice or out of order."""


# ---------------------------------------------------------------- the record

def as_json(rows, verdicts, validations, metas, info):
    """Everything measured, as plain JSON (the answer arrays reduced to counts)."""
    def row(r):
        keep = {k: v for k, v in r.items() if k not in ("answers", "differs")}
        keep["answered"] = len(r["answers"])
        keep["differs"] = len(r["differs"])
        keep["first_differing"] = r["differs"][:20].tolist()
        return keep

    def verdict(v):
        return {"disputed": v["disputed"], "settled": len(v["answers"]), "control": len(v["control"]),
                "wingedge_wrong": v["wingedge_wrong"],
                "said": {str(i): a for i, a in v["said"].items()},
                "seconds": v["seconds"],
                "answers": {str(i): (a if isinstance(a, str) else [a[0], a[1]]) for i, a in v["answers"].items()}}

    return {"machine": info, "inputs": metas, "queries": [row(r) for r in rows],
            "exact": {m: {t: verdict(v) for t, v in by.items()} for m, by in verdicts.items()},
            "validation": validations}


def markdown(rows, verdicts, validations, info, args):
    """The full table of a run, rendered from its JSON record.

    Notes the run's settings (`--rounds`, `--arbitrate`) in `info["settings"]`,
    so that the record `as_json` makes from the same `info` carries them.
    """
    info["settings"] = {"rounds": args.rounds, "arbitrate": args.arbitrate}
    return render_table(as_json(rows, verdicts, validations, {}, info))


# ---------------------------------------------------------------- cells

def _rate(row):
    rate = row["queries"] / row["seconds"] / 1e6
    text = "%.3g M/s" % rate if rate >= 0.01 else "%s /s" % format(round(rate * 1e6), ",")
    if row["queries"] < row.get("answered", row["queries"]) or row["queries"] < 1_000_000:
        text += " (%s queries)" % format(row["queries"], ",")
    return rate, text


def _exact_cell(row, verdict):
    if row["library"] == "wingedge":
        return "%d of %d settled queries wrong" % (verdict["wingedge_wrong"], verdict["settled"])
    n = row["differs"]
    if n == 0:
        return "—"
    checked = row["checked"]
    text = "wingedge %d, %s %d wrong" % (row["wingedge_wrong"], row["library"].split()[0], row["peer_wrong"])
    if checked < n:
        text += " (%d of %d checked)" % (checked, n)
    return text


def _ratio(x):
    return "**%.2f×**" % x if x >= 0.1 else "**%.2g×**" % x


def _label(row):
    return "%s (%s, %d thr)" % (row["library"], row["precision"], row["threads"])


def _settings(record):
    settings = record["machine"].get("settings")
    if settings is None:
        raise SystemExit("the record has no machine.settings (rounds, arbitrate): it predates report.py's "
                         "writer; add them by hand from the run's command line")
    return settings


SET_WORDS = {"near1e-3": "points at 1e-3 of the diagonal from the surface",
             "near1e-6": "points at 1e-6 of the diagonal from the surface",
             "inside": "rays from inside the box, random directions",
             "vertices": "rays aimed at vertices", "grazing": "rays grazing along faces"}
# The README's columns: the uniform points and sphere rays (no set), then the sets.
SUMMARY_COLUMNS = [("points", None, "uniform points"), ("points", "near1e-3", "points near, 1e-3"),
                   ("points", "near1e-6", "points near, 1e-6"), ("rays", None, "rays from outside"),
                   ("rays", "inside", "rays from inside"), ("rays", "vertices", "rays at vertices"),
                   ("rays", "grazing", "grazing rays")]


def _key(row):
    """A row's key in `record["exact"]`: the mesh, or `mesh@set` for a harder query set."""
    return row["mesh"] + ("@" + row["set"] if row.get("set") else "")


def _query_groups(record, with_sets=False):
    """(key, task, wingedge's row, every row) for each mesh (and query set,
    when `with_sets`) and query task, in run order."""
    rows = [r for r in record["queries"] if with_sets or not r.get("set")]
    for key in dict.fromkeys(_key(r) for r in rows):
        for task in ("points", "rays"):
            group = [r for r in rows if _key(r) == key and r["task"] == task]
            if group:
                yield key, task, next(r for r in group if r["library"] == "wingedge"), group


# ---------------------------------------------------------------- the full table

def _table_row(r, ours, task, what, exact):
    """One library's row of a query table: mesh, `what` was asked, setup,
    rate, ratio to wingedge, disagreements and their exact settling."""
    our_rate, _ = _rate(ours)
    rate, rate_text = _rate(r)
    differ = "%s of %s" % (format(r["differs"], ","), format(r.get("answered", r["queries"]), ","))
    if task == "rays" and r["library"] != "wingedge":
        differ += "; elsewhere \\|Δt\\| ≤ %.1g" % r["max_t_gap"]
    return "| %s (%s) | %s | %s | %.3f | %s | %s | %s | %s |" % (
        r["mesh"], format(r["triangles"], ","), what, _label(r), r["setup_s"], rate_text,
        "1" if r is ours else _ratio(rate / our_rate), differ, _exact_cell(r, exact))


def _query_lines(record):
    lines = []
    for mesh, task, ours, group in _query_groups(record):
        for r in group:
            lines.append(_table_row(r, ours, task, TASK_WORDS[task], record["exact"][mesh][task]))
    return lines


def _set_lines(record):
    lines = []
    for key, task, ours, group in _query_groups(record, with_sets=True):
        if not ours.get("set"):
            continue
        for r in group:
            what = SET_WORDS.get(r["set"], r["set"])
            lines.append(_table_row(r, ours, task, what, record["exact"][key][task]))
    return lines


def _validation_lines(record):
    triangles = {r["mesh"]: r["triangles"] for r in record["queries"]}
    lines = []
    for mesh, results in record["validation"].items():
        ours = results["wingedge"]
        for library, v in results.items():
            tri_rate = triangles[mesh] / v["seconds"] / 1e6
            rate = "%.3g s (%.2f M tri/s), peak %.0f MiB" % (
                v["seconds"], tri_rate, float("nan") if v["rss_mib"] is None else v["rss_mib"])
            if library == "wingedge":
                agree = "%s, genus %s, volume %.9g" % (
                    v["verdict"], v["genus"], float("nan") if v["volume"] is None else v["volume"])
                ratio = "1"
            else:
                ratio = _ratio(ours["seconds"] / v["seconds"])
                if "status" in v:
                    same = v["valid"] == ours["valid"]
                    vol = abs(v["volume"] - ours["volume"]) / abs(ours["volume"]) if ours["volume"] else float("nan")
                    agree = "%s: status %s, genus %d, volume rel. diff %.0e; trimesh watertight %s, winding consistent %s" % (
                        "agrees" if same and v["genus"] == ours["genus"] else "**differs**", v["status"],
                        v["genus"], vol, v["trimesh_watertight"], v["trimesh_winding_consistent"])
                else:
                    same = v["topology_ok"] == ours["valid"]
                    agree = "%s: half-edge topology %s (checks only orientation and repeated corners)" % (
                        "agrees" if same else "**differs**",
                        "ok" if v["topology_ok"] else "error: " + str(v["topology_error"]))
            lines.append("| %s (%s) | import + validate | %s | %.3f (import) | %s | %s | %s | |" % (
                mesh, format(triangles[mesh], ","), library, v["import_s"], rate, ratio, agree))
    return lines


def _dispute_lines(record):
    lines = []
    for mesh, by_task in record["exact"].items():
        for task, v in by_task.items():
            for i, said in list(v["said"].items())[:10]:
                truth = v["answers"][i]
                if task == "points":
                    exact_text = truth
                    words = ", ".join("%s %s" % (lib, a) for lib, a in said.items())
                else:
                    exact_text = "miss" if truth[0] == float("inf") else "t = %.9g (%s)" % tuple(truth)
                    words = ", ".join("%s %s" % (lib, "miss" if a == float("inf") else "%.7g" % a)
                                      for lib, a in said.items())
                lines.append("- %s %s #%d: exact %s; %s" % (
                    mesh, "point" if task == "points" else "ray", int(i), exact_text, words))
    return lines


def render_table(record):
    """The full Markdown block of one run: the machine, every row, the exact arbitration, the disputes."""
    info, settings = record["machine"], _settings(record)
    pk = info["packages"]
    out = ["Measured %s on %s (%d cores), %d threads for every library that can use them; "
           "Python %s, numpy %s, trimesh %s with embreex %s, libigl %s, open3d %s, manifold3d %s; "
           "%s; parry3d / parry3d-f64 %s. wingedge and open3d took turns over %d rounds, each keeping "
           "its best. The run took %.1f min; 1-minute load average %.1f at its start, "
           "%.1f at its end."
           % (info["date"], info["cpu"], info["cores"], info["threads"], info["python"], pk["numpy"],
              pk["trimesh"], pk["embreex"], pk["libigl"], pk["open3d"], pk["manifold3d"], info["rustc"],
              info["parry3d"], settings["rounds"], info["minutes"], info["load"][0], info["load"][1]),
           "",
           "| mesh (triangles) | task | library (precision, threads) | setup s | throughput | ÷ wingedge "
           "| answers that differ from wingedge | exact arithmetic on those: who is wrong |",
           "|---|---|---|---:|---:|---:|---|---|"]
    out += _query_lines(record)
    out += _validation_lines(record)
    sets = _set_lines(record)
    if sets:
        out += ["",
                "The harder query sets, wingedge and open3d taking turns in the same run (%d rounds, each "
                "keeping its best):" % settings["rounds"],
                "",
                "| mesh (triangles) | queries | library (precision, threads) | setup s | throughput "
                "| ÷ wingedge | answers that differ from wingedge | exact arithmetic on those: who is wrong |",
                "|---|---|---|---:|---:|---:|---|---|"]
        out += sets
    out += ["",
            "Exact arbitration (rational arithmetic, independent of every library): per mesh and task, "
            "the disputed queries (up to %d) plus a control sample of unanimous ones." % settings["arbitrate"],
            "",
            "| mesh | task | disputed | settled exactly | wingedge wrong | control sample: libraries wrong | seconds |",
            "|---|---|---:|---:|---:|---|---:|"]
    for mesh, by_task in record["exact"].items():
        for task, v in by_task.items():
            control_wrong = ["%s %d" % (r["library"], r["control_wrong"]) for r in record["queries"]
                             if _key(r) == mesh and r["task"] == task and r["control_wrong"]]
            out.append("| %s | %s | %d | %d | %d | %d queries: %s | %.1f |" % (
                mesh, TASK_WORDS[task], v["disputed"], v["settled"], v["wingedge_wrong"], v["control"],
                ", ".join(control_wrong) or "none", v["seconds"]))
    disputes = _dispute_lines(record)
    if disputes:
        out += ["", "The disputed queries (first 10 per mesh and task), with the exact answer and every library's:", ""]
        out += disputes
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- the short table

def _fastest_peer(ours, group):
    peers = [r for r in group if r is not ours]
    if not peers:
        return "—"
    best = max(peers, key=lambda r: _rate(r)[0])
    return "%s %s" % (_short(best), _ratio(_rate(best)[0] / _rate(ours)[0]).strip("*"))


def _short(row):
    return row["library"].split()[0]


def _build_cell(ours, group):
    peers = [r for r in group if r is not ours]
    text = "%.3f s" % ours["setup_s"]
    if peers:
        best = min(peers, key=lambda r: r["setup_s"])
        text += " (%s %.3f s)" % (_short(best), best["setup_s"])
    return text


def _open3d_cell(ours, group):
    """wingedge's rate and how many times open3d's it is, or wingedge's rate alone."""
    open3d = [r for r in group if r["library"].startswith("open3d")]
    text = "%.3g" % _rate(ours)[0]
    if open3d:
        text += " **%.2f×**" % (_rate(ours)[0] / _rate(open3d[0])[0])
    return text


def render_goal_summary(record):
    """The README's short table when the run has the harder query sets:
    per mesh and query set, wingedge's rate and its ratio to open3d's."""
    info = record["machine"]
    cells = {}
    for _, task, ours, group in _query_groups(record, with_sets=True):
        cells[(ours["mesh"], task, ours.get("set"))] = _open3d_cell(ours, group)
        if not ours.get("set"):
            cells[(ours["mesh"], "build")] = "%.3f" % ours["setup_s"] + "".join(
                " (%.3f)" % r["setup_s"] for r in group if r["library"].startswith("open3d"))
    settled = sum(v["settled"] for by in record["exact"].values() for v in by.values())
    wrong = sum(v["wingedge_wrong"] for by in record["exact"].values() for v in by.values())
    out = ["Measured %s on %s (%d cores), %d threads, wingedge and open3d taking turns in one run. "
           "Each cell: wingedge's millions of queries per "
           "second and, in bold, that rate over open3d's. Of %s queries settled by exact rational "
           "arithmetic (disputed ones and a control sample), wingedge answered %d wrong."
           % (info["date"][:10], info["cpu"], info["cores"], info["threads"],
              format(settled, ","), wrong),
           "",
           "| mesh (triangles) | " + " | ".join(words for _, _, words in SUMMARY_COLUMNS)
           + " | build s (open3d) |",
           "|---|" + "---:|" * (len(SUMMARY_COLUMNS) + 1)]
    triangles = {}
    for r in record["queries"]:
        triangles.setdefault(r["mesh"], r["triangles"])
    for mesh, count in triangles.items():
        out.append("| %s (%s) | %s | %s |" % (
            mesh, format(count, ","),
            " | ".join(cells.get((mesh, task, query_set), "—") for task, query_set, _ in SUMMARY_COLUMNS),
            cells.get((mesh, "build"), "—")))
    return "\n".join(out) + "\n"


def render_summary(record):
    """The README's short table: per mesh, wingedge's rates and the fastest peer's, as a ratio.

    A run with the harder query sets gets `render_goal_summary` instead."""
    if any(r.get("set") for r in record["queries"]):
        return render_goal_summary(record)
    info = record["machine"]
    rows = {}
    for mesh, task, ours, group in _query_groups(record):
        entry = rows.setdefault(mesh, {"triangles": ours["triangles"], "setup": _build_cell(ours, group)})
        entry[task] = (_rate(ours)[1], _fastest_peer(ours, group))
    settled = sum(v["settled"] for by in record["exact"].values() for v in by.values())
    wrong = sum(v["wingedge_wrong"] for by in record["exact"].values() for v in by.values())
    disputed = sum(v["disputed"] for by in record["exact"].values() for v in by.values())
    out = ["Measured %s on %s (%d cores), %d threads for every library that can use them. "
           "A ratio is the peer's throughput divided by wingedge's (below 1: slower). "
           "Of %d queries settled by exact rational arithmetic (%d where some library disagreed with "
           "wingedge, the rest a control sample), wingedge answered %d wrong."
           % (info["date"], info["cpu"], info["cores"], info["threads"], settled, disputed, wrong),
           "",
           "| mesh (triangles) | points, wingedge | fastest peer on points | first-hit rays, wingedge "
           "| fastest peer on rays | accel build, wingedge (fastest peer) | import + validate, wingedge |",
           "|---|---:|---|---:|---|---:|---:|"]
    for mesh, entry in rows.items():
        validation = record["validation"].get(mesh, {}).get("wingedge")
        points, rays = entry.get("points", ("—", "—")), entry.get("rays", ("—", "—"))
        out.append("| %s (%s) | %s | %s | %s | %s | %s | %s |" % (
            mesh, format(entry["triangles"], ","), points[0], points[1], rays[0], rays[1], entry["setup"],
            "%.3g s" % validation["seconds"] if validation else "—"))
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- the writer

def replace_between(text, name, block):
    """`text` with the lines between `<!-- NAME:begin ... -->` and `<!-- NAME:end -->` replaced by `block`.

    The marker lines themselves are kept; a missing, repeated or misordered
    marker raises `MarkerError` naming it.
    """
    lines = text.splitlines(keepends=True)
    begin = [i for i, line in enumerate(lines) if line.startswith("<!-- %s:begin" % name)]
    end = [i for i, line in enumerate(lines) if line.startswith("<!-- %s:end" % name)]
    if len(begin) != 1 or len(end) != 1:
        raise MarkerError("expected one <!-- %s:begin --> and one <!-- %s:end --> line, found %d and %d"
                          % (name, name, len(begin), len(end)))
    if end[0] < begin[0]:
        raise MarkerError("<!-- %s:end --> comes before <!-- %s:begin -->" % (name, name))
    body = block if block.endswith("\n") else block + "\n"
    return "".join(lines[: begin[0] + 1]) + "\n" + body + "\n" + "".join(lines[end[0]:])


def write_docs(record, docs_page=DOCS_PAGE, readme=README):
    """Writes the full table into `docs_page` and the short one into `readme`, between their markers."""
    for path, name, block in ((docs_page, FULL_TABLE, render_table(record)),
                              (readme, SHORT_TABLE, render_summary(record))):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        try:
            updated = replace_between(text, name, block)
        except MarkerError as e:
            raise SystemExit("%s: %s" % (path, e))
        with open(path, "w", encoding="utf-8") as f:
            f.write(updated)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("record", help="a run's OUT/peers.json")
    ap.add_argument("--write-docs", action="store_true",
                    help="write the tables into docs/performance.md and README.md instead of printing")
    ap.add_argument("--docs-page", default=DOCS_PAGE, help="the page for the full table (default: %(default)s)")
    ap.add_argument("--readme", default=README, help="the page for the short table (default: %(default)s)")
    args = ap.parse_args(argv)
    with open(args.record, encoding="utf-8") as f:
        record = json.load(f)
    if args.write_docs:
        write_docs(record, args.docs_page, args.readme)
    else:
        sys.stdout.write(render_table(record))


if __name__ == "__main__":
    main()
