#!/usr/bin/env bash
# Installs the Debian packages impactkit needs (only if some are missing),
# then configures and builds it in ./build (Release).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake
  libeigen3-dev libsundials-dev libceres-dev libfmt-dev libboost-dev libmimalloc-dev
  catch2 libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libtomlplusplus-dev gnuplot-nox zlib1g-dev
  clang-format
  openmpi-bin libopenmpi-dev
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-matplotlib
  python3-pandas python3-yaml python3-tqdm
  python3-xarray python3-nbclient python3-nbformat python3-ipykernel
  python3-venv python3-setuptools python3-wheel
)

missing=()
for package in "${packages[@]}"; do
  dpkg -s "$package" 2>/dev/null | grep -q '^Status: install ok installed' || missing+=("$package")
done

if ((${#missing[@]} > 0)); then
  echo "setup: installing ${missing[*]}"
  sudo=()
  [[ $(id -u) -eq 0 ]] || sudo=(sudo)
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
