#!/usr/bin/env bash
# End-to-end tests of the `lookout` program. Usage: cli_test.sh LOOKOUT SOURCE_DIR CASE
set -euo pipefail
lookout=$1
src=$2
case_name=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

fail() { echo "FAIL: $*" >&2; exit 1; }

case "$case_name" in
  run_default)
    "$lookout" run --out "$work/out" >"$work/stdout"
    [[ -s "$work/out/recording.mcap" ]] || fail "no recording"
    [[ -s "$work/out/metrics.json" ]] || fail "no metrics.json"
    grep -q '"scenario": "left-turn-across-path"' "$work/out/metrics.json" ||
      fail "metrics.json scenario"
    grep -q '"timing.frames": 151' "$work/out/metrics.json" || fail "timing.frames should be 151"
    for word in scenario simulated frames messages warnings "wall time" "real time" recording; do
      grep -q "^$word" "$work/stdout" || fail "summary lacks '$word'"
    done
    ls "$work/out" | grep -q '\.part$' && fail "a .part file was left behind"
    ;;
  bench)
    # Every bench key of docs/cli-contract.md that has a stage behind it, a positive number.
    "$lookout" bench --json "$work/bench.json" 2>/dev/null >/dev/null
    node -e '
      const b = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
      for (const key of ["sim.realtime_factor", "grid.cycle_ms_median", "grid.reference_speedup",
                         "tracking.mht_step_ms_median", "risk.step_ms_median",
                         "pipeline.realtime_factor"]) {
        if (!(typeof b[key] === "number" && b[key] > 0)) { console.error(`${key}: ${b[key]}`); process.exit(1); }
      }
      // The fast path must beat the literal reference it is measured against.
      if (!(b["grid.reference_speedup"] > 1)) { console.error("no speed-up"); process.exit(1); }
    ' "$work/bench.json" || fail "bench keys"
    ;;
  deterministic)
    "$lookout" run --out "$work/a" --threads 1 >/dev/null
    "$lookout" run --out "$work/b" --threads 2 >/dev/null
    "$lookout" run --out "$work/c" --threads 2 >/dev/null
    cmp "$work/a/recording.mcap" "$work/b/recording.mcap" || fail "1 vs 2 threads differ"
    cmp "$work/b/recording.mcap" "$work/c/recording.mcap" || fail "two 2-thread runs differ"
    ;;
  bad_scenario)
    printf 'format: 1\nname: broken\nduration: -3\nego:\n  path: [[0, 0], [10, 0]]\n  speed: 1\n' \
      >"$work/broken.yaml"
    set +e
    "$lookout" run "$work/broken.yaml" --out "$work/out" 2>"$work/stderr"
    code=$?
    set -e
    [[ $code == 2 ]] || fail "exit code $code, expected 2"
    grep -q "broken.yaml:3: duration" "$work/stderr" ||
      fail "message lacks file:line: field: $(cat "$work/stderr")"
    [[ $(wc -l <"$work/stderr") == 1 ]] || fail "more than one line on stderr"
    [[ ! -e "$work/out" ]] || fail "output written for a bad scenario"
    ;;
  bad_option)
    set +e
    "$lookout" run --threads 0 --out "$work/out" 2>"$work/stderr"; code1=$?
    "$lookout" run --no-such-flag 2>/dev/null; code2=$?
    "$lookout" run "$work/missing.yaml" 2>"$work/stderr3"; code3=$?
    "$lookout" run --snapshot 99 --out "$work/out" 2>/dev/null; code4=$?
    "$lookout" run --grid-scan-flow maybe --out "$work/out" 2>/dev/null; code5=$?
    set -e
    [[ $code1 == 2 && $code2 == 2 && $code3 == 2 && $code4 == 2 && $code5 == 2 ]] ||
      fail "exit codes $code1 $code2 $code3 $code4 $code5"
    grep -q "missing.yaml" "$work/stderr3" || fail "missing file not named"
    [[ ! -e "$work/out" ]] || fail "output written for a bad option"
    ;;
  reference_reader)
    # The default run, read back by the reference TypeScript MCAP reader (@mcap/core).
    "$lookout" run --out "$work/out" >/dev/null
    node "$src/tests/node/read_mcap.mjs" "$work/out/recording.mcap" >"$work/read.json"
    node -e '
      const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
      // 12 s: lidar 12.5 Hz -> 151 frames, stereo 20 Hz -> 241, odometry 50 Hz -> 601; the grid
      // every fifth lidar frame -> 31; /tf: two mounts, world -> odom, and one per lidar frame;
      // the grid objects, the tracks and the risk step at every lidar frame -> 151; the warning
      // events: at least the warning of the turning car.
      const want = {"/lidar/scan": 151, "/stereo/objects": 241, "/odometry": 601,
                    "/truth/actors": 151, "/truth/scene": 151, "/truth/ego": 151,
                    "/tf": 154, "/world/static": 1, "/grid/belief": 31, "/lidar/objects": 151,
                    "/tracks": 151, "/risk/assessment": 151};
      for (const [topic, n] of Object.entries(want)) {
        if (r.topics[topic] !== n) { console.error(`${topic}: ${r.topics[topic]} != ${n}`); process.exit(1); }
      }
      if (!(r.topics["/risk/warnings"] >= 1)) { console.error("no warning event"); process.exit(1); }
      if (Object.keys(r.topics).length !== Object.keys(want).length + 1) { console.error("extra topics"); process.exit(1); }
    ' "$work/read.json" || fail "reference reader counts: $(cat "$work/read.json")"
    ;;
  catalogue)
    # Every catalogue scenario once through `lookout run`: a recording and a metrics.json with
    # the keys of every stage. `lookout eval`'s own report is checked on two of them: running
    # the whole catalogue twice would double CI's longest test for no path it does not cover.
    shopt -s nullglob
    files=("$src"/scenarios/*.yaml)
    (( ${#files[@]} >= 12 )) || fail "catalogue has ${#files[@]} files, expected >= 12"
    keys='["timing.frames", "timing.pipeline_ms_median", "timing.realtime_factor",
           "tracking.gospa_m", "risk.warned", "risk.max_level"]'
    for f in "${files[@]}"; do
      name=$(basename "$f" .yaml)
      "$lookout" run "$f" --out "$work/$name" >/dev/null || fail "run $f"
      [[ -s "$work/$name/recording.mcap" ]] || fail "no recording for $f"
      node -e '
        const m = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8")).metrics;
        for (const k of JSON.parse(process.argv[2]))
          if (typeof m[k] !== "number") { console.error(k); process.exit(1); }
      ' "$work/$name/metrics.json" "$keys" || fail "metrics.json of $name"
    done
    pair=("$src/scenarios/fast-car.yaml" "$src/scenarios/child-behind-parked-car.yaml")
    "$lookout" eval "${pair[@]}" --json "$work/eval.json" 2>/dev/null
    node -e '
      const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
      const names = r.scenarios.map(s => s.scenario).join(",");
      if (names !== "fast-car,child-behind-parked-car") { console.error(names); process.exit(1); }
      if (typeof r.summary !== "object") { console.error("no summary"); process.exit(1); }
      for (const s of r.scenarios)
        for (const k of JSON.parse(process.argv[2]))
          if (typeof s.metrics[k] !== "number") { console.error(s.scenario, k); process.exit(1); }
    ' "$work/eval.json" "$keys" || fail "eval JSON"
    # The same scenario scored by run and by eval: the same figures.
    node -e '
      const fs = require("fs");
      const run = JSON.parse(fs.readFileSync(process.argv[1], "utf8")).metrics;
      const ev = JSON.parse(fs.readFileSync(process.argv[2], "utf8")).scenarios[0].metrics;
      for (const k of ["tracking.gospa_m", "risk.max_level", "grid.static_false_dynamic_rate"])
        if (run[k] !== ev[k]) { console.error(k, run[k], ev[k]); process.exit(1); }
    ' "$work/fast-car/metrics.json" "$work/eval.json" || fail "run and eval disagree"
    ;;
  short_run)
    # The default scenario's first 3 s (its warning expectation dropped: the contact is later),
    # every stage on: recording, metrics, the same bytes with 1 and 2 threads, and the
    # reference reader's topic counts. The sanitizer run's end-to-end test of the pipeline.
    sed -e 's/^duration: .*/duration: 3.0/' -e 's/^  warning: true/  warning: false/' \
        -e '/^  warn_before:/d' "$src/scenarios/left-turn-across-path.yaml" >"$work/short.yaml"
    "$lookout" run "$work/short.yaml" --out "$work/a" --threads 1 >/dev/null
    "$lookout" run "$work/short.yaml" --out "$work/b" --threads 2 >/dev/null
    cmp "$work/a/recording.mcap" "$work/b/recording.mcap" || fail "1 vs 2 threads differ"
    grep -q '"timing.frames": 38' "$work/a/metrics.json" || fail "timing.frames should be 38"
    # The grid without the scan pair's windows (on by default): the same bytes with 1 and 2
    # threads, and not the default's bytes (the option reaches the grid).
    "$lookout" run "$work/short.yaml" --out "$work/fa" --threads 1 --grid-scan-flow off >/dev/null
    "$lookout" run "$work/short.yaml" --out "$work/fb" --threads 2 --grid-scan-flow off >/dev/null
    cmp "$work/fa/recording.mcap" "$work/fb/recording.mcap" || fail "no scan flow: 1 vs 2 threads differ"
    if cmp -s "$work/a/recording.mcap" "$work/fa/recording.mcap"; then
      fail "--grid-scan-flow off changed nothing"
    fi
    node "$src/tests/node/read_mcap.mjs" "$work/a/recording.mcap" >"$work/read.json"
    node -e '
      const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
      // 3 s: lidar 12.5 Hz -> 38 frames, stereo 20 Hz -> 61, odometry 50 Hz -> 151, the grid
      // every fifth lidar frame -> 8, tracks and risk at every lidar frame.
      const want = {"/lidar/scan": 38, "/stereo/objects": 61, "/odometry": 151, "/grid/belief": 8,
                    "/lidar/objects": 38, "/tracks": 38, "/risk/assessment": 38};
      for (const [topic, n] of Object.entries(want))
        if (r.topics[topic] !== n) { console.error(`${topic}: ${r.topics[topic]} != ${n}`); process.exit(1); }
    ' "$work/read.json" || fail "reference reader counts: $(cat "$work/read.json")"
    ;;
  *)
    fail "unknown case $case_name"
    ;;
esac
echo "ok: $case_name"
