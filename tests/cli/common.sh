# shellcheck shell=bash disable=SC2034 # the sections that source this file use its variables
# The `stochtex` command as a user meets it (docs/design.md §6 and §9). Every bad input must
# exit with its code (1 runtime failure, 2 usage error), print exactly one line on stderr starting
# with "stochtex: error:", and leave no output file behind, not even a temporary one. The good
# paths must work, print valid JSON where asked, and render the same bytes whatever the threads.
#
# The checks are split into one script per section, tests/cli/cli_<section>.sh, each a CTest test
# of label cli, so that CTest runs them side by side. Each sources this file, which checks the
# arguments, makes the work folder and holds the helpers and the summary line.
#
# usage: cli_<section>.sh STOCHTEX_BINARY TEXTURE_DIR SHARED_DIR
#
# cli_setup.sh writes the inputs and models that several sections read (the test images of
# "inputs", the models of the default analyses) into SHARED_DIR; every other section copies them
# into its own work folder, so no section can change what another reads. In CTest cli_setup is the
# setup of the fixture cli_shared (SHARED_DIR is build/tests/cli_shared), which every other section
# requires: `ctest --test-dir build -R cli_meshes` runs cli_setup first by itself. By hand, from the
# repository root after a build, SHARED_DIR any folder:
#
#   bash tests/cli/cli_setup.sh build/stochtex data/exemplars /tmp/cli_shared
#   bash tests/cli/cli_meshes.sh build/stochtex data/exemplars /tmp/cli_shared
#
# STOCHTEX_CLI_GL=one-per-method keeps one `--backend gl` render per method and the GL checks of
# refusals, which stop before any shader is compiled, and counts the other GL runs' checks as
# skipped: a shorter local run where llvmpipe's shader compiles are slow. Unset (as in CI, where
# it saved only 4% of the sanitizer run), every check runs.
set -u

script=$(basename "$0" .sh)
if [[ $# -ne 3 ]]; then
  echo "usage: $0 STOCHTEX_BINARY TEXTURE_DIR SHARED_DIR" >&2
  exit 2
fi
stochtex=$1
textures=$2
shared=$3
exemplar=$textures/grass_lawn_128.png
for required in "$stochtex" "$exemplar"; do
  if [[ ! -f $required ]]; then
    echo "$script: $required does not exist" >&2
    exit 2
  fi
done
if ! command -v python3 >/dev/null; then
  echo "$script: python3 is needed to check JSON output and to write test images" >&2
  exit 2
fi
case ${STOCHTEX_CLI_GL:-} in
  "" | one-per-method) ;;
  *)
    echo "$script: STOCHTEX_CLI_GL is '$STOCHTEX_CLI_GL'; leave it unset (every GL run) or set" \
      "it to one-per-method" >&2
    exit 2
    ;;
esac

work=$(mktemp -d) || exit 2
trap 'rm -rf "$work"' EXIT
# scripts/sanitize.sh runs the tests with Mesa's software driver preloaded (LD_PRELOAD keeps the
# driver's own leak reachable, docs/reliability.md). Only stochtex needs it: every other process
# of a check (grep, find, wc, python3) started 20 ms to a second slower with it. So the checks run
# without it, and stochtex through a wrapper that puts it back and becomes stochtex (exec: the
# same process, its exit status and signals).
if [[ -n ${LD_PRELOAD:-} ]]; then
  printf '#!/bin/sh\nLD_PRELOAD=%q exec %q "$@"\n' "$LD_PRELOAD" "$(realpath "$stochtex")" \
    >"$work/stochtex"
  chmod +x "$work/stochtex"
  stochtex=$work/stochtex
  unset LD_PRELOAD
fi
inputs=$work/in     # bad and good inputs, made by cli_setup.sh and by the sections
models=$work/models # outputs of the good paths
out=$work/out       # where failing commands are told to write: must stay empty
mkdir -p "$inputs" "$models" "$out"

