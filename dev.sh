#!/usr/bin/env bash
# One entry point for people and CI. Each command does its own set-up first:
# installs the Debian packages that are missing (tools/packages.txt), configures
# a Release build once, and builds incrementally.
#
#   ./dev.sh bake [SCENE] [bake options]  bake a scene (default: the Cornell box), print the report
#   ./dev.sh test [ctest options]         run the whole test suite with ctest
#   ./dev.sh build                        set up and build only
set -euo pipefail
cd "$(dirname "$0")"
root=$(pwd)
build_dir="$root/build/release"

log() { printf '[dev] %s\n' "$*" >&2; }

install_missing_packages() {
  local missing=()
  while read -r pkg; do
    [[ -z "$pkg" || "$pkg" == \#* ]] && continue
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$pkg")
    fi
  done <"$root/tools/packages.txt"
  ((${#missing[@]} == 0)) && return 0
  log "installing ${#missing[@]} missing packages: ${missing[*]}"
  local sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

build() {
  install_missing_packages
  if [[ ! -f "$build_dir/build.ninja" ]]; then
    log "configuring Release build in build/release"
    cmake --preset release >/dev/null
  fi
  cmake --build --preset release -- -j"$(nproc)"
}

cmd=${1:-help}
shift || true
case "$cmd" in
  build)
    build
    ;;
  bake)
    build
    scene="resources/scenes/cornell-box"
    if [[ $# -gt 0 && "$1" != -* ]]; then
      scene=$1
      shift
    fi
    name=$(basename "${scene%/scene.json}")
    exec "$build_dir/app/bounce" bake "$scene" --out "bakes/${name%.*}" "$@"
    ;;
  test)
    build
    cd "$build_dir"
    exec ctest --output-on-failure -j"$(nproc)" "$@"
    ;;
  *)
    sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
    [[ "$cmd" == help || "$cmd" == -h || "$cmd" == --help ]] || exit 2
    ;;
esac
