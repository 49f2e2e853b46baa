#!/bin/bash
# A script with a typo on line 3 must fail before any window opens, naming the file and the line.
# usage: bad_script.sh NANOVIEW PACKAGE WORKDIR
set -euo pipefail
nanoview=$1 package=$2 work=$3
mkdir -p "$work"
cd "$work"
printf 'camera fov=30\nwait 1\nscreenshot\n' > bad.script
# No DISPLAY: if parsing did not come first, the error would be about the window instead.
if env -u DISPLAY "$nanoview" view "$package" --script bad.script > out.txt 2> err.txt; then
  echo "FAIL: a malformed script was accepted"; exit 1
fi
if ! grep -q "bad.script:line 3: screenshot expects a PATH" err.txt; then
  echo "FAIL: the error does not name bad.script:line 3:"; cat err.txt; exit 1
fi
echo "ok: $(cat err.txt)"
