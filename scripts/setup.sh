#!/usr/bin/env bash
# Installs every system package Nanouniverse needs (Debian 12), idempotently, then configures
# and builds. Mesa's lavapipe (software Vulkan with ray queries) comes from bookworm-backports;
# the backports source is derived from the mirror already configured on this machine.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${NANO_BUILD_DIR:-$here/build}
build_type=${NANO_BUILD_TYPE:-Release}

packages=(
  build-essential cmake ninja-build pkg-config clang-14 libclang-rt-14-dev lld-14
  libzstd-dev libxxhash-dev libglm-dev libpng-dev zlib1g-dev
  libcgal-dev libcgal-demo libeigen3-dev libdraco-dev libassimp-dev libgmp-dev libmpfr-dev
  glslang-tools glslang-dev spirv-tools
  libvulkan-dev vulkan-validationlayers
  libglfw3-dev libimgui-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev
  python3 python3-gemmi python3-numpy python-biopython-doc freesasa
  xvfb xauth xdotool
)
backports_packages=(mesa-vulkan-drivers)

as_root() { if [[ $(id -u) -eq 0 ]]; then "$@"; else sudo "$@"; fi; }

# The URI of the configured bookworm mirror, read from deb822 .sources or a one-line sources.list.
mirror_uri() {
  local f
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f $f ]] || continue
    awk 'BEGIN{RS=""} /Suites:[^\n]*bookworm([ \n]|$)/ && !/security/ {
           for (i = 1; i <= NF; i++) if ($i == "URIs:") { print $(i+1); exit } }' "$f"
  done | head -n1
  if [[ -f /etc/apt/sources.list ]]; then
    awk '$1 == "deb" && $3 == "bookworm" { for (i = 2; i <= NF; i++) if ($i ~ /^[a-z]+:\/\//) { print $i; exit } }' /etc/apt/sources.list
  fi
}

ensure_backports_source() {
  if grep -rqs 'bookworm-backports' /etc/apt/sources.list /etc/apt/sources.list.d/; then return 0; fi
  local uri
  uri=$(mirror_uri | head -n1)
  if [[ -z $uri ]]; then
    echo "setup: no bookworm mirror found in /etc/apt/sources.list(.d); cannot add bookworm-backports" >&2
    exit 1
  fi
  echo "setup: adding bookworm-backports from the configured mirror"
  as_root tee /etc/apt/sources.list.d/nanouniverse-backports.sources >/dev/null <<SRC
Types: deb
URIs: $uri
Suites: bookworm-backports
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  need_update=1
}

missing_packages() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}\n' "$p" 2>/dev/null | grep -q '^install ok installed$' || echo "$p"
  done
}

lavapipe_from_backports() {
  local v
  v=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
  [[ -n $v ]] && dpkg --compare-versions "$v" ge 25 && return 0
  return 1
}

need_update=0
ensure_backports_source
mapfile -t missing < <(missing_packages "${packages[@]}")
if ((${#missing[@]})) || ! lavapipe_from_backports; then
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get update -q
  if ((${#missing[@]})); then
    echo "setup: installing ${missing[*]}"
    as_root apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
  if ! lavapipe_from_backports; then
    echo "setup: installing Mesa (lavapipe) from bookworm-backports"
    as_root apt-get install -y -q --no-install-recommends -t bookworm-backports "${backports_packages[@]}"
  fi
elif ((need_update)); then
  as_root apt-get update -q
fi

if [[ ${NANO_SETUP_ONLY:-0} == 1 ]]; then exit 0; fi
cmake -S "$here" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" \
  -DCMAKE_UNITY_BUILD="${NANO_UNITY_BUILD:-ON}" >/dev/null
cmake --build "$build_dir" -j "${NANO_JOBS:-2}"
