"""The peer comparison's Markdown table and JSON record."""
TASK_WORDS = {"points": "points", "rays": "first-hit rays", "validate": "import + validate"}


def _rate(row):
    rate = row["queries"] / row["seconds"] / 1e6
    text = "%.3g M/s" % rate if rate >= 0.01 else "%s /s" % format(round(rate * 1e6), ",")
    if row["queries"] < len(row["answers"]) or row["queries"] < 1_000_000:
        text += " (%s queries)" % format(row["queries"], ",")
    return rate, text


def _exact_cell(row, verdict):
    n = len(row["differs"])
    if row["library"] == "wingedge":
        return "%d of %d settled queries wrong" % (verdict["wingedge_wrong"], len(verdict["answers"]))
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


def _query_rows(rows, verdicts):
    lines = []
    for mesh in dict.fromkeys(r["mesh"] for r in rows):
        for task in ("points", "rays"):
            group = [r for r in rows if r["mesh"] == mesh and r["task"] == task]
            ours = next(r for r in group if r["library"] == "wingedge")
            our_rate, _ = _rate(ours)
            for r in group:
                rate, rate_text = _rate(r)
                differ = "%s of %s" % (format(len(r["differs"]), ","), format(len(r["answers"]), ","))
                if task == "rays" and r["library"] != "wingedge":
                    differ += "; elsewhere \\|Δt\\| ≤ %.1g" % r["max_t_gap"]
                lines.append("| %s (%s) | %s | %s | %.3f | %s | %s | %s | %s |" % (
                    mesh, format(r["triangles"], ","), TASK_WORDS[task], _label(r), r["setup_s"], rate_text,
                    "1" if r is ours else _ratio(rate / our_rate), differ,
                    _exact_cell(r, verdicts[mesh][task])))
    return lines


def _validation_rows(validations, triangles):
    lines = []
    for mesh, results in validations.items():
        ours = results["wingedge"]
        for library, v in results.items():
            tri_rate = triangles[mesh] / v["seconds"] / 1e6
            rate = "%.3g s (%.2f M tri/s), peak %.0f MiB" % (v["seconds"], tri_rate, v["rss_mib"] or float("nan"))
            if library == "wingedge":
                agree = "%s, genus %s, volume %.9g" % (v["verdict"], v["genus"], v["volume"] or float("nan"))
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


def markdown(rows, verdicts, validations, info, args):
    triangles = {r["mesh"]: r["triangles"] for r in rows}
    out = []
    pk = info["packages"]
    out.append("Measured %s on %s (%d cores), %d threads for every library that can use them; "
               "Python %s, numpy %s, trimesh %s with embreex %s, libigl %s, open3d %s, manifold3d %s; "
               "%s; parry3d / parry3d-f64 %s. wingedge and open3d took turns over %d rounds, each keeping "
               "its best. The run took %.1f min; 1-minute load average %.1f at its start, "
               "%.1f at its end."
               % (info["date"], info["cpu"], info["cores"], info["threads"], info["python"], pk["numpy"],
                  pk["trimesh"], pk["embreex"], pk["libigl"], pk["open3d"], pk["manifold3d"], info["rustc"],
                  info["parry3d"], args.rounds, info["minutes"], info["load"][0], info["load"][1]))
    out.append("")
    out.append("| mesh (triangles) | task | library (precision, threads) | setup s | throughput | ÷ wingedge "
               "| answers that differ from wingedge | exact arithmetic on those: who is wrong |")
    out.append("|---|---|---|---:|---:|---:|---|---|")
    out += _query_rows(rows, verdicts)
    out += _validation_rows(validations, triangles)
    out.append("")
    out.append("Exact arbitration (rational arithmetic, independent of every library): per mesh and task, "
               "the disputed queries (up to %d) plus a control sample of unanimous ones." % args.arbitrate)
    out.append("")
    out.append("| mesh | task | disputed | settled exactly | wingedge wrong | control sample: libraries wrong | seconds |")
    out.append("|---|---|---:|---:|---:|---|---:|")
    for mesh, by_task in verdicts.items():
        for task, v in by_task.items():
            control_wrong = ["%s %d" % (r["library"], r["control_wrong"]) for r in rows
                             if r["mesh"] == mesh and r["task"] == task and r["control_wrong"]]
            out.append("| %s | %s | %d | %d | %d | %d queries: %s | %.1f |" % (
                mesh, TASK_WORDS[task], v["disputed"], len(v["answers"]), v["wingedge_wrong"], len(v["control"]),
                ", ".join(control_wrong) or "none", v["seconds"]))
    disputes = [(mesh, task, i, v["answers"][i], said) for mesh, by_task in verdicts.items()
                for task, v in by_task.items() for i, said in list(v["said"].items())[:10]]
    if disputes:
        out.append("")
        out.append("The disputed queries (first 10 per mesh and task), with the exact answer and every library's:")
        out.append("")
        for mesh, task, i, truth, said in disputes:
            if task == "points":
                exact_text = truth
                words = ", ".join("%s %s" % (lib, a) for lib, a in said.items())
            else:
                exact_text = "miss" if truth[0] == float("inf") else "t = %.9g (%s)" % truth
                words = ", ".join("%s %s" % (lib, "miss" if a == float("inf") else "%.7g" % a)
                                  for lib, a in said.items())
            out.append("- %s %s #%d: exact %s; %s" % (mesh, "point" if task == "points" else "ray", i,
                                                      exact_text, words))
    return "\n".join(out) + "\n"


def as_json(rows, verdicts, validations, metas, info):
    def row(r):
        keep = {k: v for k, v in r.items() if k not in ("answers", "differs")}
        keep["differs"] = len(r["differs"])
        keep["first_differing"] = r["differs"][:20].tolist()
        return keep

    def verdict(v):
        return {"disputed": v["disputed"], "settled": len(v["answers"]), "wingedge_wrong": v["wingedge_wrong"],
                "said": {str(i): a for i, a in v["said"].items()},
                "seconds": v["seconds"],
                "answers": {str(i): (a if isinstance(a, str) else [a[0], a[1]]) for i, a in v["answers"].items()}}

    return {"machine": info, "inputs": metas, "queries": [row(r) for r in rows],
            "exact": {m: {t: verdict(v) for t, v in by.items()} for m, by in verdicts.items()},
            "validation": validations}
