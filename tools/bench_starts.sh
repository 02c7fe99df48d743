#!/bin/bash
# The log benchmark from several starts (issue 14). Run from anywhere:
#   tools/bench_starts.sh [--starts "0 50 100 150 200"] [--max-rmse-m 0.5] DIR PROFILE OUT
# Runs tools/bench_logs.sh --start-at-scan S DIR PROFILE OUT/start_S for each start S, then
# prints, as Markdown on stdout and in OUT/starts.md (OUT/starts.tsv too), each log's SLAM
# RMSE against GMapping's poses from every start, and how many (log, start) runs exceed
# --max-rmse-m. One start is one roll of the dice: a change that helps from scan 0 and breaks
# a building from scan 50 is luck, not a mechanism; this table tells the two apart.
# Progress on stderr; each start's own table, images and contact sheet stay in OUT/start_S.
# Exit 1 if a start's benchmark failed, 2 on bad usage. Binaries as in bench_logs.sh
# ($FUSEMAP_BUILD, default build/ of this checkout).
set -u
export LC_ALL=C
# shellcheck source=help_lib.sh
source "$(dirname "$0")/help_lib.sh"
usage() { help_from_header "$0"; }
STARTS="0 50 100 150 200"
MAX_RMSE_M=0.5
while [ $# -ge 1 ]; do
  case $1 in
    -h | --help)
      usage
      exit 0
      ;;
    --starts)
      [ $# -ge 2 ] && [[ $2 =~ ^[0-9]+( +[0-9]+)*$ ]] ||
        { echo "bench_starts: --starts needs scan counts, e.g. \"0 50 100\"" >&2; exit 2; }
      STARTS=$2
      shift 2
      ;;
    --max-rmse-m)
      [ $# -ge 2 ] && [[ $2 =~ ^[0-9]+(\.[0-9]+)?$ ]] ||
        { echo "bench_starts: --max-rmse-m needs a distance in metres" >&2; exit 2; }
      MAX_RMSE_M=$2
      shift 2
      ;;
    *) break ;;
  esac
done
if [ $# -ne 3 ]; then
  usage >&2
  exit 2
fi
DIR=$1 PROFILE=$2 OUT=$(realpath -m "$3")
BENCH=$(dirname "$0")/bench_logs.sh
mkdir -p "$OUT" || exit 1

status=0
for s in $STARTS; do
  echo "bench_starts: from scan $s" >&2
  "$BENCH" --start-at-scan "$s" "$DIR" "$PROFILE" "$OUT/start_$s" >/dev/null
  rc=$?
  # 2: bad usage or missing binaries, the same for every start.
  [ $rc -eq 2 ] && exit 2
  [ $rc -ne 0 ] && status=1
done

# One row per log, one column per start: the slam_rmse_m column of each start's table.tsv.
awk -v starts="$STARTS" -v out="$OUT" -v max_rmse="$MAX_RMSE_M" '
  BEGIN {
    num_starts = split(starts, s, " ")
    for (i = 1; i <= num_starts; ++i) {
      file = out "/start_" s[i] "/table.tsv"
      column = 0
      while ((getline line < file) > 0) {
        n = split(line, f, "\t")
        if (!column) {
          for (c = 1; c <= n; ++c) if (f[c] == "slam_rmse_m") column = c
          continue
        }
        if (!(f[1] in seen)) { seen[f[1]] = 1; logs[++num_logs] = f[1] }
        rmse[f[1], i] = f[column]
      }
      close(file)
    }
    header = "| log |"; rule = "|---|"; tsv = "log"
    for (i = 1; i <= num_starts; ++i) {
      header = header " from scan " s[i] " |"; rule = rule "---|"; tsv = tsv "\tstart_" s[i]
    }
    print header "\n" rule > out "/starts.md"
    print tsv > out "/starts.tsv"
    runs = 0; above = 0
    for (l = 1; l <= num_logs; ++l) {
      row = "| " logs[l] " |"; tsv = logs[l]
      for (i = 1; i <= num_starts; ++i) {
        value = ((logs[l], i) in rmse) ? rmse[logs[l], i] : "-"
        row = row " " value " |"; tsv = tsv "\t" value
        if (value ~ /^[0-9.]+$/) { ++runs; if (value + 0 > max_rmse + 0) ++above }
      }
      print row > out "/starts.md"
      print tsv > out "/starts.tsv"
    }
    printf "\nSLAM RMSE m against GMapping'"'"'s poses; %d of %d runs above %s m.\n", above, runs,
           max_rmse > out "/starts.md"
  }'
cat "$OUT/starts.md"
exit $status
