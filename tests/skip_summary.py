#!/usr/bin/env python3
"""How many tests CTest skipped and why, from the JUnit file of `ctest --output-junit FILE`.

GoogleTest prints a skip's reason on the line after "file:line: Skipped"; the tests that need
third-party data say "needs test data: PATH" (tests/test_data.h, tests/data/third_party_test.py).
Prints one line per reason with its count. Exits 1 when CI=true and a test was skipped for want
of data (there the data must be present), else 0.
Usage: skip_summary.py JUNIT.xml
"""
import collections
import os
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "data"))
import third_party  # noqa: E402  (the data folder, to name missing files relative to it)

DATA = "needs test data:"


def skip_reason(output):
    lines = output.splitlines()
    for i, line in enumerate(lines):
        if line.rstrip().endswith(": Skipped") and i + 1 < len(lines) and lines[i + 1].strip():
            return lines[i + 1].strip()
    for line in lines:
        if DATA in line:
            return line[line.index(DATA):].strip()
    return "no reason printed"


def main(argv):
    if len(argv) != 2:
        print(__doc__.rsplit("Usage: ", 1)[1].strip(), file=sys.stderr)
        return 2
    root = ET.parse(argv[1]).getroot()
    cases = root.iter("testcase")
    total, skipped = 0, collections.Counter()
    data_paths = collections.Counter()
    for case in cases:
        total += 1
        if case.find("skipped") is None and case.get("status") not in ("notrun", "disabled"):
            continue
        out = case.findtext("system-out") or ""
        reason = skip_reason(out)
        if reason.startswith(DATA):
            path = reason[len(DATA):].split(" (")[0].strip()
            root = third_party.data_dir().rstrip("/") + "/"
            data_paths[path[len(root):] if path.startswith(root) else path] += 1
            reason = DATA.rstrip(":") + " (set PTLAB_DATA or run ./lab data)"
        skipped[reason] += 1
    n = sum(skipped.values())
    print(f"lab: {n} of {total} tests skipped" + (":" if n else ""))
    for reason, count in skipped.most_common():
        print(f"  {count:4d}  {reason}")
        if reason.startswith(DATA.rstrip(":")):
            shown = [p for p, _ in data_paths.most_common(5)]
            more = len(data_paths) - len(shown)
            print("        missing: " + ", ".join(shown) + (f" and {more} more" if more > 0 else ""))
    data_skips = sum(c for r, c in skipped.items() if r.startswith(DATA.rstrip(":")))
    if data_skips and os.environ.get("CI") == "true":
        print(f"lab: CI=true and {data_skips} tests skipped for want of test data: failing the run")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
