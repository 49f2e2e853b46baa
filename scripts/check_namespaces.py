#!/usr/bin/env python3
"""Namespaces follow folders: code in runtime/X/ or bake/X/ lives in nano::X, code in format/ in
nano::format, code directly in bake/ in nano::bake, and code in common/ in nano (or below it).

  check_namespaces.py REPO

Reads every .hpp, .cpp and .h under REPO's runtime/, bake/, format/ and common/ and each namespace
opened at the start of a line: one named nano or nano::... must be the folder's namespace or one
nested in it (nested helpers such as nano::mesh::parse, and namespaces not under nano such as
format's header_offset, are fine), and so is a namespace opened and closed on one line (forward
declarations of another folder's types). Prints FILE:LINE: found, expected for each mismatch; the known
ones below are printed as such and do not fail. Exits 1 when it found another, 2 on bad arguments.
"""
import pathlib
import re
import sys

FOLDERS = ("runtime", "bake", "format", "common")
OPENING = re.compile(r"^namespace\s+(nano(?:::\w+)*)\s*\{")

# Known mismatches, by file (relative to REPO): why each stays.
KNOWN = {
    # The nanobake command functions are declared in bake/commands.hpp (nano::bake) and defined
    # beside the code they drive.
    "bake/structure/inspect_command.cpp": "defines a command declared in bake/commands.hpp",
    "bake/scene_bake/check_mesh_command.cpp": "defines a command declared in bake/commands.hpp",
    "bake/mesh/make_mesh_command.cpp": "defines a command declared in bake/commands.hpp",
    "bake/scene_bake/bake_command.cpp": "defines a command declared in bake/commands.hpp",
    "bake/cellpack/import_command.cpp": "defines a command declared in bake/commands.hpp",
}
# Folders whose whole content is a known mismatch.
KNOWN_FOLDERS = {
}


def expected(folder: pathlib.PurePosixPath) -> str:
    if folder.parts[0] == "common":
        return "nano"
    if len(folder.parts) == 1:  # format/, bake/
        return "nano::" + folder.parts[0]
    return "nano::" + folder.parts[-1]


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    repo = pathlib.Path(sys.argv[1])
    failures = 0
    for top in FOLDERS:
        for path in sorted((repo / top).rglob("*")):
            if path.suffix not in (".hpp", ".cpp", ".h") or not path.is_file():
                continue
            rel = pathlib.PurePosixPath(path.relative_to(repo).as_posix())
            want = expected(rel.parent)
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                m = OPENING.match(line)
                if not m or line.rstrip().endswith("}"):
                    continue
                found = m.group(1)
                if found == want or found.startswith(want + "::"):
                    continue
                reason = KNOWN.get(str(rel)) or KNOWN_FOLDERS.get(str(rel.parent))
                if reason:
                    print(f"{rel}:{number}: {found}, expected {want} (known: {reason})")
                else:
                    print(f"{rel}:{number}: {found}, expected {want}")
                    failures += 1
    if failures:
        print(f"{failures} namespace(s) do not follow their folder", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
