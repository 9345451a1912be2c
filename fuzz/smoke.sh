#!/usr/bin/env bash
# A short libFuzzer run from the seed corpus, as a test: any crash, leak or sanitizer report
# fails it. New inputs go to a temporary directory, never into the committed seeds.
# Usage: smoke.sh FUZZER SEED_DIR RUNS [MORE_SEED_DIRS...]
set -euo pipefail
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$1" -runs="$3" -max_total_time=300 -print_final_stats=1 "$work" "$2" "${@:4}" 2>&1 | tail -n 12
