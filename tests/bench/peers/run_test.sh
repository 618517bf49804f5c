#!/usr/bin/env bash
# bench/peers/run's paths that need no Blender: Blender missing, a Blender
# that fails, one that exits 0 but writes no result (or a broken one). Each
# must print exactly one line on stdout, nothing on stderr, and exit 0 (the
# peer benchmark is optional). Run by ctest (label peers) with
# NEUROCLOTH_CLI set; fake `blender` programs go first on PATH.
set -u
run="$1"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0

# PATH holds python3 (the driver's interpreter) and, per case, a fake blender.
mkdir "$scratch/python"
# (the interpreter itself: a shim such as pyenv's would need more of PATH).
ln -s "$(python3 -c 'import os, sys; print(os.path.realpath(sys.executable))')" \
  "$scratch/python/python3"

fake() {  # fake NAME BODY: a directory holding a `blender` that runs BODY
  mkdir -p "$scratch/$1"
  printf '#!/bin/sh\n%s\n' "$2" >"$scratch/$1/blender"
  chmod +x "$scratch/$1/blender"
}

# expect CASE PATH WORDS: one line on stdout containing WORDS, exit 0, no stderr.
expect() {
  local name=$1 path=$2 words=$3
  env -u BLENDER PATH="$path" "$run" --sizes 8 --repeat 1 --seconds 0.1 \
    >"$scratch/out" 2>"$scratch/err"
  local code=$? lines
  lines=$(wc -l <"$scratch/out")
  if [ "$code" -ne 0 ] || [ "$lines" -ne 1 ] || [ -s "$scratch/err" ] ||
    ! grep -q -- "$words" "$scratch/out"; then
    echo "FAIL $name: exit $code, $lines lines (expected 0, 1 line with '$words'):"
    cat "$scratch/out" "$scratch/err"
    failures=$((failures + 1))
  else
    echo "ok   $name: $(cat "$scratch/out")"
  fi
}

expect missing "$scratch/python" "blender not found"

fake fails 'echo "Blender 3.4.1"; echo "Error: something broke" >&2; exit 1'
expect fails "$scratch/fails:$scratch/python" "blender failed (exit 1).*something broke"

fake silent 'exit 0'
expect silent "$scratch/silent:$scratch/python" "wrote no result"

# A result file that is not the drape's JSON: the path follows "--" as argument 5.
fake broken 'while [ "$1" != "--" ]; do shift; done; echo "{not json" >"$6"; exit 0'
expect broken "$scratch/broken:$scratch/python" "not the drape's JSON"

fake short 'while [ "$1" != "--" ]; do shift; done
echo "{\"positions\": [[0, 0, 0]], \"step_seconds\": 1}" >"$6"; exit 0'
expect short "$scratch/short:$scratch/python" "not 64"

[ "$failures" -eq 0 ]
