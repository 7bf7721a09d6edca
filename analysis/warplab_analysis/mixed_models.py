"""The trial-level mixed models, fitted by R: analysis/r/mixed_models.R (with models.R) is the
engine, and this module only writes the copy of it that a report keeps, runs it with Rscript, and
reads back the JSON it writes.

The copy (REPORT_DIR/mixed_models.R) is the very script that runs: the repository's file with
models.R inlined and its settings block replaced by the values this report used (the export's
path, the condition order, each game's reference condition, the participants analysed), so
`Rscript mixed_models.R` re-run by a reviewer prints the same estimates and writes the same
mixed_models.json and mixed_models.rds. Without R, or without one of its packages, the section
is one sentence saying what to install, and the rest of the report is made as before.
"""
import json
import os
import re
import shutil
import subprocess

R_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "r")
SCRIPT = "mixed_models.R"
HELPERS = "models.R"
RESULTS = "mixed_models.json"
MODELS = "mixed_models.rds"
SETTINGS_START = "# >>> settings"
SETTINGS_END = "# <<< settings"
# mixed_models.R's line that reads models.R, which the copy replaces with models.R itself.
SOURCE_HELPERS = ('source(file.path(dirname(script_path()), "models.R"))  # analyze\'s copy has models.R here, '
                  'inline')
# mixed_models.R's exit status when R lacks a package (it names them and their Debian packages).
MISSING_PACKAGE = 3
INSTALL = "apt-get install r-base-core r-cran-lme4 r-cran-emmeans r-cran-ordinal r-cran-jsonlite"
# The files whose rows the models fit: without any of them there is nothing to run R for.
MODELLED_FILES = ("shots.csv", "matches.csv", "answers.csv")
# Long enough for a large study's maximal models (minutes), short of hanging a report for ever.
TIMEOUT_S = 3600


def r_string(text):
    """An R string literal of any text: escapes for quotes, backslashes, control and non-ASCII
    characters, so the script reads the same in any locale."""
    out = []
    for ch in text:
        code = ord(ch)
        if ch in '"\\':
            out.append("\\" + ch)
        elif 32 <= code < 127:
            out.append(ch)
        elif code < 0x10000:
            out.append(f"\\u{{{code:04x}}}")
        else:
            out.append(f"\\U{{{code:08x}}}")
    return '"' + "".join(out) + '"'


def r_value(value):
    """None, a string, a list of strings or a dict of strings as R code."""
    if value is None:
        return "NULL"
    if isinstance(value, str):
        return r_string(value)
    if isinstance(value, dict):
        return "list(" + ", ".join(f"{r_string(k)} = {r_value(v)}" for k, v in value.items()) + ")"
    if not value:
        return "character(0)"
    return "c(" + ", ".join(r_string(v) for v in value) + ")"


def settings(results):
    """What the report analysed, as mixed_models.R's SETTINGS: the export (absolute, so the copy
    runs from anywhere), the condition order, the reference of the game whose matches have one
    (analyze.choose_reference), and the participants of the group analysed first."""
    matches = results.get("matches")
    matches_game = None
    reference = {}
    if matches is not None:
        matches_game = matches["game"] or "matches"
        if matches["reference_condition"]:
            reference[matches_game] = matches["reference_condition"]
    who = results["players"]
    group = who["analysed"]
    return {"export_dir": os.path.abspath(results["export_dir"]), "condition_order": results["condition_order"],
            "reference": reference, "participants": None if group is None else who["groups"][group],
            "matches_game": matches_game}


def script_text(values):
    """The repository's mixed_models.R with models.R inlined and the settings block holding `values`."""
    with open(os.path.join(R_DIR, SCRIPT), encoding="utf-8") as f:
        text = f.read()
    with open(os.path.join(R_DIR, HELPERS), encoding="utf-8") as f:
        helpers = f.read()
    before, rest = text.split(SETTINGS_START, 1)
    template, after = rest.split(SETTINGS_END, 1)
    # Each setting keeps the comment the repository's script gives it.
    comments = dict(re.findall(r"^\s*(\w+) = .*?(#.*)$", template, flags=re.M))
    lines = [f"  {key} = {r_value(value)}" + ("," if k < len(values) - 1 else "")
             for k, (key, value) in enumerate(values.items())]
    width = max(len(line) for line in lines) + 2
    block = [f"{SETTINGS_START}: the values analyze used for this report (edit to re-run otherwise)",
             "SETTINGS <- list("]
    block += [f"{line:<{width}}{comments[key]}" if key in comments else line for line, key in zip(lines, values)]
    block.append(")")
    text = before + "\n".join(block) + "\n" + SETTINGS_END + after
    inline = f"# ---- models.R, inlined by analyze ----\n{helpers}# ---- end of models.R ----"
    assert SOURCE_HELPERS in text, "mixed_models.R no longer sources models.R as mixed_models.py expects"
    return text.replace(SOURCE_HELPERS, inline)


def left_out(sentence, script=None):
    return {"left_out": sentence, "script": script, "results": None, "models_file": None, "models": [],
            "notes": [], "figures": {}}


def fit(results, out_dir, rscript="Rscript"):
    """Writes REPORT_DIR/mixed_models.R, runs it and returns report.json's `mixed_models`: R's
    results (mixed_models.json) with the file names, or, where R could not run them, a section
    whose `left_out` says why in one sentence."""
    values = settings(results)
    for name in (RESULTS, MODELS):  # never leave an earlier run's results beside this report
        if os.path.exists(os.path.join(out_dir, name)):
            os.remove(os.path.join(out_dir, name))
    script = os.path.join(out_dir, SCRIPT)
    with open(script, "w", encoding="utf-8") as f:
        f.write(script_text(values))
    export_dir = results["export_dir"]
    if not any(os.path.isfile(os.path.join(export_dir, name)) for name in MODELLED_FILES):
        return left_out(f"Nothing to model: the export has none of {', '.join(MODELLED_FILES)}.", SCRIPT)
    program = shutil.which(rscript)
    if program is None:
        return left_out(f"Left out: R's Rscript ({rscript}) was not found; install R and its packages with "
                        f"`{INSTALL}`, then re-run the report or `Rscript {SCRIPT}` beside it.", SCRIPT)
    try:
        done = subprocess.run([program, "--vanilla", script], capture_output=True, text=True, timeout=TIMEOUT_S,
                              env=dict(os.environ, LC_ALL="C.UTF-8"))
    except subprocess.TimeoutExpired:
        return left_out(f"Left out: R took longer than {TIMEOUT_S} s; run `Rscript {SCRIPT}` beside this report "
                        "to fit the models without a limit.", SCRIPT)
    except OSError as e:
        return left_out(f"Left out: {rscript} could not be run ({e.strerror or e}); install R and its packages with "
                        f"`{INSTALL}`.", SCRIPT)
    last = (done.stderr.strip().splitlines() or [""])[-1].removeprefix("mixed_models.R: ")
    if done.returncode == MISSING_PACKAGE:
        return left_out(f"Left out: {last} (Debian's packages), then re-run the report or `Rscript {SCRIPT}` "
                        "beside it.", SCRIPT)
    if done.returncode != 0 or not os.path.exists(os.path.join(out_dir, RESULTS)):
        return left_out(f"Left out: R stopped (exit status {done.returncode}): {last or 'no message'}", SCRIPT)
    with open(os.path.join(out_dir, RESULTS), encoding="utf-8") as f:
        section = json.load(f)
    section.update(left_out=None, script=SCRIPT, results=RESULTS, models_file=MODELS, figures={},
                   settings=values)
    return section