# Made by cli_setup.sh: the texton model most checks render, every method's default model
# ($models/every_<method>.stx) and the gabor model that edit works on.
model=$models/grass.stx
gabor_model=$models/gabor_edit.stx
tiling_model=$models/every_tiling.stx
size=(--size 64x64)
fast=(-m texton -p support=32)
# A model of data, for the checks whose subject is not colour: the default (auto: a PNG is sRGB)
# measures a srgb model's removed deviations at analysis (docs/colour.md), seconds of the
# sanitizer run per analysis. The default is what every_<method> and cli_colour analyse with.
data=(--colour-space data)
analyze_to=(-o "$out/model.stx")
edit_to=(-o "$out/edited.stx")

# Copies cli_setup.sh's inputs and models into this section's own folders and reads the names of
# the registry's methods into $methods, and of the export languages into $languages and (all but
# glsl, the methods' own source) $cross_languages.
load_shared() {
  if [[ ! -f $shared/methods ]]; then
    echo "$script: $shared holds no output of cli_setup.sh: run it first (tests/cli/common.sh)" >&2
    exit 2
  fi
  if ! cp -R "$shared/in/." "$inputs" || ! cp -R "$shared/models/." "$models"; then
    echo "$script: cannot copy $shared into $work" >&2
    exit 2
  fi
  methods=$(<"$shared/methods")
  languages=$(<"$shared/languages")
  cross_languages=$(tr ' ' '\n' <<<"$languages" | grep -vx glsl | tr '\n' ' ')
}

passed=0
skipped=0
failed=()

pass() { passed=$((passed + 1)); }
fail() {
  failed+=("$1")
  echo "FAIL: $1: $2"
  if [[ -s $work/stderr ]]; then sed 's/^/  stderr: /' "$work/stderr"; fi
}

# gl_skipped COUNT NAME: with STOCHTEX_CLI_GL=one-per-method, counts the COUNT checks of the GL run
# NAME as skipped and succeeds; otherwise fails, and the caller runs them:
#   if ! gl_skipped 2 "render gabor --backend gl"; then expect_ok ... && expect_file ...; fi
gl_skipped() {
  [[ ${STOCHTEX_CLI_GL:-} == one-per-method ]] || return 1
  skipped=$((skipped + $1))
}

# Runs the command with stdout and stderr captured in $work/stdout and $work/stderr; sets $status.
capture() {
  "$@" >"$work/stdout" 2>"$work/stderr"
  status=$?
}

# Checks a failure after `capture`: exit code, one "stochtex: error:" line, no file left in $out.
# With mention non-empty, the sentence must also name it (the bad file).
check_failure() {
  local name=$1 code=$2 mention=$3 lines
  lines=$(wc -l <"$work/stderr")
  if [[ $status -ne $code ]]; then
    fail "$name" "exit code $status, expected $code"
  elif [[ $lines -ne 1 ]] || ! head -n 1 "$work/stderr" | grep -q '^stochtex: error: .'; then
    fail "$name" "stderr is $lines line(s), expected one 'stochtex: error: ...' line"
  elif [[ -n $mention ]] && ! grep -qF -- "$mention" "$work/stderr"; then
    fail "$name" "the message does not name '$mention'"
  elif [[ -n $(find "$out" -mindepth 1 -print -quit) ]]; then
    fail "$name" "left output behind: $(find "$out" -mindepth 1 | tr '\n' ' ')"
  else
    pass
  fi
  find "$out" -mindepth 1 -delete
}

# expect_error NAME CODE MENTION COMMAND...: a bad input the CLI itself diagnoses.
expect_error() {
  local name=$1 code=$2 mention=$3
  shift 3
  capture "$@"
  check_failure "$name" "$code" "$mention"
}

