#!/usr/bin/env bash
# Installs the Debian packages nsbridge needs to build, test and plot. Idempotent: when every
# package is present it prints nothing and changes nothing. OpenMPI is optional for the build
# (without it `nsbridge sweep` runs on threads only); CI installs it to test sweeps under mpirun.
# The Python packages build and test the module `nsbridge` for Debian's /usr/bin/python3
# (docs/python.md), pip route included.
# Debian's Siconos for Python (python3-siconos) is the peer of the check
# verification.siconos_two_frame (docs/verification.md), which CMake registers only when
# /usr/bin/python3 imports it: CI installs it so that the check runs; nothing needs it to build.
#   --with-siconos   also install Siconos Numerics, the optional reference for benchmarks
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libboost-dev libgsl-dev
  doctest-dev libcli11-dev libtomlplusplus-dev
  libgnuplot-iostream-dev libboost-iostreams-dev libboost-system-dev libboost-filesystem-dev
  gnuplot-nox
  libopenmpi-dev openmpi-bin
  libhdf5-dev
  clang libfuzzer-14-dev libclang-rt-14-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-pandas
  python3-h5py
  python3-venv python3-pip python3-setuptools
  python3-siconos
)
if [[ "${1:-}" == "--with-siconos" ]]; then
  packages+=(libsiconos-numerics-dev)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
# apt's own chatter (progress, debconf notes) goes to a log that is shown only on failure.
log=$(mktemp)
if ! { $sudo apt-get update -qq && \
       $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
  cat "$log" >&2
  rm -f "$log"
  exit 1
fi
rm -f "$log"
