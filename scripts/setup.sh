#!/usr/bin/env bash
# Install every Debian 12 package fsai needs. Idempotent: packages already
# installed are skipped and `apt-get update` runs at most once per call (and
# not at all when nothing is missing). Nothing is downloaded from elsewhere.
set -euo pipefail

PACKAGES=(
  # Toolchain
  build-essential cmake pkg-config git clang-format
  # FEniCSx 0.5 stack: DOLFINx C++ (pulls PETSc 3.18 with MUMPS/hypre,
  # SLEPc 3.18, HDF5-MPI, Open MPI), FFCx/UFL/basix for the form compiler
  libdolfinx-dev python3-ffcx python3-ufl python3-basix
  libpetsc-real-dev libslepc-real-dev openmpi-bin libopenmpi-dev
  # Meshing
  libgmsh-dev gmsh
  # Configuration, logging, tests
  libcli11-dev libtoml11-dev nlohmann-json3-dev libfmt-dev catch2
  # Optimised BLAS/LAPACK (single-threaded: one MPI rank per core). It
  # replaces the reference BLAS through Debian's alternatives; MUMPS's
  # factorisation of the FE glottis flow is 1.65x faster with it
  libopenblas0-serial
  # Signal processing and sound output
  libfftw3-dev libsndfile1-dev
  # Charts
  python3-matplotlib python3-numpy
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# Optional: headless ParaView rendering of run folders
# (scripts/render_paraview.py, test paraview_render). Without them that
# test is skipped; a failed install only warns.
OPTIONAL=(paraview python3-paraview xvfb xauth libgl1-mesa-dri)
missing_opt=()
for p in "${OPTIONAL[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing_opt+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ] && [ ${#missing_opt[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages (and ${#OPTIONAL[@]} optional) present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} package(s): ${missing[*]}"
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if [ ${#missing_opt[@]} -gt 0 ]; then
  echo "setup: installing ${#missing_opt[@]} optional package(s): ${missing_opt[*]}"
  $SUDO apt-get install -y -qq --no-install-recommends "${missing_opt[@]}" ||
    echo "setup: warning: optional packages not installed (ParaView rendering test will be skipped)"
fi
