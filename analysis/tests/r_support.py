"""Running an R script over a data file, for the tests that check the analysis against R."""
import shutil
import subprocess

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
