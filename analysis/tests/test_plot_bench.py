"""analysis/plot_bench.py run as the bench runs it: a subprocess on a CSV, checked by its exit
status, its stderr and the PNG it writes."""
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[1] / "plot_bench.py"
HEADER = ("sequence,method,frame,time_s,psnr_db,ssim,disocc_mae,corr_all_lt_0p1,corr_all_lt_0p5,corr_all_lt_1,"
          "corr_hit_lt_0p1,corr_hit_lt_0p5,corr_hit_lt_1,pass_ms,gpu_ms,conventional_ms")
ROWS = [
    # inf PSNR (identical frame), empty not-applicable fields, a method without PSNR.
    "pan,hold,0,0.0,inf,1,,,,,,,,0.05,,2.1",
    "pan,hold,1,0.0167,24.5,0.8,,,,,,,,0.06,,2.0",
    "pan,warp-full,0,0.0,31.2,0.95,3.5,0.9,0.97,0.98,0.94,0.99,0.995,0.9,0.8,2.2",
    "pan,warp-full,1,0.0167,30.1,0.94,4.0,0.88,0.96,0.98,0.93,0.99,0.995,1.1,0.9,1.9",
    "target,warp-full,0,0.0,33.0,0.97,2.0,0.95,0.99,1,0.97,1,1,0.95,0.85,2.05",
    "target,bidir-m2,0,0.0,34.0,0.97,,0.96,0.99,1,0.98,1,1,1.4,1.2,2.0",
    "target,conventional-15,0,0.0,,,,,,,,,,,,2.0",
]


def run(*args):
    return subprocess.run(["/usr/bin/python3", str(SCRIPT), *map(str, args)], capture_output=True, text=True,
                          timeout=120)


def write_csv(path, header=HEADER, rows=ROWS):
    path.write_text("\n".join([header, *rows]) + "\n")
    return path


def test_writes_a_png(tmp_path):
    out = tmp_path / "speed_vs_error.png"
    result = run(write_csv(tmp_path / "bench.csv"), out, "--title", "llvmpipe, 96x54")
    assert result.returncode == 0, result.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert out.stat().st_size > 10_000  # a real figure, not an empty canvas


def test_missing_column_is_named_and_exits_1(tmp_path):
    header = HEADER.replace(",pass_ms,", ",")
    rows = [",".join(r.split(",")[:13] + r.split(",")[14:]) for r in ROWS]
    out = tmp_path / "out.png"
    result = run(write_csv(tmp_path / "bench.csv", header, rows), out)
    assert result.returncode == 1
    assert "pass_ms" in result.stderr and "bench.csv" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
    assert not out.exists()


def test_missing_file_is_named_and_exits_1(tmp_path):
    result = run(tmp_path / "nowhere.csv", tmp_path / "out.png")
    assert result.returncode == 1
    assert "nowhere.csv" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_non_numeric_field_is_named_and_exits_1(tmp_path):
    rows = list(ROWS)
    rows[1] = rows[1].replace("24.5", "fast")
    result = run(write_csv(tmp_path / "bench.csv", rows=rows), tmp_path / "out.png")
    assert result.returncode == 1
    assert "psnr_db" in result.stderr and "line 3" in result.stderr


if __name__ == "__main__":
    sys.exit(subprocess.call(["/usr/bin/python3", "-m", "pytest", "-q", __file__]))
