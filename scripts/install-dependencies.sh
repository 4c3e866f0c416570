#!/usr/bin/env bash
# Installs every Debian package (bookworm) that building Opal and running its
# tests need. Idempotent: with everything present it only checks and exits.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake pkg-config python3 python3-numpy python3-pip
  # ParaView 5.11 with its bundled VTK 9.2, and MPI for pvbatch
  paraview paraview-dev python3-paraview mpi-default-bin mpi-default-dev
  # Vulkan compute: headers, loader, shader compiler, Mesa lavapipe, validation layer
  libvulkan-dev mesa-vulkan-drivers vulkan-tools vulkan-validationlayers
  glslang-tools glslang-dev spirv-tools
  # libraries of our own code
  libpng-dev libopenimageio-dev openimageio-tools libcli11-dev libglm-dev nlohmann-json3-dev
  libbenchmark-dev
  # headless ParaView GUI tests
  xvfb xauth
  # fuzzing (libFuzzer) and the sanitizer configuration
  clang libclang-rt-14-dev libfuzzer-14-dev
  # what paraview-dev's CMake configuration looks for beyond its package dependencies
  qtbase5-dev qttools5-dev qttools5-dev-tools libqt5svg5-dev libqt5opengl5-dev
  libqt5x11extras5-dev qtmultimedia5-dev qtxmlpatterns5-dev-tools libhdf5-mpi-dev
  libutfcpp-dev libdouble-conversion-dev libeigen3-dev libexpat1-dev libfreetype-dev
  libgl2ps-dev libglew-dev libjpeg-dev libjsoncpp-dev liblz4-dev libnetcdf-dev
  libnetcdf-cxx-legacy-dev libpng-dev libpython3-dev libtheora-dev libogg-dev
  libtiff-dev libxml2-dev zlib1g-dev liblzma-dev libprotobuf-dev protobuf-compiler
  libpugixml-dev libcgns-dev libgdal-dev libproj-dev libavcodec-dev libavformat-dev
  libswscale-dev
)

missing=()
for package in "${packages[@]}"; do
  if [[ "$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null)" != "installed" ]]; then
    missing+=("$package")
  fi
done

if ((${#missing[@]})); then
  echo "Installing ${#missing[@]} missing package(s): ${missing[*]}"
  sudo=()
  if ((EUID != 0)); then
    sudo=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo[@]}" apt-get update -q
  "${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "All ${#packages[@]} Debian packages are present."
fi

# colour-science (PyPI) for the independent colorimetry test, into the system
# Python that pvpython uses; its only dependency, numpy, comes from Debian.
if ! /usr/bin/python3 -c "import colour" 2>/dev/null; then
  echo "Installing colour-science 0.4.7 from PyPI for /usr/bin/python3"
  sudo=()
  if ((EUID != 0)); then
    sudo=(sudo)
  fi
  "${sudo[@]}" /usr/bin/python3 -m pip install -q --break-system-packages --no-deps colour-science==0.4.7
fi
