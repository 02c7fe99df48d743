#!/usr/bin/env bash
# tools/bench_logs.sh --start-at-scan N on a small synthetic CARMEN log (a robot creeping down a
# corridor towards its end wall): the first N scans are blanked, not dropped (local SLAM skips
# them as too few returns; every odometry record stays), their reference poses leave the
# scores, and the table says where the logs were started. Without the option, nothing is
# blanked. Usage: bench_logs_start_test.sh SOURCE_DIR BUILD_DIR
# shellcheck source=bench_test_lib.sh
source "$(dirname "$0")/bench_test_lib.sh" "$@"

bench="$src/tools/bench_logs.sh"
profile="$src/config/default.yaml"
bash "$bench" --start-at-scan 10 "$work/logs" "$profile" "$work/started" >"$work/started.md" \
  2>"$work/started.err" || fail "--start-at-scan 10 exited $? ($(tail -1 "$work/started.err"))"
grep -q "too_few_returns=10 " "$work/started/corridor/offline.txt" ||
  fail "--start-at-scan 10: local SLAM did not skip exactly 10 scans"
grep -q "^scans=40 .*odometry=40 " "$work/started/corridor/import.txt" ||
  fail "--start-at-scan 10: the import lost scans or odometry records"
poses=$(grep -vc '^#' "$work/started/corridor/reference.tum")
[ "$poses" = 30 ] || fail "--start-at-scan 10: $poses reference poses scored, expected 30"
grep -q "from its scan 10 on" "$work/started.md" || fail "the table does not say where logs start"
ls "$work/started/corridor/"*.gfs.log >/dev/null 2>&1 && fail "the blanked copy was left behind"

bash "$bench" "$work/logs" "$profile" "$work/whole" >/dev/null 2>"$work/whole.err" ||
  fail "without --start-at-scan exited $?"
grep -q "too_few_returns=0 " "$work/whole/corridor/offline.txt" ||
  fail "without --start-at-scan: scans were skipped"
poses=$(grep -vc '^#' "$work/whole/corridor/reference.tum")
[ "$poses" = 40 ] || fail "without --start-at-scan: $poses reference poses, expected 40"

for bad in "--start-at-scan" "--start-at-scan x" "--start-at-scan -1"; do
  # shellcheck disable=SC2086  # the words are the arguments
  bash "$bench" $bad "$work/logs" "$profile" "$work/bad" >/dev/null 2>&1
  code=$?
  [ $code = 2 ] || fail "'$bad' exited $code, expected 2"
done

[ $failures = 0 ] && echo "bench_logs --start-at-scan: all checks passed"
exit $((failures > 0))
