#!/usr/bin/env python3
"""tools/chi2/power_table.py on a real `chi2 --power` run of two subjects (one real, one broken):
the table has both rows, the real one's power figures as chi2 printed them, the summary counts;
a truncated run (no final line) and a run without --power are refused (exit 1).

Usage: power_table_test.py CHI2_BINARY
"""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "..", "tools", "chi2", "power_table.py")


def run_table(log_text):
    with tempfile.NamedTemporaryFile("w", suffix=".log", delete=False) as f:
        f.write(log_text)
        path = f.name
    try:
        return subprocess.run([sys.executable, SCRIPT, path, "--date", "2026-12-07"],
                              capture_output=True, text=True)
    finally:
        os.unlink(path)


def main():
    chi2 = sys.argv[1]
    names = ["warp/tent", "broken/tent_pdf_scaled"]
    run = subprocess.run([chi2, *names, "--power", "--samples", "100000"], capture_output=True,
                         text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    power_line = next(l for l in run.stdout.splitlines() if "power: detects a" in l)
    eps = power_line.split("detects a ")[1].split(" %")[0]
    tent_line = next(l for l in run.stdout.splitlines() if l.startswith("PASS   warp/tent "))
    p_fine = tent_line.split(" p=")[1].split()[0]
    p_coarse = tent_line.split("coarse 6x6: ")[1].split(" p=")[1].split()[0]

    table = run_table(run.stdout)
    assert table.returncode == 0, table.stderr
    rows = [l for l in table.stdout.splitlines() if l.startswith("| `")]
    assert len(rows) == 2, table.stdout
    assert rows[0].startswith(f"| `warp/tent` | PASS | {p_fine} | {p_coarse} |") and f"| {float(eps):g} % |" in rows[0], rows[0]
    assert rows[1].startswith("| `broken/tent_pdf_scaled` | XFAIL |") and "— | — | — | —" in rows[1]
    summary = table.stdout.splitlines()[-1]
    assert summary.startswith(f"Real subjects: 1, ε₉₅ from {float(eps):g} % to {float(eps):g} %"), summary
    assert "Broken: 1, all rejected: yes" in summary and "2 as expected, 0 not (PASS)" in summary

    truncated = run_table("\n".join(run.stdout.splitlines()[:-1]))
    assert truncated.returncode == 1 and "not a complete" in truncated.stderr, truncated.stderr
    no_power = "\n".join(l for l in run.stdout.splitlines() if "power:" not in l)
    refused = run_table(no_power)
    assert refused.returncode == 1 and "no power line" in refused.stderr, refused.stderr
    print("power_table: OK")


if __name__ == "__main__":
    main()
