#!/usr/bin/env bash
# End-to-end tests of `lookout slam` (docs/cli-contract.md). Usage:
#   slam_cli_test.sh LOOKOUT SOURCE_DIR CASE
set -euo pipefail
lookout=$1
src=$2
case_name=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
aces="$src/../shared/data/carmen/aces-corrected.log.gz"

case "$case_name" in
  aces)
    # The localisation on a real log, scored against the log's corrected poses: the goal is
    # an ATE of at most 0.2 m (docs/lidar-slam.md), dead reckoning is several metres off.
    [[ -f "$aces" ]] || { echo "skipped: $aces not found"; exit 0; }
    "$lookout" slam "$aces" --trajectory "$work/slam.txt" --map "$work/map.png" >"$work/stdout"
    cat "$work/stdout"
    ate=$(awk '$1 == "ate" { print $2 }' "$work/stdout")
    awk -v a="$ate" 'BEGIN { exit !(a != "" && a <= 0.2) }' || fail "ATE $ate m above 0.2 m"
    records=$(awk '$1 == "log" { gsub(/\(/, "", $3); print $3 }' "$work/stdout")
    [[ $(wc -l <"$work/slam.txt") == "$records" ]] || fail "not one trajectory line per record"
    awk 'NF != 4 { exit 1 }' "$work/slam.txt" || fail "trajectory lines are not 't x y theta'"
    [[ $(head -c 8 "$work/map.png" | od -An -tx1 | tr -d ' ') == 89504e470d0a1a0a ]] ||
      fail "map is not a PNG"
    "$lookout" slam "$aces" --odometry-only --trajectory "$work/odo.txt" >"$work/stdout_odo"
    odo=$(awk '$1 == "ate" { print $2 }' "$work/stdout_odo")
    awk -v a="$ate" -v o="$odo" 'BEGIN { exit !(o > 5 * a) }' ||
      fail "odometry-only ATE $odo m is not far worse than $ate m"
    # Same input, same bytes.
    "$lookout" slam "$aces" --trajectory "$work/slam2.txt" >/dev/null
    cmp "$work/slam.txt" "$work/slam2.txt" || fail "two runs differ"
    ;;
  goal_logs)
    # The ATE goal of docs/lidar-slam.md on each of the four goal logs, on the default seed:
    # at most 0.2 m against the log's corrected poses (11 s of processor time for the four).
    for name in aces csail fhw freiburg-101; do
      log="$src/../shared/data/carmen/$name-corrected.log.gz"
      [[ -f "$log" ]] || { echo "skipped: $log not found"; exit 0; }
    done
    for name in aces csail fhw freiburg-101; do
      "$lookout" slam "$src/../shared/data/carmen/$name-corrected.log.gz" >"$work/$name.out"
      ate=$(awk '$1 == "ate" { print $2 }' "$work/$name.out")
      echo "$name: ATE $ate m"
      awk -v a="$ate" 'BEGIN { exit !(a != "" && a <= 0.2) }' ||
        fail "$name: ATE $ate m above 0.2 m"
    done
    ;;
  bad_input)
    printf 'this is not\na CARMEN log\n' >"$work/junk.log"
    set +e
    "$lookout" slam "$work/junk.log" --trajectory "$work/t.txt" 2>"$work/e1"; c1=$?
    "$lookout" slam "$work/missing.log" --trajectory "$work/t.txt" 2>"$work/e2"; c2=$?
    "$lookout" slam "$work/junk.log" --map "$work/map.jpg" 2>"$work/e3"; c3=$?
    "$lookout" slam "$work/junk.log" --trajectory "$work/no/such/dir/t.txt" 2>"$work/e4"; c4=$?
    "$lookout" slam "$work/junk.log" --no-such-flag 2>/dev/null; c5=$?
    set -e
    [[ "$c1 $c2 $c3 $c4 $c5" == "2 2 2 2 2" ]] || fail "exit codes $c1 $c2 $c3 $c4 $c5"
    for e in e1 e2 e3 e4; do
      [[ $(wc -l <"$work/$e") == 1 ]] || fail "$e: not one line on stderr: $(cat "$work/$e")"
    done
    grep -q "junk.log" "$work/e1" || fail "bad log not named: $(cat "$work/e1")"
    grep -q "missing.log" "$work/e2" || fail "missing log not named"
    [[ ! -e "$work/t.txt" && ! -e "$work/map.jpg" ]] || fail "output written for bad input"
    ;;
  *) fail "unknown case $case_name" ;;
esac
