#!/usr/bin/env bash
# Installs what is missing (Debian 12 packages), configures and builds
# pushout in build/: every target, or only those named
# (scripts/setup.sh pushout: the program without the unit tests, as
# scripts/demo.sh builds it). Idempotent: installs nothing that is there,
# rebuilds only what changed. Used by scripts/demo.sh and scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  -h | --help)
    echo "usage: scripts/setup.sh [TARGET...]   (no target: all of them; PUSHOUT_BUILD_TYPE=Debug: a debug build)"
    exit 0
    ;;
  -*)
    echo "setup: unknown option $1 (scripts/setup.sh --help)" >&2
    exit 2
    ;;
esac
# Debian's HDF5 compiler wrapper (h5pcc), which CMake runs to find the HDF5
# that DOLFINx needs, splits its arguments at spaces: a build folder whose
# path has one cannot be configured.
case "$PWD" in
  *[[:space:]]*)
    echo "setup: $PWD has a space in its path, which Debian's HDF5 compiler wrapper (h5pcc) cannot take: clone pushout to a path without spaces" >&2
    exit 1
    ;;
esac

packages=(
  cmake g++ make pkg-config
  libdolfinx-dev python3-ffcx           # DOLFINx 0.5.2, FFCx (forms at build time)
  libptscotch-dev                       # nested dissection for the LU on several processes
                                        # (PETSc's development package brings it too)
  libopenblas0-pthread                  # fast BLAS for MUMPS (8-15x over reference)
  libgmsh-dev                           # mesh generation (C++ API)
  libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  python3-matplotlib                    # curve.png
  python3-h5py                          # e2e tests read fields.h5
  paraview python3-paraview xvfb       # pvbatch renders the interface maps (Fig. 8);
                                        # its Python module is only a recommended package
  libgtest-dev clang-format             # unit tests; the format test (ctest -R format)
  mount                                 # e2e_full_disk_fails_cleanly mounts a small tmpfs
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Configured once (a configure that failed left no Makefile: again), or
# again where PUSHOUT_BUILD_TYPE asks for a build type.
if [ ! -f build/Makefile ] || [ -n "${PUSHOUT_BUILD_TYPE:-}" ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE="${PUSHOUT_BUILD_TYPE:-Release}" >/dev/null
fi
# The compiler's words but the progress lines; a failed build fails here
# (an older build/pushout must not stand in for it).
status=0
targets=()
(($#)) && targets=(--target "$@")
cmake --build build -j"$(nproc)" "${targets[@]}" >build/build.log 2>&1 || status=$?
grep -vE '^\[ *[0-9]+%\]|^(Consolidate|-- )' build/build.log >&2 || true
if [ "$status" -ne 0 ] || [ ! -x build/pushout ]; then
  echo "setup: build failed (build/build.log)" >&2
  exit 1
fi