# expect_parse_error NAME COMMAND...: rejected by the option parser (CLI11), whose own message
# is accepted; the exit code must still be 2 and nothing may be written.
expect_parse_error() {
  local name=$1
  shift
  capture "$@"
  if [[ $status -ne 2 ]]; then
    fail "$name" "exit code $status, expected 2"
  elif [[ ! -s $work/stderr ]]; then
    fail "$name" "no message on stderr"
  elif [[ -n $(find "$out" -mindepth 1 -print -quit) ]]; then
    fail "$name" "left output behind"
  else
    pass
  fi
  find "$out" -mindepth 1 -delete
}

# expect_ok NAME COMMAND...: exit code 0.
expect_ok() {
  local name=$1
  shift
  capture "$@"
  if [[ $status -ne 0 ]]; then
    fail "$name" "exit code $status, expected 0"
    return 1
  fi
  pass
}

# expect_readme_files NAME DIR: every GLSL and data file an export's README names was written.
expect_readme_files() {
  local name=$1 dir=$2 files missing=""
  files=$(grep -o '`[A-Za-z0-9_]*\.\(png\|exr\|glsl\)`' "$dir/README.md" | tr -d '`' | sort -u)
  for file in $files; do
    [[ -s $dir/$file ]] || missing+=" $file"
  done
  if [[ -z $files ]]; then
    fail "$name" "the README names no file"
  elif [[ -n $missing ]]; then
    fail "$name" "missing:$missing"
  else
    pass
  fi
}

# expect_json NAME COMMAND...: exit code 0 and stdout is one valid JSON document.
expect_json() {
  local name=$1
  shift
  capture "$@"
  if [[ $status -ne 0 ]]; then
    fail "$name" "exit code $status, expected 0"
  elif ! python3 -c 'import json,sys; json.load(sys.stdin)' <"$work/stdout" 2>/dev/null; then
    fail "$name" "stdout is not one valid JSON document"
  else
    pass
  fi
}

# expect_file NAME PATH: a good path wrote a non-empty file and no temporary beside it.
expect_file() {
  local name=$1 path=$2 leftovers
  leftovers=$(find "$(dirname "$path")" -name '*.tmp*' | tr '\n' ' ')
  if [[ ! -s $path ]]; then
    fail "$name" "did not write $path"
  elif [[ -n $leftovers ]]; then
    fail "$name" "left temporaries: $leftovers"
  else
    pass
  fi
}

# signal_during_write NAME SIGNAL FOLDER PATTERN COMMAND...: runs COMMAND, which writes into the
# empty FOLDER, and sends it SIGNAL once a file named like PATTERN (a temporary) is there, that is
# during a write. Passes when its exit status names the signal and FOLDER is left empty. Job
# control (set -m) keeps SIGINT from being ignored by the background job.
signal_during_write() {
  local name=$1 signal=$2 folder=$3 pattern=$4 victim status expected left
  shift 4
  set -m
  "$@" 2>/dev/null &
  victim=$!
  set +m
  for _ in $(seq 1000); do
    [[ -n $(find "$folder" -name "$pattern" -print -quit) ]] && break
    sleep 0.01
  done
  kill -s "$signal" $victim
  wait $victim
  status=$?
  expected=$((128 + $(kill -l "$signal")))
  left=$(find "$folder" -mindepth 1 | tr '\n' ' ')
  if [[ $status -eq $expected && -z $left ]]; then pass; else
    fail "$name" "exit $status (expected $expected), left: $left"
  fi
}

# The last line of every section: its counts, and exit status 1 if a check failed.
summary() {
  local skips=""
  if [[ -n ${STOCHTEX_CLI_GL:-} ]]; then
    skips=" $skipped skipped (STOCHTEX_CLI_GL=$STOCHTEX_CLI_GL),"
  fi
  echo "$script: ${passed} passed,${skips} ${#failed[@]} failed"
  if [[ ${#failed[@]} -gt 0 ]]; then
    printf '  failed: %s\n' "${failed[@]}"
    exit 1
  fi
}
