#!/usr/bin/env bash
# Installs the Debian packages cosmpm needs, only those that are missing.
set -euo pipefail
# paraview, python3-paraview, xvfb and xauth: CI opens frames in ParaView's own readers
# (pvbatch under a virtual X server); scripts/paraview_layers.py renders the paper's view.
packages=(build-essential cmake ninja-build git libeigen3-dev libhdf5-dev doctest-dev
          libbenchmark-dev clang-format ccache python3 python3-matplotlib python3-h5py python3-numpy
          paraview python3-paraview xvfb xauth)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
