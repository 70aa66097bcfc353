#!/usr/bin/env python3
"""The download path of `./lab data` (tests/data/third_party.py) against a local mirror.

A temporary folder laid out like the upstream URLs ({repo}/{commit}/{path}) is built from the
local data (links to its files) and served by Python's http.server on 127.0.0.1. One file of
the mirror is corrupted (a byte flipped): the fetch must refuse it by its SHA-256, keep every
other file, and succeed once the mirror serves the right bytes; the EXR conversions, which no
repository holds, are made from their downloaded sources and must match the manifest too.
Exits 77 (CTest: skipped) when the local data is absent, or fails under CI=true, where the data
must be present.
"""
import functools
import http.server
import os
import shutil
import subprocess
import sys
import tempfile
import threading

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import third_party  # noqa: E402

SCRIPT = os.path.join(HERE, "third_party.py")


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def run_fetch(env):
    return subprocess.run([sys.executable, SCRIPT, "fetch"], env=env, capture_output=True,
                          text=True, timeout=600)


def main():
    source = third_party.data_dir()
    rows = third_party.read_manifest()
    if not all(os.path.isfile(os.path.join(source, r["path"])) for r in rows):
        print(f"needs test data: {source} (set PTLAB_DATA or run ./lab data)")
        return 1 if os.environ.get("CI") == "true" else 77
    failures = []

    def expect(condition, what):
        if not condition:
            failures.append(what)

    with tempfile.TemporaryDirectory(prefix="ptlab_data_mirror_") as tmp:
        mirror, dest = os.path.join(tmp, "mirror"), os.path.join(tmp, "data")
        corrupted = next(r for r in rows if r["path"].endswith("cbox_mis.xml"))
        for r in rows:
            src = os.path.join(source, r["path"])
            if r["repo"] == "derived":
                continue  # made from its downloaded source by the fetch
            url_path = os.path.join(mirror, r["repo"], r["commit"], r["in_repo"])
            os.makedirs(os.path.dirname(url_path), exist_ok=True)
            if os.path.lexists(url_path):
                continue  # the same upstream file under two local paths
            if r is corrupted:
                data = bytearray(open(src, "rb").read())
                data[len(data) // 2] ^= 0x20
                open(url_path, "wb").write(data)
            else:
                os.symlink(src, url_path)

        handler = functools.partial(QuietHandler, directory=mirror)
        server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        threading.Thread(target=server.serve_forever, daemon=True).start()
        try:
            env = dict(os.environ, PTLAB_DATA=dest,
                       PTLAB_DATA_URL=f"http://127.0.0.1:{server.server_port}/{{repo}}/{{commit}}/{{path}}")
            dir_out = subprocess.run([sys.executable, SCRIPT, "dir"], env=env,
                                     capture_output=True, text=True).stdout.strip()
            expect(dir_out == dest, f"`dir` printed {dir_out!r}, expected {dest!r}")

            first = run_fetch(env)
            expect(first.returncode == 1, f"first fetch exited {first.returncode}, expected 1")
            bad = [l for l in first.stderr.splitlines() if corrupted["path"] in l]
            expect(len(bad) == 1 and "sha256" in bad[0] and corrupted["sha256"] in bad[0],
                   f"the corrupted file's sha256 mismatch is not reported: {first.stderr!r}")
            expect(not os.path.exists(os.path.join(dest, corrupted["path"])),
                   "the corrupted download was kept")
            expect(not any(n.startswith(".download-") for _, _, fs in os.walk(dest) for n in fs),
                   "a temporary download file was left behind")
            kept = [r for r in rows if r is not corrupted]
            expect(all(third_party.check(os.path.join(dest, r["path"]), r) is None for r in kept),
                   "a file other than the corrupted one is missing or wrong after the fetch")
            expect(f"{len(rows) - 1} of {len(rows)}" not in first.stdout and
                   "1 missing or wrong" in first.stdout, f"summary: {first.stdout!r}")

            # The mirror now serves the right bytes: only that file is downloaded, and it checks.
            url_path = os.path.join(mirror, corrupted["repo"], corrupted["commit"],
                                    corrupted["in_repo"])
            shutil.copyfile(os.path.join(source, corrupted["path"]), url_path)
            second = run_fetch(env)
            expect(second.returncode == 0, f"second fetch exited {second.returncode}: "
                                           f"{second.stderr!r}")
            expect(f"{len(rows) - 1} of {len(rows)} files present and checked, 1 downloaded"
                   in second.stdout, f"summary: {second.stdout!r}")

            # A derived file that is wrong is made again from its source, and checks.
            derived = next(r for r in rows if r["repo"] == "derived")
            with open(os.path.join(dest, derived["path"]), "r+b") as f:
                f.seek(derived["bytes"] // 2)
                f.write(b"\0\0\0\0")
            third = run_fetch(env)
            expect(third.returncode == 0 and "1 downloaded or made" in third.stdout and
                   third_party.check(os.path.join(dest, derived["path"]), derived) is None,
                   f"third fetch: {third.returncode} {third.stdout!r} {third.stderr!r}")
        finally:
            server.shutdown()
            server.server_close()

    for f in failures:
        print("FAILED:", f)
    if not failures:
        print(f"third_party fetch: {len(rows)} files through a local mirror, the corrupted one "
              "refused by its sha256, the EXR conversions made and checked")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
