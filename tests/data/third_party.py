#!/usr/bin/env python3
"""Finds or downloads the third-party test data listed in tests/data/third_party.tsv.

The data (Nori, CS184, Poly Haven, Mitsuba 3 scenes and references) is never in this
repository. It is looked for where the tests look (tests/test_data.h): $PTLAB_DATA when set,
else ../shared/data beside the checkout. A file that is absent there, or whose size or SHA-256
differs from the manifest, is downloaded from its repository at the pinned commit through
PTLAB_DATA_URL, a template with {repo}, {commit} and {path} (default: GitHub's raw files), and
kept only when its size and SHA-256 match. Rows of repository `derived` (the EXR conversions
of the environment maps) are made again from their source file (envmap_exr.py) and checked the
same way.

Usage: third_party.py dir            print the data folder
       third_party.py fetch [-n]     find, check and download what is missing (-n: only report)
Exit status: 0 every file present and checked, 1 some file missing or wrong, 2 usage error.
"""
import hashlib
import os
import sys
import tempfile
import urllib.error
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(os.path.dirname(HERE))
MANIFEST = os.path.join(HERE, "third_party.tsv")
DEFAULT_URL = "https://raw.githubusercontent.com/{repo}/{commit}/{path}"
MAX_LISTED = 20  # files named in the report; the rest are counted
MAX_UNREACHABLE = 3  # downloads in a row that could not connect before the rest are not tried


def data_dir():
    env = os.environ.get("PTLAB_DATA", "")
    if env:
        return os.path.abspath(env)
    return os.path.normpath(os.path.join(SOURCE_DIR, "..", "shared", "data"))


def read_manifest():
    rows = []
    with open(MANIFEST, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line or line.startswith("#") or line.startswith("path\t"):
                continue
            cols = line.split("\t")
            if len(cols) != 6:
                sys.exit(f"{MANIFEST}:{number}: expected 6 tab-separated columns, got {len(cols)}")
            path, repo, commit, in_repo, size, sha = cols
            rows.append({"path": path, "repo": repo, "commit": commit, "in_repo": in_repo,
                         "bytes": int(size), "sha256": sha})
    return rows


def sha256_of(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def check(path, row):
    """None when `path` holds the manifest's bytes, else what is wrong."""
    if not os.path.isfile(path):
        return "absent"
    size = os.path.getsize(path)
    if size != row["bytes"]:
        return f"{size} bytes, expected {row['bytes']}"
    sha = sha256_of(path)
    if sha != row["sha256"]:
        return f"sha256 {sha}, expected {row['sha256']}"
    return None


class Unreachable(Exception):
    """The download's host could not be reached (not an answer such as 404)."""


def download(row, dest):
    """Downloads `row` into `dest` (atomically); returns None or what went wrong."""
    template = os.environ.get("PTLAB_DATA_URL", DEFAULT_URL)
    url = template.format(repo=row["repo"], commit=row["commit"], path=row["in_repo"])
    os.makedirs(os.path.dirname(dest), exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(dest), prefix=".download-")
    try:
        with os.fdopen(fd, "wb") as out, urllib.request.urlopen(url, timeout=30) as response:
            while True:
                block = response.read(1 << 20)
                if not block:
                    break
                out.write(block)
        wrong = check(tmp, row)
        if wrong:
            return f"{url}: {wrong}"
        os.replace(tmp, dest)
        tmp = None
        return None
    except urllib.error.HTTPError as e:
        return f"{url}: {e}"
    except (urllib.error.URLError, OSError, ValueError) as e:
        raise Unreachable(f"{url}: {e}") from e
    finally:
        if tmp and os.path.exists(tmp):
            os.remove(tmp)


def derive(row, root, dest):
    """Makes `row` from its source file (row["in_repo"], a checked file of the data folder) into
    `dest` (atomically); returns None or what went wrong."""
    import envmap_exr  # beside this file
    source = os.path.join(root, row["in_repo"])
    try:
        data = envmap_exr.hdr_to_exr(open(source, "rb").read(), os.path.basename(source))
    except (OSError, ValueError, IndexError) as e:
        return f"conversion of {row['in_repo']} failed: {e}"
    sha = hashlib.sha256(data).hexdigest()
    if len(data) != row["bytes"] or sha != row["sha256"]:
        return f"conversion of {row['in_repo']}: sha256 {sha}, expected {row['sha256']}"
    os.makedirs(os.path.dirname(dest), exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(dest), prefix=".derive-")
    with os.fdopen(fd, "wb") as out:
        out.write(data)
    os.replace(tmp, dest)
    return None


def fetch(report_only):
    root = data_dir()
    rows = read_manifest()
    present, fetched, failed, unreachable = 0, 0, [], 0
    bad = set()  # paths still missing or wrong, which derived rows cannot be made from
    # Downloads first, then the rows made from them.
    for row in sorted(rows, key=lambda r: r["repo"] == "derived"):
        dest = os.path.join(root, row["path"])
        wrong = check(dest, row)
        if wrong is None:
            present += 1
            continue
        bad.add(row["path"])
        if report_only:
            failed.append(f"{row['path']}: {wrong}")
            continue
        if row["repo"] == "derived":
            if row["in_repo"] in bad:
                failed.append(f"{row['path']}: {wrong}; its source {row['in_repo']} is missing")
                continue
            error = derive(row, root, dest)
            if error:
                failed.append(f"{row['path']}: {wrong}; {error}")
            else:
                fetched += 1
                bad.discard(row["path"])
            continue
        if os.path.exists(dest) and not os.access(dest, os.W_OK):
            failed.append(f"{row['path']}: {wrong}; read-only, not replaced")
            continue
        if unreachable >= MAX_UNREACHABLE:
            failed.append(f"{row['path']}: {wrong}; not tried (the host was unreachable)")
            continue
        try:
            error = download(row, dest)
            unreachable = 0
        except Unreachable as e:
            error, unreachable = str(e), unreachable + 1
        if error:
            failed.append(f"{row['path']}: {wrong}; download failed: {error}")
        else:
            fetched += 1
            bad.discard(row["path"])
    for line in failed[:MAX_LISTED]:
        print(f"data: {line}", file=sys.stderr)
    if len(failed) > MAX_LISTED:
        print(f"data: ... and {len(failed) - MAX_LISTED} more", file=sys.stderr)
    print(f"data: {root}: {present} of {len(rows)} files present and checked, {fetched} "
          f"downloaded or made, {len(failed)} missing or wrong")
    return 0 if not failed else 1


def main(argv):
    if argv[1:] == ["dir"]:
        print(data_dir())
        return 0
    if argv[1:2] == ["fetch"] and argv[2:] in ([], ["-n"]):
        return fetch(argv[2:] == ["-n"])
    print("usage: third_party.py dir | fetch [-n]", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
