#!/usr/bin/env python3
"""Turns the output of `chi2 --all --power` into docs/chi2-power-table.md (markdown, stdout).

    build/bin/chi2 --all --power > /tmp/power.log
    python3 tools/chi2/power_table.py /tmp/power.log --date 2026-12-07 > docs/chi2-power-table.md

Reads the run's header, each subject's verdict line (fine and coarse p) and power line (epsilon_95
per shape, P(2 %), samples for 95 % at 2 %), and the run's last line. Exits 1 when the output is
not a complete run (a subject without its power line, no final line).
"""
import argparse
import re
import sys

HEADER = re.compile(r"^chi2: (\d+) tests, (\d+) samples, res (\d+), seed (\d+), alpha (\S+) "
                    r"\(alpha' = (\S+) per test\)")
VERDICT = re.compile(r"^(PASS|FAIL|XFAIL|XPASS)\s+(\S+)\s+chi2=\S+\s+dof=\S+\s+p=(\S+)\s")
COARSE = re.compile(r"coarse \d+x\d+: chi2=\S+ dof=\S+ p=(\S+)")
POWER = re.compile(r"^\s+power: detects a (\S+) % error with 95 % probability \(worst of:(.*)\); "
                   r"a 2 % error with probability (\S+); (\S+) samples for 95 %")
SHAPE = re.compile(r"(\S+) (\S+) %")
FINAL = re.compile(r"^chi2: (\d+) as expected, (\d+) not: (PASS|FAIL)")


def parse(lines):
    header, final, rows = None, None, []
    for line in lines:
        if m := HEADER.match(line):
            header = m.groups()
        elif m := VERDICT.match(line):
            verdict, name, p_fine = m.groups()
            coarse = COARSE.search(line)
            p_coarse = coarse.group(1) if coarse else None
            rows.append({"verdict": verdict, "name": name, "p_fine": p_fine,
                         "p_coarse": p_coarse or "—", "power": None})
        elif m := POWER.match(line):
            if not rows:
                sys.exit("power_table: a power line before any subject")
            eps, shapes, p2, n95 = m.groups()
            shape_text = " ".join(f"{s} {e}" for s, e in SHAPE.findall(shapes))
            rows[-1]["power"] = (float(eps), shape_text, float(p2), n95)
        elif m := FINAL.match(line):
            final = m.groups()
    if header is None or final is None:
        sys.exit("power_table: not a complete `chi2 --power` run (no header or no final line)")
    if int(header[0]) != len(rows):
        sys.exit(f"power_table: the header says {header[0]} tests, the output has {len(rows)}")
    for r in rows:
        real = r["verdict"] in ("PASS", "FAIL")
        if real and r["power"] is None:
            sys.exit(f"power_table: {r['name']} has no power line (run with --power)")
    return header, final, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("log", help="the output of `chi2 --all --power`")
    ap.add_argument("--date", required=True, help="the run's date (YYYY-MM-DD)")
    ap.add_argument("--command", default="build/bin/chi2 --all --power",
                    help="the command that produced the log")
    ap.add_argument("--note", default="", help="a sentence about the run (branch, wall time)")
    args = ap.parse_args()
    with open(args.log, encoding="utf-8") as f:
        header, final, rows = parse(f.read().splitlines())
    tests, samples, res, seed, alpha, alpha1 = header
    out = ["# Per-subject power of the chi² lab", ""]
    out.append(f"`{args.command}` ({args.date}; {tests} tests, {samples} samples, res {res}, "
               f"seed {seed}, alpha {alpha} (alpha' = {alpha1} per test)){args.note}. "
               "This page: `build/bin/chi2 --all --power > LOG; "
               "python3 tools/chi2/power_table.py LOG --date DATE > docs/chi2-power-table.md`.")
    out.append(f"Samples: {samples} × the subject's `sample_scale`, set in "
               "`tools/chi2/*_subjects.cpp` where the power at the default count was low "
               "(the run's output does not print it).")
    out.append("ε₉₅: the smallest smooth error detected with 95 % probability (worst shape; each "
               "shape in the next column);")
    out.append("P(2 %): the probability of detecting a 2 % error; N₉₅(2 %): the samples at which "
               "that probability is 95 %.")
    out.append("Broken subjects have no power line: their verdict is the point (XFAIL = rejected "
               "as required).")
    out.append("")
    out.append("| subject | verdict | p fine | p coarse | ε₉₅ | per shape | P(2 %) | N₉₅(2 %) |")
    out.append("|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r["power"] is None:
            tail = "— | — | — | —"
        else:
            eps, shapes, p2, n95 = r["power"]
            tail = f"{eps:g} % | {shapes} | {p2:.4f} | {n95}"
        out.append(f"| `{r['name']}` | {r['verdict']} | {r['p_fine']} | {r['p_coarse']} | {tail} |")
    real = [r for r in rows if r["verdict"] in ("PASS", "FAIL")]
    broken = [r for r in rows if r["verdict"] in ("XFAIL", "XPASS")]
    eps = [r["power"][0] for r in real]
    worst = max(real, key=lambda r: r["power"][0])
    weakest = min(real, key=lambda r: r["power"][2])
    above = [r["name"] for r in real if r["power"][0] > 2.0]
    failed = [r["name"] for r in real if r["verdict"] == "FAIL"]
    out.append("")
    out.append(f"Real subjects: {len(real)}, ε₉₅ from {min(eps):g} % to {max(eps):g} % (the "
               f"largest: `{worst['name']}`); P(2 %) ≥ {weakest['power'][2]:.4f} for every one "
               f"(the lowest: `{weakest['name']}`). Above 2 %: "
               f"{', '.join(f'`{n}`' for n in above) if above else 'none'}. "
               f"Failed: {', '.join(f'`{n}`' for n in failed) if failed else 'none'}. "
               f"Broken: {len(broken)}, all rejected: "
               f"{'yes' if all(r['verdict'] == 'XFAIL' for r in broken) else 'NO'}. "
               f"The run: {final[0]} as expected, {final[1]} not ({final[2]}).")
    print("\n".join(out))


if __name__ == "__main__":
    main()
