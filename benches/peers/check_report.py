#!/usr/bin/env python3
"""A self-check of report.py's tables and writer, run by hand (not part of `cargo test`):

    python3 benches/peers/check_report.py

`testdata/peers.json` is the record of a published run (2 cores, five
meshes), rebuilt from its table; `testdata/peers.md` is that table as
run.py printed it. The check renders the record and compares it with the
table byte for byte, writes the tables into copies of `docs/performance.md`
and `README.md` and checks what changed, and runs `markdown` on a small
in-memory run the way run.py does. numpy is needed for the last part only.
"""
import copy
import json
import os
import shutil
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import report  # noqa: E402


def _load(name):
    with open(os.path.join(HERE, "testdata", name), encoding="utf-8") as f:
        return json.load(f) if name.endswith(".json") else f.read()


def _between(text, name):
    lines = text.splitlines(keepends=True)
    begin = next(i for i, line in enumerate(lines) if line.startswith("<!-- %s:begin" % name))
    end = next(i for i, line in enumerate(lines) if line.startswith("<!-- %s:end" % name))
    return "".join(lines[begin + 1:end]), "".join(lines[:begin + 1]) + "".join(lines[end:])


class Tables(unittest.TestCase):
    def test_the_record_renders_the_published_table(self):
        self.assertEqual(report.render_table(_load("peers.json")), _load("peers.md"))

    def test_the_summary_has_one_row_per_mesh_with_the_fastest_peer(self):
        summary = report.render_summary(_load("peers.json"))
        rows = [line for line in summary.splitlines() if line.startswith("| ") and not line.startswith("| mesh")]
        self.assertEqual([r.split("|")[1].split()[0] for r in rows],
                         ["sphere_80k", "torus_knot", "sphere_1m", "fandisk", "spot"])
        self.assertIn("| 18.8 M/s | open3d 0.43× | 11.9 M/s | open3d 0.84× | 0.020 s (open3d 0.027 s) | 0.127 s |",
                      rows[0])
        self.assertIn("Of 120 queries settled by exact rational arithmetic (20 where", summary)
        self.assertIn("wingedge answered 0 wrong", summary)

    def test_a_wrong_answer_is_counted_in_the_summary(self):
        record = _load("peers.json")
        record["exact"]["spot"]["rays"]["wingedge_wrong"] = 2
        self.assertIn("wingedge answered 2 wrong", report.render_summary(record))

    def test_a_record_without_settings_is_refused(self):
        record = _load("peers.json")
        del record["machine"]["settings"]
        with self.assertRaises(SystemExit):
            report.render_table(record)


class QuerySets(unittest.TestCase):
    """A record with a harder query set: its own table rows, and the README's table by query set."""

    def _record(self):
        record = _load("peers.json")
        base = next(r for r in record["queries"] if r["mesh"] == "spot" and r["library"] == "wingedge"
                    and r["task"] == "rays")
        ours = dict(base, set="grazing", seconds=0.5, setup_s=0.002, differs=0, first_differing=[])
        open3d = dict(base, library="open3d RaycastingScene", precision="f32", set="grazing", seconds=0.25,
                      setup_s=0.003, differs=3, first_differing=[1, 2, 3], checked=3, peer_wrong=1,
                      wingedge_wrong=2, control_wrong=0, max_t_gap=1e-5)
        record["queries"] += [ours, open3d]
        record["exact"]["spot@grazing"] = {"rays": {"disputed": 3, "settled": 13, "control": 10,
                                                    "wingedge_wrong": 2, "said": {}, "seconds": 0.1,
                                                    "answers": {}}}
        return record

    def test_the_set_has_rows_of_its_own_and_the_base_table_is_unchanged(self):
        table = report.render_table(self._record())
        self.assertTrue(table.startswith(report.render_table(_load("peers.json")).split("\n\nExact")[0]))
        self.assertIn("| spot (5,856) | rays grazing along faces | open3d RaycastingScene (f32, 2 thr) | 0.003 "
                      "| 4 M/s | **2.00×** | 3 of 1,000,000; elsewhere \\|Δt\\| ≤ 1e-05 "
                      "| wingedge 2, open3d 1 wrong |", table)
        self.assertIn("| spot@grazing | first-hit rays | 3 | 13 | 2 |", table)

    def test_the_summary_gives_each_set_a_column_with_the_ratio_to_open3d(self):
        summary = report.render_summary(self._record())
        self.assertIn("| mesh (triangles) | uniform points | points near, 1e-3 | points near, 1e-6 "
                      "| rays from outside | rays from inside | rays at vertices | grazing rays "
                      "| build s (open3d) |", summary)
        spot = next(line for line in summary.splitlines() if line.startswith("| spot "))
        cells = [c.strip() for c in spot.split("|")[1:-1]]
        self.assertEqual(cells[7], "2 **0.50×**")
        self.assertEqual(cells[2], "—")
        self.assertIn("wingedge answered 2 wrong", summary)


