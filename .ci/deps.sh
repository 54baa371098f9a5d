#!/usr/bin/env bash
# Installs idbench's build and test dependencies from Debian 12 packages.
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config
          libbullet-dev libeigen3-dev nlohmann-json3-dev libyaml-cpp-dev libcli11-dev
          liburdfdom-dev libtinyxml-dev libassimp-dev libnlopt-cxx-dev
          libosmesa6-dev libgl-dev libcairo2-dev libpng-dev fonts-dejavu-core
          libimgui-dev libstb-dev libglfw3-dev
          libsqlite3-dev liblz4-dev libzstd-dev zlib1g-dev  # rosbag2 bags (.db3, .mcap)
          libdsdp-dev                 # the tests' second SDP solver
          pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module and its tests
          libgtest-dev libbenchmark-dev
          xvfb xauth libgl1-mesa-dri  # the windowed GUI's smoke test runs under Xvfb
          poppler-utils               # pdfinfo: the report tests open the PDFs
          libmujoco-dev               # the MJCF export's test loads it with MuJoCo (mj_inverse)
          clang-16 libclang-rt-16-dev)  # the sanitizer build and the libFuzzer harnesses (.ci/sanitizers)
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
# Only refresh the package lists when something is missing.
if ! dpkg-query -W -f='${Status}\n' "${packages[@]}" 2>/dev/null | grep -qv "install ok installed" \
   && [ "$(dpkg-query -W -f='${Status}\n' "${packages[@]}" 2>/dev/null | wc -l)" -eq "${#packages[@]}" ]; then
  exit 0
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${packages[@]}"
