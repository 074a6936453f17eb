#!/usr/bin/env bash
# Installs what darcydem needs from Debian 12's packages. Idempotent: does
# nothing when everything is already present. Needs root (or sudo) for apt-get.
# With --compare it also installs YADE and LIGGGHTS (with Open MPI), which only
# bench/compare/compare_codes.py uses (about 190 packages).
set -euo pipefail

packages=(
  cmake g++ make
  libeigen3-dev libtomlplusplus-dev libcli11-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-matplotlib python3-numpy
  pybind11-dev python3-dev
)
case "${1:-}" in
  "") ;;
  --compare) packages+=(yade liggghts openmpi-bin) ;;
  *)
    echo "install-deps: unknown option '$1' (allowed: --compare, to add YADE and LIGGGHTS)" >&2
    exit 2
    ;;
esac

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
