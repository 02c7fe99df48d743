#!/bin/bash
# Laser SLAM benchmark over a folder of CARMEN logs (issue 14). Run from anywhere:
#   tools/bench_logs.sh [--start-at-scan N] DIR PROFILE OUT
# For every DIR/*.gfs.log and DIR/*.gfs.log.gz: import with fusemap_carmen2lcm (GMapping's
# poses as reference.tum; a stamp map too when DIR/<log>.relations exists), map with
# fusemap_offline --threads 2, score nodes.tum and the input odometry (odometry.tum, sampled at
# the scan stamps) against the reference after an SE(2) alignment (fusemap_eval ate --se2),
# and draw OUT/<log>/side_by_side.png (reference map | our map) and OUT/contact_sheet.png.
# PROFILE: a YAML file used for every log, or a folder: <log>.yaml there where it exists,
# else its default.yaml, else its carmen.yaml. Prints the table as Markdown on stdout and
# writes OUT/table.md and OUT/table.tsv; progress on stderr. Exit 1 if any log failed (its row
# says where), 2 on bad usage. Binaries from $FUSEMAP_BUILD (default: build/ of this checkout).
# --start-at-scan N: map each log from its N-th FLASER scan (from 0) on, as if the robot had
# been switched on there: the earlier scans keep their lines with every range blanked (0), so
# the importer still undoes the odometry's rebasing at them, and local SLAM skips them as
# having too few returns; their reference poses are left out of the scores (and relations are
# not scored).
# The same buildings from other starts, to tell a mechanism from the luck of one start.
set -u
export LC_ALL=C  # decimal points in the figures and the table
# shellcheck source=help_lib.sh
source "$(dirname "$0")/help_lib.sh"
usage() { help_from_header "$0"; }
if [ $# -ge 1 ] && { [ "$1" = "--help" ] || [ "$1" = "-h" ]; }; then
  usage
  exit 0
fi
START_AT_SCAN=0
if [ $# -ge 1 ] && [ "$1" = "--start-at-scan" ]; then
  if [ $# -lt 2 ] || ! [[ $2 =~ ^[0-9]+$ ]]; then
    echo "bench_logs: --start-at-scan needs a scan count (0, 1, ...)" >&2
    exit 2
  fi
  START_AT_SCAN=$2
  shift 2
fi
if [ $# -ne 3 ]; then
  usage >&2
  exit 2
fi
DIR=$(realpath "$1") PROFILE=$(realpath "$2") OUT=$(realpath -m "$3")
SRC=$(realpath "$(dirname "$0")/..")
BUILD=$(realpath "${FUSEMAP_BUILD:-$SRC/build}")
CARMEN2LCM=$BUILD/tools/carmen2lcm/fusemap_carmen2lcm
OFFLINE=$BUILD/tools/offline/fusemap_offline
EVAL=$BUILD/tools/eval/fusemap_eval
IMAGES=$BUILD/tools/bench_logs/fusemap_bench_images
for f in "$CARMEN2LCM" "$OFFLINE" "$EVAL" "$IMAGES"; do
  [ -x "$f" ] || { echo "bench_logs: missing $f (build it)" >&2; exit 2; }
done
[ -d "$DIR" ] || { echo "bench_logs: $DIR is not a folder" >&2; exit 2; }
[ -e "$PROFILE" ] || { echo "bench_logs: no profile $PROFILE" >&2; exit 2; }
mkdir -p "$OUT" || exit 1

# The Kuemmerle relations are stamped on the raw log's clock; its offset to the log's time base
# (data README). DIR/<log>.relations_offset overrides.
declare -A RELATIONS_OFFSET=([intel]=976052857.337284)

# kv FILE KEY [DIGITS]: the value of the last KEY=value token in FILE (empty if none), rounded
# to DIGITS decimals when given.
kv() {
  local line tok value="" toks
  while IFS= read -r line; do
    read -ra toks <<<"$line"
    for tok in "${toks[@]}"; do [[ $tok == "$2="* ]] && value=${tok#*=}; done
  done <"$1"
  if [ $# -ge 3 ] && [ -n "$value" ]; then
    printf "%.${3}f" "$value"
  else
    printf '%s' "$value"
  fi
}

# The first three fields of /proc/loadavg: the machine is shared and timings follow its load.
load() {
  local fields
  read -ra fields </proc/loadavg
  printf '%s %s %s' "${fields[0]}" "${fields[1]}" "${fields[2]}"
}

profile_for() {
  if [ -f "$PROFILE" ]; then
    printf '%s' "$PROFILE"
  elif [ -f "$PROFILE/$1.yaml" ]; then
    printf '%s' "$PROFILE/$1.yaml"
  elif [ -f "$PROFILE/default.yaml" ]; then
    printf '%s' "$PROFILE/default.yaml"
  else
    printf '%s' "$PROFILE/carmen.yaml"
  fi
}

load_start=$(load)
shopt -s nullglob
LOGS=("$DIR"/*.gfs.log "$DIR"/*.gfs.log.gz)
shopt -u nullglob
[ ${#LOGS[@]} -gt 0 ] || { echo "bench_logs: no *.gfs.log[.gz] in $DIR" >&2; exit 1; }

COLUMNS=(log profile scans odometry skipped gmapping_dropped closures_searched
  closures_accepted max_pending scan_ms_median scan_ms_p99 scan_ms_p99_first scan_ms_p99_last
  wall_s realtime_factor cpu_s cpu_realtime_factor peak_rss_mb
  slam_rmse_m slam_max_m odom_rmse_m odom_max_m relations_trans_m relations_rot_deg status)
HEADERS=("log" "profile" "scans" "odometry" "skipped" "GMapping poses dropped"
  "closures searched" "accepted" "max pending searches" "ms/scan median" "p99"
  "p99 first 1000" "p99 last 1000" "wall s" "× real time" "CPU s" "× real time per CPU s"
  "peak RSS MB"
  "SLAM RMSE m" "SLAM max m" "odometry RMSE m" "odometry max m" "relations m" "relations °"
  "status")
ROWS=()
SHEET_ARGS=()
failed=0
index=0
for log in "${LOGS[@]}"; do
  index=$((index + 1))
  name=$(basename "$log")
  name=${name%.gz}
  name=${name%.gfs.log}
  work=$OUT/$name
  mkdir -p "$work"
  profile=$(profile_for "$name")
  declare -A row=()
  for c in "${COLUMNS[@]}"; do row[$c]="–"; done
  row[log]=$name
  row[profile]=$(basename "$profile")
  status=ok
  t0=$SECONDS
  printf '[%d/%d] %s (%s): import' "$index" "${#LOGS[@]}" "$name" "${row[profile]}" >&2

  relations=$DIR/$name.relations
  offset=${RELATIONS_OFFSET[$name]:-}
  [ -f "$DIR/$name.relations_offset" ] && offset=$(<"$DIR/$name.relations_offset")
  import_args=(--reference-poses "$work/reference.tum")
  score_relations=0
  # Relations span the whole log, blanked part included: not scored from another start.
  if [ -f "$relations" ] && [ -n "$offset" ] && [ "$START_AT_SCAN" -eq 0 ]; then
    import_args+=(--stamp-map "$work/stamps.txt")
    score_relations=1
  fi
  input=$log
  if [ "$START_AT_SCAN" -gt 0 ]; then
    input=$work/started_at_scan_$START_AT_SCAN.gfs.log
    { if [[ $log == *.gz ]]; then zcat -- "$log"; else cat -- "$log"; fi; } |
      awk -v first="$START_AT_SCAN" '
        $1 == "FLASER" && n++ < first { for (i = 3; i < 3 + $2; ++i) $i = 0 }
        { print }' >"$input"
  fi
  "$CARMEN2LCM" "$input" "$work/log.lcm" "${import_args[@]}" >"$work/import.txt" \
    2>"$work/import.err"
  imported=$?
  if [ "$START_AT_SCAN" -gt 0 ]; then
    rm -f -- "$input"
    # The blanked scans' reference poses out too: odometry is scored over the same scans.
    if [ $imported -eq 0 ]; then
      awk -v first="$START_AT_SCAN" '/^#/ || n++ >= first' "$work/reference.tum" \
        >"$work/reference.tum.tmp" && mv -- "$work/reference.tum.tmp" "$work/reference.tum"
    fi
  fi
  if [ $imported -ne 0 ]; then
    status="FAILED: import (see $work/import.err)"
  else
    row[scans]=$(kv "$work/import.txt" scans)
    row[odometry]=$(kv "$work/import.txt" odometry)
    row[skipped]=$(kv "$work/import.txt" skipped)
    row[gmapping_dropped]=$(kv "$work/import.txt" gmapping_poses_dropped)
    synthesized=0
    [ "$(kv "$work/import.txt" time_policy)" = synthesized ] && synthesized=1

    printf ', slam' >&2
    offline_args=(--log "$work/log.lcm" --config "$profile" --out "$work" --threads 2)
    if [ $score_relations = 1 ]; then
      offline_args+=(--relations "$relations" --relations-time-offset "$offset"
        --relations-stamp-map "$work/stamps.txt")
    fi
    if ! "$OFFLINE" "${offline_args[@]}" >"$work/offline.txt" 2>"$work/offline.err"; then
      status="FAILED: fusemap_offline (see $work/offline.err)"
    else
      o=$work/offline.txt
      row[closures_searched]=$(kv "$o" loop_closure_searches)
      row[closures_accepted]=$(kv "$o" loop_closures_accepted)
      row[scan_ms_median]=$(kv "$o" median)
      row[scan_ms_p99]=$(kv "$o" p99)
      row[peak_rss_mb]=$(kv "$o" peak_rss_mb)
      row[wall_s]=$(kv "$o" wall_s 1)
      row[realtime_factor]=$(kv "$o" realtime_factor)
      row[max_pending]=$(kv "$o" max_pending_searches)
      row[scan_ms_p99_first]=$(kv "$o" first_p99)
      row[scan_ms_p99_last]=$(kv "$o" last_p99)
      row[cpu_s]=$(kv "$o" cpu_s 1)
      row[cpu_realtime_factor]=$(kv "$o" cpu_realtime_factor)
      if [ $synthesized = 1 ]; then
        row[realtime_factor]="n/a (time synthesized)"
        row[cpu_realtime_factor]="n/a"
      fi
      if [ $score_relations = 1 ]; then
        row[relations_trans_m]=$(kv "$o" trans_mean_m)
        row[relations_rot_deg]=$(kv "$o" rot_mean_deg)
      fi

      printf ', eval' >&2
      if "$EVAL" ate --gt "$work/reference.tum" --est "$work/nodes.tum" --se2 \
        >"$work/ate_slam.txt" 2>&1; then
        row[slam_rmse_m]=$(kv "$work/ate_slam.txt" ate_rmse_m 3)
        row[slam_max_m]=$(kv "$work/ate_slam.txt" ate_max_m 3)
      else
        status="FAILED: ate (see $work/ate_slam.txt)"
      fi
      if [ "${row[odometry]:-0}" -lt 2 ]; then
        row[odom_rmse_m]="n/a (no odometry)"
        row[odom_max_m]="n/a"
      elif "$EVAL" ate --gt "$work/reference.tum" --est "$work/odometry.tum" --se2 \
        --interpolate 1.0 >"$work/ate_odometry.txt" 2>&1; then
        row[odom_rmse_m]=$(kv "$work/ate_odometry.txt" ate_rmse_m 3)
        row[odom_max_m]=$(kv "$work/ate_odometry.txt" ate_max_m 3)
      else
        status="FAILED: odometry ate (see $work/ate_odometry.txt)"
      fi

      printf ', images' >&2
      if "$IMAGES" reference-map --log "$work/log.lcm" --poses "$work/reference.tum" \
        --anchor "$work/nodes.tum" --config "$profile" --out "$work/reference_map.png" \
        >"$work/images.txt" 2>&1 &&
        "$IMAGES" side-by-side --left "$work/reference_map.png" \
          --left-title "reference: GMapping's poses" --right "$work/map.png" \
          --right-title "fusemap (${row[profile]})" \
          --title "$name: SLAM RMSE ${row[slam_rmse_m]} m, odometry ${row[odom_rmse_m]} m" \
          --out "$work/side_by_side.png" >>"$work/images.txt" 2>&1; then
        SHEET_ARGS+=("$work/side_by_side.png")
      else
        status="FAILED: images (see $work/images.txt)"
      fi
    fi
  fi
  [ "$status" = ok ] || failed=1
  row[status]=$status
  printf ': %s (%d s)\n' "$status" $((SECONDS - t0)) >&2
  line=""
  for c in "${COLUMNS[@]}"; do line+="${row[$c]}"$'\t'; done
  ROWS+=("${line%$'\t'}")
  unset row
done

if [ ${#SHEET_ARGS[@]} -gt 0 ] &&
  ! "$IMAGES" contact-sheet --out "$OUT/contact_sheet.png" "${SHEET_ARGS[@]}" \
    >"$OUT/contact_sheet.txt" 2>&1; then
  echo "bench_logs: contact sheet failed (see $OUT/contact_sheet.txt)" >&2
  failed=1
fi

{
  line=""
  for c in "${COLUMNS[@]}"; do line+="$c"$'\t'; done
  printf '%s\n' "${line%$'\t'}"
  for r in "${ROWS[@]}"; do printf '%s\n' "$r"; done
} >"$OUT/table.tsv"
{
  line="|"
  for h in "${HEADERS[@]}"; do line+=" $h |"; done
  printf '%s\n' "$line"
  line="|"
  for h in "${HEADERS[@]}"; do line+="---|"; done
  printf '%s\n' "$line"
  for r in "${ROWS[@]}"; do
    IFS=$'\t' read -ra cells <<<"$r"
    line="|"
    for cell in "${cells[@]}"; do line+=" $cell |"; done
    printf '%s\n' "$line"
  done
  [ "$START_AT_SCAN" -eq 0 ] ||
    printf '\nEach log mapped from its scan %s on (--start-at-scan).\n' "$START_AT_SCAN"
  printf '\nProfile %s, %s; load average (1, 5, 15 min) %s at the start, %s at the end, %s cores.\n' \
    "$2" "$(date -u '+%Y-%m-%d %H:%M UTC')" "$load_start" "$(load)" "$(nproc)"
} >"$OUT/table.md"
cat "$OUT/table.md"
exit $failed
