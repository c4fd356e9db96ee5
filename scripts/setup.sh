# Shared by scripts/demo and scripts/test: installs missing Debian packages, then
# configures and builds Release into build/. Sourced, not run.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build"

# Debian 12 packages the build and tests need.
PACKAGES=(
  build-essential cmake pkg-config
  libglfw3-dev libglm-dev libtinygltf-dev libosmesa6-dev libegl-dev libegl1 libgl1-mesa-dri
  libstb-dev libtinyexr-dev python3-glad nlohmann-json3-dev libcli11-dev libtbb-dev libdraco-dev libmeshoptimizer-dev
  libgtest-dev libgmock-dev libbenchmark-dev libimgui-dev libembree-dev
  xvfb xauth
  python3 clang libclang-rt-14-dev
)

missing_packages() {
  local p missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  echo "${missing[@]:-}"
}

install_packages() {
  local missing
  missing="$(missing_packages)"
  [ -z "$missing" ] && return 0
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
      sudo="sudo"
    else
      echo "These Debian packages are missing; install them and run this again:" >&2
      echo "  sudo apt-get install -y $missing" >&2
      exit 1
    fi
  fi
  echo "Installing: $missing"
  export DEBIAN_FRONTEND=noninteractive
  if ! { $sudo apt-get update -qq && $sudo apt-get install -y -qq $missing; }; then
    echo "apt-get failed; install the packages by hand:" >&2
    echo "  sudo apt-get install -y $missing" >&2
    exit 1
  fi
}

configure_and_build() {
  # Tests and benchmarks are always configured, so scripts/demo and scripts/test share
  # one build tree and a second run of either is incremental.
  if [ ! -f "$BUILD/CMakeCache.txt" ]; then
    cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DENGINE_WERROR=ON >/dev/null
  fi
  cmake --build "$BUILD" -j"$(nproc)" "$@"
}