class Writer(unittest.TestCase):
    PAGE = "# Title\n\nprose\n\n<!-- peers:begin (generated) -->\nold table\n<!-- peers:end -->\n\nmore prose\n"

    def test_the_block_is_replaced_and_everything_else_kept(self):
        out = report.replace_between(self.PAGE, "peers", "new\ntable\n")
        self.assertEqual(out, "# Title\n\nprose\n\n<!-- peers:begin (generated) -->\n\nnew\ntable\n\n"
                              "<!-- peers:end -->\n\nmore prose\n")
        self.assertEqual(report.replace_between(out, "peers", "new\ntable\n"), out)

    def test_missing_repeated_or_reversed_markers_are_refused(self):
        for page in ("no markers\n",
                     self.PAGE + "<!-- peers:begin -->\n",
                     "<!-- peers:end -->\nx\n<!-- peers:begin -->\n"):
            with self.assertRaises(report.MarkerError):
                report.replace_between(page, "peers", "t\n")

    def test_write_docs_fills_both_pages(self):
        record = _load("peers.json")
        with tempfile.TemporaryDirectory() as tmp:
            page, readme = os.path.join(tmp, "performance.md"), os.path.join(tmp, "README.md")
            shutil.copy(report.DOCS_PAGE, page)
            shutil.copy(report.README, readme)
            before = {p: _between(open(p, encoding="utf-8").read(), n)[1]
                      for p, n in ((page, report.FULL_TABLE), (readme, report.SHORT_TABLE))}
            report.main([os.path.join(HERE, "testdata", "peers.json"), "--write-docs",
                         "--docs-page", page, "--readme", readme])
            table, rest = _between(open(page, encoding="utf-8").read(), report.FULL_TABLE)
            self.assertEqual(table.strip("\n"), report.render_table(record).strip("\n"))
            self.assertEqual(rest, before[page])
            summary, rest = _between(open(readme, encoding="utf-8").read(), report.SHORT_TABLE)
            self.assertEqual(summary.strip("\n"), report.render_summary(record).strip("\n"))
            self.assertEqual(rest, before[readme])


class RunPath(unittest.TestCase):
    """`markdown` and `as_json` on the in-memory rows run.py builds."""

    def test_markdown_renders_through_the_record_and_records_the_settings(self):
        import argparse
        import numpy as np
        answers = np.zeros(1_000_000, np.uint8)
        rows = [dict(library="wingedge", precision="f64, exact signs", threads=2, task="points", mesh="m",
                     triangles=12, setup_s=0.001, seconds=0.05, queries=1_000_000, answers=answers,
                     differs=np.array([], int), checked=0, peer_wrong=0, wingedge_wrong=0, control_wrong=0),
                dict(library="open3d RaycastingScene", precision="f32", threads=2, task="points", mesh="m",
                     triangles=12, setup_s=0.002, seconds=0.1, queries=1_000_000, answers=answers == 1,
                     differs=np.array([7]), checked=1, peer_wrong=1, wingedge_wrong=0, control_wrong=0)]
        verdicts = {"m": {"points": {"answers": {7: "inside", 9: "outside"}, "disputed": 1, "checked": 1,
                                     "control": [9], "wingedge_wrong": 0, "seconds": 0.01,
                                     "said": {7: {"wingedge": "inside", "open3d RaycastingScene": "outside"}}}}}
        info = {"date": "D", "cpu": "C", "cores": 2, "threads": 2, "python": "3", "rustc": "rustc 1",
                "parry3d": "0", "minutes": 1.0, "load": (0.5, 0.7),
                "packages": dict.fromkeys(("numpy", "trimesh", "embreex", "libigl", "open3d", "manifold3d"), "1")}
        args = argparse.Namespace(rounds=3, arbitrate=200)
        table = report.markdown(rows, verdicts, {}, info, args)
        self.assertEqual(info["settings"], {"rounds": 3, "arbitrate": 200})
        record = json.loads(json.dumps(report.as_json(rows, verdicts, {}, {}, copy.deepcopy(info))))
        self.assertEqual(report.render_table(record), table)
        self.assertIn("| m (12) | points | open3d RaycastingScene (f32, 2 thr) | 0.002 | 10 M/s | **0.50×** "
                      "| 1 of 1,000,000 | wingedge 0, open3d 1 wrong |", table)
        self.assertIn("| m | points | 1 | 2 | 0 | 1 queries: none | 0.0 |", table)
        self.assertIn("- m point #7: exact inside; wingedge inside, open3d RaycastingScene outside", table)


if __name__ == "__main__":
    unittest.main()
