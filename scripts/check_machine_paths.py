#!/usr/bin/env python3
"""Nothing the project tracks may name where it was made: no absolute home, work or temporary path.

  check_machine_paths.py REPO [--also PATH ...]

Lists the tracked files (git ls-files; every file under REPO outside build folders when REPO is not the
top of a git checkout), and prints FILE:LINE: TEXT for each line that names an absolute path under /home,
/root, /work, /Users, /tmp or /mnt, or any of the --also paths (the test passes the checkout's own
and the build folder's locations). Exits 1 when it found any, 2 on bad arguments.
"""
import argparse
import os
import re
import subprocess
import sys

# One of those folders right after a slash that no variable, word or relative path precedes, then a
# name: a CMake "${CMAKE_BINARY_DIR}" followed by the work folder, or "build" followed by the
# temporary one, are relative paths; the same folder names at the start of a path are not.
ABSOLUTE = re.compile(r"(?<![\w}$.\-/~])/(home|root|work|Users|tmp|mnt)/[\w.\-]")


def tracked_files(repo):
    if not os.path.exists(os.path.join(repo, ".git")):
        return walked_files(repo)
    try:
        listing = subprocess.run(["git", "-C", repo, "ls-files", "-z"], check=True, capture_output=True).stdout
        return [os.path.join(repo, f) for f in listing.decode().split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        return walked_files(repo)


def walked_files(repo):
    files = []
    for root, dirs, names in os.walk(repo):
        dirs[:] = [d for d in dirs if d not in (".git", "out") and not d.startswith("build")]
        files += [os.path.join(root, n) for n in names]
    return files


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("repo")
    ap.add_argument("--also", action="append", default=[], help="another absolute path no file may name")
    a = ap.parse_args()
    if not os.path.isdir(a.repo):
        print(f"check_machine_paths: {a.repo}: not a folder", file=sys.stderr)
        return 2
    # A short location ("/src") could match text that merely contains it: only distinctive ones count.
    extra = [p.rstrip("/") for p in a.also if len(p.rstrip("/")) >= 8]
    found = 0
    files = tracked_files(a.repo)
    for path in files:
        if not os.path.isfile(path):
            continue  # deleted in the working tree
        with open(path, "rb") as f:
            data = f.read()
        if b"\0" in data[:8192]:
            continue  # binary (images, gzipped structures)
        for number, line in enumerate(data.decode("utf-8", "replace").splitlines(), 1):
            if ABSOLUTE.search(line) or any(p in line for p in extra):
                print(f"{os.path.relpath(path, a.repo)}:{number}: {line.strip()[:160]}")
                found += 1
    print(f"{found} line(s) naming a machine path in {len(files)} tracked files")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
