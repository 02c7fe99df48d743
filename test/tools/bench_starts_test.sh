#!/usr/bin/env bash
# tools/bench_starts.sh on a small synthetic CARMEN log (bench_test_lib.sh): one benchmark per
# start, one row per log with a SLAM RMSE per start, the count of runs above --max-rmse-m, and
# exit 2 on bad options. Usage: bench_starts_test.sh SOURCE_DIR BUILD_DIR
# shellcheck source=bench_test_lib.sh
source "$(dirname "$0")/bench_test_lib.sh" "$@"

starts="$src/tools/bench_starts.sh"
profile="$src/config/default.yaml"
bash "$starts" --starts "0 10" "$work/logs" "$profile" "$work/out" >"$work/out.md" \
  2>"$work/out.err" || fail "exited $? ($(tail -1 "$work/out.err"))"
for s in 0 10; do
  [ -f "$work/out/start_$s/table.tsv" ] || fail "no benchmark from scan $s"
done
grep -q "too_few_returns=10 " "$work/out/start_10/corridor/offline.txt" ||
  fail "the run from scan 10 did not start there"
grep -q "| log | from scan 0 | from scan 10 |" "$work/out.md" || fail "no header for the starts"
row=$(grep '^corridor' "$work/out/starts.tsv")
# A straight corridor with exact odometry maps to within centimetres from either start.
awk -F'\t' '{ exit !(NF == 3 && $2 ~ /^[0-9.]+$/ && $2 < 0.1 && $3 ~ /^[0-9.]+$/ && $3 < 0.1) }' \
  <<<"$row" || fail "corridor row '$row': expected two RMSEs below 0.1 m"
grep -q "0 of 2 runs above 0.5 m" "$work/out.md" || fail "the count of runs above 0.5 m"
# Every RMSE is above 0 m: both runs count.
bash "$starts" --starts "10" --max-rmse-m 0 "$work/logs" "$profile" "$work/zero" >"$work/zero.md" \
  2>/dev/null || fail "--max-rmse-m 0 exited $?"
grep -q "1 of 1 runs above 0 m" "$work/zero.md" || fail "--max-rmse-m 0: the count"

for bad in "--starts" "--starts x" "--starts -1" "--max-rmse-m" "--max-rmse-m far"; do
  # shellcheck disable=SC2086  # the words are the arguments
  bash "$starts" $bad "$work/logs" "$profile" "$work/bad" >/dev/null 2>&1
  code=$?
  [ $code = 2 ] || fail "'$bad' exited $code, expected 2"
done
bash "$starts" "$work/logs" "$profile" >/dev/null 2>&1
[ $? = 2 ] || fail "two arguments: expected exit 2"

[ $failures = 0 ] && echo "bench_starts: all checks passed"
exit $((failures > 0))
