#!/usr/bin/env bash
# Writes the sample recordings with lookout_mcap_sample and reads each with the reference
# TypeScript MCAP reader (read_mcap.mjs: indexed and streamed), comparing the counts with the
# ones the sample is known to hold. Run by ctest as `mcap_reference_reader`.
#
# Usage: check_sample.sh PATH/TO/lookout_mcap_sample
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
sample_writer="${1:?usage: check_sample.sh PATH/TO/lookout_mcap_sample}"

# Missing tools fail rather than skip: a skipped check would let an unreadable file land.
if ! command -v node >/dev/null 2>&1; then
  echo "check_sample.sh: node is not installed; run scripts/install-deps --test" \
       "(it installs node and runs npm ci in tests/node)" >&2
  exit 1
fi
if [[ ! -d "$here/node_modules/@mcap/core" ]]; then
  echo "check_sample.sh: $here/node_modules is missing; run scripts/install-deps --test" \
       "(it runs npm ci in tests/node)" >&2
  exit 1
fi

out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$sample_writer" "$out"

expected='{"topics":{"/detections":25,"/status":10,"/tracks":40},"schemas":["lookout.Detection","lookout.Track"],"messages":75}'
status=0
for compression in zstd lz4 none; do
  file="$out/sample-$compression.mcap"
  if ! actual="$(node "$here/read_mcap.mjs" "$file")"; then
    echo "FAIL $compression: the reference reader refused $file" >&2
    status=1
  elif [[ "$actual" != "$expected" ]]; then
    echo "FAIL $compression: read $actual" >&2
    echo "     expected  $expected" >&2
    status=1
  else
    echo "ok   $compression: $actual"
  fi
done
exit "$status"
