#!/usr/bin/env bash
# Glimmer set-up in one command on a fresh Debian 12 machine.
#   bash tools/bootstrap.sh run    install what is missing, build, run the main job (the walkthrough window when a
#                                  display exists, else an offscreen render of the default scene; prints the PNG path)
#   bash tools/bootstrap.sh test   install what is missing, build, run every test (CTest)
# Options: --sanitize (AddressSanitizer + UBSan build in build-asan/), --debug, --jobs N,
#          --no-fuzz (test: skip the loader tests under ASan + UBSan and the fuzzers, tools/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-run}
shift || true
build_dir=build
cmake_args=(-DCMAKE_BUILD_TYPE=Release)
jobs=$(nproc)
fuzz=1
while [ $# -gt 0 ]; do
  case "$1" in
    --sanitize) build_dir=build-asan; cmake_args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DGLIMMER_SANITIZE=ON) ;;
    --debug) build_dir=build-debug; cmake_args=(-DCMAKE_BUILD_TYPE=Debug) ;;
    --jobs) jobs=$2; shift ;;
    --no-fuzz) fuzz=0 ;;
    *) echo "bootstrap.sh: unknown option '$1' (use run|test [--sanitize] [--debug] [--jobs N])" >&2; exit 2 ;;
  esac
  shift
done
case "$mode" in run|test) ;; *) echo "bootstrap.sh: unknown mode '$mode' (use run or test)" >&2; exit 2 ;; esac

# Debian packages (see ../shared/toolchain.md: libgl1-mesa-dri and xauth are not pulled in automatically).
packages=(cmake ninja-build g++ pkg-config libglfw3-dev libglm-dev libosmesa6-dev libegl-dev libegl1-mesa-dev
          libgl-dev libgles-dev libgl1-mesa-dri libtinygltf-dev libopenimageio-dev openimageio-tools
          nlohmann-json3-dev libgtest-dev python3-glad xvfb xauth x11-utils python3-matplotlib zlib1g-dev
          libbullet-dev libmeshoptimizer-dev libembree-dev)
[ "$mode" = test ] && [ "$fuzz" = 1 ] && packages+=(clang libclang-rt-14-dev)   # tools/fuzz.sh
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "bootstrap: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S . -B "$build_dir" -G Ninja "${cmake_args[@]}" >/dev/null
cmake --build "$build_dir" -j "$jobs"

if [ "$mode" = test ]; then
  export GALLIUM_OVERRIDE_CPU_CAPS=avx   # bit-stable llvmpipe output across AVX2 / AVX-512 machines
  ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
  # The loaders under ASan + UBSan: their tests, then the five libFuzzer targets at once for 10 s (fails on a
  # crash). 10 s of wall time on 2 cores keeps CI within its budget (each target gets ~4 CPU s; tools/fuzz.sh N for longer).
  [ "$fuzz" = 0 ] || bash tools/fuzz.sh "${GLIMMER_FUZZ_SECONDS:-10}"
else
  exec "$build_dir/glimmer" main
fi
