"""Running an R script over a data file, for the tests that check the analysis against R."""
import shutil
import subprocess
from pathlib import Path

import pytest


def run_r(script_text, data_text, tmp_path, package, install):
    """Rscript --vanilla SCRIPT DATA; its standard output's lines. Fails the test, saying how to
    install them, when R or `package` is missing, and on any other error of R's."""
    rscript = shutil.which("Rscript")
    if rscript is None:
        pytest.fail(f"Rscript is not on PATH: {install}.")
    script, data = tmp_path / "check.R", tmp_path / "data.txt"
    script.write_text(script_text)
    data.write_text(data_text)
    done = subprocess.run([rscript, "--vanilla", str(script), str(data)], capture_output=True, text=True,
                          timeout=300)
    if package in done.stderr and done.returncode != 0:
        pytest.fail(f"R lacks the package {package}: {install}.")
    assert done.returncode == 0, f"Rscript failed: {done.stderr}"
    return done.stdout.splitlines()


def installed_by_deps():
    """The Debian packages scripts/install-deps.sh installs: the project's test command runs it
    first, so what a test needs from R must be in that list."""
    script = (Path(__file__).resolve().parents[2] / "scripts" / "install-deps.sh").read_text()
    block = script.split("packages=(", 1)[1].split("\n)", 1)[0]
    return {word for line in block.splitlines() for word in line.split("#", 1)[0].split()}
