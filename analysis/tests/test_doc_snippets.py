"""Every fenced code block tagged `r`, `python` or `sql` in README.md and docs/*.md runs, as an
analyst would paste it, against a small real study: bot sessions of both games (`warplab run`)
and their `warplab export`.

- `r`: Rscript, in a folder holding `export/` (the CSVs) and `results/` (the session files),
  the paths the docs use; a block fails when R stops with an error.
- `python`: /usr/bin/python3 in the same folder.
- `sql`: each statement through Python's sqlite3 against every session file, opened read-only.

A block the docs do not mean to run (a fragment, a template) is marked by an HTML comment on
the line before its fence, `<!-- not run: the reason -->`; a failure names the doc's file and
the line of the block's fence.
"""
import os
import re
import shutil
import sqlite3
import subprocess
import sys
from pathlib import Path

import pytest

from warplab_binary import binary, run

ROOT = Path(__file__).resolve().parents[2]
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
LANGUAGES = ("r", "python", "sql")
NOT_RUN = re.compile(r"<!--\s*not run:\s*\S.*-->\s*$")
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([\w+-]*)")
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable


class Block:
    def __init__(self, doc, line, language, code, marked):
        self.doc, self.line, self.language, self.code, self.marked = doc, line, language, code, marked

    @property
    def where(self):
        return f"{self.doc.relative_to(ROOT)}:{self.line}"


def blocks(doc):
    """The fenced blocks of one Markdown file, with the 1-based line of each opening fence."""
    lines = doc.read_text(encoding="utf-8").splitlines()
    found, i = [], 0
    while i < len(lines):
        opening = FENCE.match(lines[i])
        if not opening:
            i += 1
            continue
        fence, language = opening.group(2), opening.group(3).lower()
        start = i
        i += 1
        body = []
        while i < len(lines) and not lines[i].strip().startswith(fence):
            body.append(lines[i])
            i += 1
        marked = start > 0 and bool(NOT_RUN.search(lines[start - 1]))
        found.append(Block(doc, start + 1, language, "\n".join(body) + "\n", marked))
        i += 1
    return found


SNIPPETS = [b for doc in DOCS for b in blocks(doc) if b.language in LANGUAGES]


def test_the_docs_have_snippets_to_run():
    """The extraction finds the R snippet of docs/export.md and the SQL of docs/session-format.md."""
    where = {(b.doc.name, b.language) for b in SNIPPETS if not b.marked}
    assert ("export.md", "r") in where and ("session-format.md", "sql") in where, where


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    warplab = binary()
    base = tmp_path_factory.mktemp("docs")
    results = base / "results"
    results.mkdir()
    for seed, participant in enumerate(["P1", "P2", "P3"], start=1):
        for protocol in ("shooter-quick.json", "click-quick.json"):
            run(warplab, "run", "--headless", "--protocol", ROOT / "protocol" / protocol, "--participant",
                participant, "--out", results, "--player", f"bot:{seed}", "--seed", seed)
    run(warplab, "export", results, "--out", base / "export")
    return base


def run_r(block, folder):
    rscript = shutil.which("Rscript")
    if rscript is None:
        pytest.fail(f"{block.where}: Rscript is not on PATH, so the R block cannot be checked: run "
                    "scripts/install-deps.sh (it installs r-base-core).")
    script = folder / "snippet.R"
    script.write_text(block.code, encoding="utf-8")
    return subprocess.run([rscript, "--vanilla", str(script)], capture_output=True, text=True, timeout=120,
                          cwd=folder)


def run_python(block, folder):
    script = folder / "snippet.py"
    script.write_text(block.code, encoding="utf-8")
    return subprocess.run([PYTHON, str(script)], capture_output=True, text=True, timeout=120, cwd=folder)


def sql_statements(code):
    statements, pending = [], ""
    for line in code.splitlines(keepends=True):
        pending += line
        if sqlite3.complete_statement(pending):
            statements.append(pending.strip())
            pending = ""
    if pending.strip() and not all(l.strip().startswith("--") or not l.strip() for l in pending.splitlines()):
        statements.append(pending.strip())  # a last statement without its `;`: run, so it fails if bad
    return statements


def run_sql(block, folder):
    """Each statement runs on every session file, gives rows on at least one, and has no column
    that is NULL in all of them (a json_extract of a key the sessions do not store)."""
    sessions = sorted((folder / "results").glob("*.warplab-session"))
    assert sessions, "the study made no session file"
    databases = [sqlite3.connect(f"file:{session}?mode=ro&immutable=1", uri=True) for session in sessions]
    try:
        for statement in sql_statements(block.code):
            rows, columns = [], None
            for session, db in zip(sessions, databases):
                try:
                    cursor = db.execute(statement)
                    rows += cursor.fetchall()
                    columns = [d[0] for d in cursor.description or []]
                except sqlite3.Error as e:
                    pytest.fail(f"{block.where}: the sql block fails on {session.name}: {e}\n{statement}")
            if columns:
                assert rows, f"{block.where}: the sql block gives no row on any session file:\n{statement}"
                empty = [c for i, c in enumerate(columns) if all(row[i] is None for row in rows)]
                assert not empty, (f"{block.where}: the sql block's column(s) {', '.join(empty)} are NULL on "
                                   f"every session file:\n{statement}")
    finally:
        for db in databases:
            db.close()


@pytest.mark.parametrize("block", [b for b in SNIPPETS if not b.marked], ids=lambda b: b.where)
def test_doc_snippet_runs(block, study):
    if block.language == "sql":
        run_sql(block, study)
        return
    done = (run_r if block.language == "r" else run_python)(block, study)
    assert done.returncode == 0, (f"{block.where}: the {block.language} block fails (exit {done.returncode}):\n"
                                  f"{done.stderr[-3000:]}")
