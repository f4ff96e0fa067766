#!/usr/bin/env bash
# Installs the Debian packages BxDF Lab needs, and nothing that is already there.
# Debian's apt is the only source (PyPI is not reachable); /usr/bin/python3 is the interpreter
# Blender embeds, so every Python package below is Debian's.
set -euo pipefail

PACKAGES=(
  cmake g++ make pkg-config ccache
  libgtest-dev libbenchmark-dev
  libembree-dev libtbb-dev
  libopenimageio-dev openimageio-tools
  pybind11-dev python3-dev
  libceres-dev libeigen3-dev
  nlohmann-json3-dev libtinyobjloader-dev
  clang libclang-rt-dev
  python3-numpy python3-pytest python3-openimageio python3-matplotlib python3-distributed
  blender povray
  xvfb xauth
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
