#!/usr/bin/env bash
# One entry point for people and CI. Each command does its own set-up first:
# installs the Debian packages that are missing (tools/packages.txt), configures
# a Release build once, and builds incrementally.
#
#   ./dev.sh bake [SCENE] [bake options]  bake a scene (default: the Cornell box), print the report
#                                         and its error against the path-traced reference (builds
#                                         only the `bounce` program)
#   ./dev.sh test [ctest options]         build everything, run the whole test suite with ctest
#   ./dev.sh build                        set up and build only
#   ./dev.sh sanitize [ctest options]     unit tests under ASan + UBSan (preset asan, build/asan)
#   ./dev.sh fuzz [SECONDS|ci]            libFuzzer campaign, SECONDS per target (default 60;
#                                         clang, preset fuzz, build/fuzz; seed: BOUNCE_FUZZ_SEED);
#                                         ci: a fixed number of runs per target, same result every time
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

# Configures build/release once (again when $1 is "require-all" and the
# cache lacks BOUNCE_REQUIRE_ALL=ON) and builds incrementally: the targets
# after $1 ("require-all" or "any"), or everything when none are given.
build() {
  install_missing_packages
  local options=() targets=()
  [[ "${1:-}" == require-all ]] && options=(-DBOUNCE_REQUIRE_ALL=ON)
  (($# > 0)) && shift
  (($# > 0)) && targets=(--target "$@")
  if [[ ! -f "$build_dir/build.ninja" ]] ||
    { ((${#options[@]} > 0)) && ! grep -qx 'BOUNCE_REQUIRE_ALL:BOOL=ON' "$build_dir/CMakeCache.txt"; }; then
    log "configuring Release build in build/release ${options[*]}"
    cmake --preset release "${options[@]}" >/dev/null
  fi
  cmake --build --preset release "${targets[@]}" -- -j"$(nproc)"
}

# Tests registered per label; fails when a label has none, so that a part of
# the suite cannot vanish unnoticed (a test binary not built, discovery that
# found nothing).
check_labels() {
  local label count empty=()
  for label in unit integration render; do
    count=$(ctest --test-dir "$build_dir" -N -L "^${label}\$" | sed -n 's/^Total Tests: //p')
    log "label $label: ${count:-0} tests"
    [[ "${count:-0}" -gt 0 ]] || empty+=("$label")
  done
  if ((${#empty[@]} > 0)); then
    log "no tests with label: ${empty[*]}"
    return 1
  fi
}

# Configures preset $1 once (in build/$1) and builds its targets.
build_preset() {
  install_missing_packages
  if [[ ! -f "$root/build/$1/build.ninja" ]]; then
    log "configuring preset $1 in build/$1"
    cmake --preset "$1" >/dev/null
  fi
  cmake --build --preset "$1" -- -j"$(nproc)"
}

# Runs every fuzz target for $1 seconds over its seed corpus (tests/fuzz/corpus/<target>).
# New inputs go to build/fuzz/corpus/<target>, never into the source tree; a crash,
# sanitizer report, leak, timeout (>10 s per input) or out-of-memory input is written
# to build/fuzz/artifacts/ and fails the command.
# "ci" instead of seconds: a fixed number of inputs per target (about a minute
# or less each here; the bake-folder targets 15-60 s) with the fixed seed, so the campaign is deterministic: CI fails on
# what the code does, not on how far a time limit let libFuzzer get. Longer
# open-ended campaigns (./dev.sh fuzz 600) are how new inputs are found.
declare -A ci_fuzz_runs=([fuzz_scene_json]=60000 [fuzz_mesh_obj]=500 [fuzz_mesh_ply]=40000
                         [fuzz_mesh_gltf]=3000 [fuzz_bake_npy]=15000 [fuzz_bake_dds]=20000
                         [fuzz_bake_manifest]=30000 [fuzz_bake_folder]=10000)
fuzz() {
  local seconds=$1 failed=()
  build_preset fuzz
  mkdir -p "$root/build/fuzz/artifacts"
  for target in fuzz_scene_json fuzz_mesh_obj fuzz_mesh_ply fuzz_mesh_gltf fuzz_bake_npy \
    fuzz_bake_dds fuzz_bake_manifest fuzz_bake_folder; do
    local work="$root/build/fuzz/corpus/$target"
    mkdir -p "$work"
    local budget=(-max_total_time="$seconds")
    if [[ "$seconds" == ci ]]; then
      budget=(-runs="${ci_fuzz_runs[$target]}")
      log "fuzzing $target for ${ci_fuzz_runs[$target]} inputs"
    else
      log "fuzzing $target for ${seconds}s"
    fi
    # The targets write each input to a file under TMPDIR; libFuzzer exits
    # without running destructors, so keep that folder in the build tree.
    # intercept_tls_get_addr=0 for the same reason as in `sanitize` below.
    rm -rf "$root/build/fuzz/tmp" && mkdir -p "$root/build/fuzz/tmp"
    if ! TMPDIR="$root/build/fuzz/tmp" ASAN_OPTIONS="intercept_tls_get_addr=0" \
      LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0" \
      "$root/build/fuzz/tests/fuzz/$target" "${budget[@]}" -timeout=10 \
      -rss_limit_mb=2048 -seed="${BOUNCE_FUZZ_SEED:-1}" -print_final_stats=1 \
      -artifact_prefix="$root/build/fuzz/artifacts/$target-" \
      "$work" "$root/tests/fuzz/corpus/$target" 2>"$root/build/fuzz/$target.log"; then
      tail -n 60 "$root/build/fuzz/$target.log" >&2
      failed+=("$target")
    fi
    grep -E '^stat::(number_of_executed_units|peak_rss_mb)' "$root/build/fuzz/$target.log" |
      sed "s/^/[dev]   $target /" >&2 || true
  done
  if ((${#failed[@]} > 0)); then
    log "fuzzing found failures in: ${failed[*]} (inputs in build/fuzz/artifacts/)"
    return 1
  fi
}

cmd=${1:-help}
shift || true
case "$cmd" in
  build)
    build
    ;;
  bake)
    # Only what baking needs: the `bounce` program and the libraries it links
    # (not the tests, the studio or the Python module).
    build any bounce
    scene="resources/scenes/cornell-box"
    if [[ $# -gt 0 && "$1" != -* ]]; then
      scene=$1
      shift
    fi
    name=$(basename "${scene%/scene.json}")
    # --reference: the bake's own error against the path-traced reference and
    # its run time, one line at the end (the reference is cached under
    # ~/.cache/bounce/reference, so only the first bake of a scene renders it).
    exec "$build_dir/app/bounce" bake "$scene" --out "bakes/${name%.*}" --reference "$@"
    ;;
  test)
    # Every part built (configuring fails naming what is missing), and
    # every label has tests; ctest ends with a time summary per label.
    build require-all
    check_labels
    cd "$build_dir"
    exec ctest --output-on-failure -j"$(nproc)" "$@"
    ;;
  sanitize)
    # The preset's ASAN_OPTIONS include intercept_tls_get_addr=0: the sanitizer
    # runtimes of GCC 12 and clang 14 (Debian 12) take a dynamic TLS block whose
    # address happens to sit 16 bytes into a page for a glibc 2.19 block header,
    # read a bogus range from before it, and LeakSanitizer's tracer dies with
    # signal 11 at exit after the test has passed (seen with PoCL's threads,
    # depending only on where malloc puts the block). Without the interceptor,
    # leaks are still found; only pointers held solely in the dynamic TLS of
    # dlopen'ed libraries stop counting as reachable, and none of ours are.
    build_preset asan
    exec ctest --preset asan -j"$(nproc)" "$@"
    ;;
  fuzz)
    fuzz "${1:-60}"
    ;;
  *)
    sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'
    [[ "$cmd" == help || "$cmd" == -h || "$cmd" == --help ]] || exit 2
    ;;
esac
