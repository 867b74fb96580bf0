#!/usr/bin/env bash
# Installs the Debian packages cosmpm needs, only those that are missing.
set -euo pipefail
packages=(build-essential cmake ninja-build git libeigen3-dev libhdf5-dev doctest-dev
          libbenchmark-dev clang-format python3 python3-matplotlib python3-h5py python3-numpy)
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
