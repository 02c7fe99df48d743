#!/usr/bin/env bash
# Every binary's exit codes as README "Exit codes" lists them: --help 0, a command-line usage
# error 2, bad input 1; fusemap_carmen2lcm's refusals (issue 18 items 11 and 13); usage errors
# naming the option (issue 16).
# Usage: exit_codes.sh NAME=PATH...
set -u
declare -A bin
for arg in "$@"; do bin[${arg%%=*}]=${arg#*=}; done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

# expect CODE DESCRIPTION COMMAND...: runs it, stderr to $work/err.
expect() {
  local want=$1 what=$2
  shift 2
  "$@" >"$work/out" 2>"$work/err"
  local got=$?
  if [[ $got -ne $want ]]; then
    echo "FAIL: $what: exit $got, expected $want ($*)"
    sed 's/^/    /' "$work/err" | head -5
    failures=$((failures + 1))
  fi
}
# stderr_has TEXT DESCRIPTION: the last command's stderr contains TEXT.
stderr_has() {
  if ! grep -qF -- "$1" "$work/err"; then
    echo "FAIL: $2: stderr lacks '$1'"
    sed 's/^/    /' "$work/err" | head -5
    failures=$((failures + 1))
  fi
}

for name in "${!bin[@]}"; do
  expect 0 "$name --help" "${bin[$name]}" --help
  expect 2 "$name with an unknown flag" "${bin[$name]}" --no-such-flag-xyz
done
for name in fusemap_carmen2lcm fusemap_eval fusemap_tagscore fusemap_offline fusemapd fusemap_sim \
            fusemap_g2o fusemap_cloudeval fusemap_vloop fusemap_bench_images; do
  [[ -n ${bin[$name]:-} ]] && expect 2 "$name without arguments" "${bin[$name]}"
done

if [[ -n ${bin[fusemap_carmen2lcm]:-} ]]; then
  c2l=${bin[fusemap_carmen2lcm]}
  printf 'ODOM 0.0 0.0 0.0 0.0 0.0 0.0 1.0 host 1.0\n' >"$work/log.txt"
  size=$(stat -c %s "$work/log.txt")
  expect 2 "carmen2lcm X X" "$c2l" "$work/log.txt" "$work/log.txt"
  stderr_has "same file" "carmen2lcm X X"
  ln "$work/log.txt" "$work/hardlink.txt"
  expect 2 "carmen2lcm X hard-link-of-X" "$c2l" "$work/log.txt" "$work/hardlink.txt"
  expect 2 "carmen2lcm X ./X" "$c2l" "$work/log.txt" "$work/./log.txt"
  [[ $(stat -c %s "$work/log.txt") -eq $size ]] || { echo "FAIL: input truncated"; failures=$((failures + 1)); }
  expect 0 "carmen2lcm on one ODOM line" "$c2l" "$work/log.txt" "$work/out.lcm"
  head -c 20000 /dev/urandom >"$work/random.bin"
  expect 1 "carmen2lcm on random bytes" "$c2l" "$work/random.bin" "$work/random.lcm"
  stderr_has "no CARMEN records found" "carmen2lcm on random bytes"
  if LC_ALL=C grep -q '[^[:print:][:space:]]' "$work/err"; then
    echo "FAIL: carmen2lcm printed raw bytes"; failures=$((failures + 1))
  fi
  [[ ! -e $work/random.lcm ]] || { echo "FAIL: output left behind"; failures=$((failures + 1)); }
  expect 1 "carmen2lcm on a directory" "$c2l" "$work" "$work/dir.lcm"
  stderr_has "is a directory" "carmen2lcm on a directory"
  gzip -c "$work/log.txt" | head -c 20 >"$work/bad.gz"
  expect 1 "carmen2lcm on a truncated gzip" "$c2l" "$work/bad.gz" "$work/gz.lcm"
  stderr_has "gzip" "carmen2lcm on a truncated gzip"
  expect 1 "carmen2lcm on a missing file" "$c2l" "$work/missing.txt" "$work/m.lcm"
  stderr_has "No such file" "carmen2lcm on a missing file"
  expect 2 "carmen2lcm --range-max x" "$c2l" "$work/log.txt" "$work/o.lcm" --range-max x
fi
if [[ -n ${bin[fusemap_eval]:-} ]]; then
  expect 2 "fusemap_eval unknown command" "${bin[fusemap_eval]}" nonsense
  expect 2 "fusemap_eval ate without --est" "${bin[fusemap_eval]}" ate --gt "$work/x.tum"
  expect 1 "fusemap_eval ate on missing files" "${bin[fusemap_eval]}" ate --gt "$work/x.tum" \
    --est "$work/y.tum"
  printf '1 0 0 0 0 0 0 1\n2 1 0 0 0 0 0 1\n' >"$work/gt.tum"
  expect 1 "fusemap_eval loops without DIR/loops.tsv" "${bin[fusemap_eval]}" loops \
    --gt "$work/gt.tum" --dir "$work/norun"
  stderr_has "nodes.tum: cannot open" "fusemap_eval loops without DIR/loops.tsv"
  expect 1 "fusemap_eval start-end far from the gt" "${bin[fusemap_eval]}" start-end \
    --gt "$work/gt.tum" --est <(printf '5 0 0 0 0 0 0 1\n')
  stderr_has "no ground truth near" "fusemap_eval start-end far from the gt"
fi
if [[ -n ${bin[fusemap_tagscore]:-} ]]; then
  expect 2 "fusemap_tagscore unknown command" "${bin[fusemap_tagscore]}" nonsense
  expect 2 "fusemap_tagscore score without --gt" "${bin[fusemap_tagscore]}" score
  expect 1 "fusemap_tagscore detect on a missing image" "${bin[fusemap_tagscore]}" detect \
    "$work/missing.png"
fi
# Usage errors name the option (common::CommandLine): a bad number, a missing value, a missing
# argument; subcommands take --help.
# usage NAME DESCRIPTION TEXT ARGS...: exit 2 and stderr containing TEXT.
usage() {
  local name=$1 what=$2 text=$3
  shift 3
  [[ -n ${bin[$name]:-} ]] || return 0
  expect 2 "$name $what" "${bin[$name]}" "$@"
  stderr_has "$text" "$name $what"
}
usage fusemap_g2o "--iterations 0" "--iterations: '0'" "$work/x.g2o" --iterations 0
usage fusemap_g2o "--huber without a value" "--huber needs a value" "$work/x.g2o" --huber
usage fusemap_g2o "two inputs" "unexpected argument" "$work/x.g2o" "$work/y.g2o"
usage fusemap_sim "--threads 0" "--threads: '0'" --world w.yaml --out "$work/sim" --threads 0
usage fusemap_sim "--seed -1" "--seed: '-1'" --world w.yaml --out "$work/sim" --seed -1
usage fusemap_sim "--seconds nan" "--seconds: 'nan'" --world w.yaml --out "$work/sim" --seconds nan
usage fusemap_sim "without --out" "missing required option --out" --world w.yaml
# Checked against the simulation's own limits before the world is read.
usage fusemap_sim "--seconds -5" "seconds must be in" --world w.yaml --out "$work/sim" --seconds -5
usage fusemap_sim "--laser-rate 0" "rate_hz must be in" --world w.yaml --out "$work/sim" \
  --laser-rate 0
usage fusemap_cloudeval "--camera-height-m 0" "--camera-height-m: '0'" --cloud c.ply --world w.yaml \
  --camera-height-m 0
usage fusemap_bench_cloud "--sizes 1,0" "--sizes: '0'" --sizes 1,0
usage fusemap_bench_cloud "--sizes without a value" "--sizes needs a value" --sizes
usage fusemap_bench_vloop "--rounds 0" "--rounds: '0'" --rounds 0
usage fusemap_bench_vloop "--keyframes x" "--keyframes: 'x'" --keyframes x
usage fusemap_eval "rpe --delta-unit km" "--delta-unit: 'km'" rpe --gt a.tum --est b.tum \
  --delta-unit km
usage fusemap_eval "start-end --max-time-gap -1" "--max-time-gap: '-1'" start-end --gt a.tum \
  --est b.tum --max-time-gap -1
usage fusemap_eval "loops without --dir" "missing required option --dir" loops --gt a.tum
usage fusemap_eval "relations --max-time-gap -1" "--max-time-gap: '-1'" relations \
  --relations r --trajectory t --max-time-gap -1
usage fusemap_tagscore "groundtruth without --tags" "missing required option --tags" groundtruth \
  --log l.lcm --out gt.tum
usage fusemap_tagscore "detect without images" "missing IMAGE" detect
usage fusemap_tagscore "detect --family nope" "family 'nope'" detect x.png --family nope
usage fusemap_vloop "match with one image" "missing B" match a.png
usage fusemap_vloop "detect --intrinsics 1,2,3" "--intrinsics: '1,2,3'" detect "$work" \
  --intrinsics 1,2,3
usage fusemap_vloop "train-vocabulary --k 1" "branching" train-vocabulary v.bin "$work" --k 1
usage fusemap_bench_images "contact-sheet without images" "missing IMAGE" contact-sheet --out x.png
usage fusemap_bench_images "unknown command" "unknown command 'nonsense'" nonsense
for command in "fusemap_eval ate" "fusemap_eval rpe" "fusemap_eval relations" \
               "fusemap_eval start-end" "fusemap_eval loops" \
               "fusemap_tagscore detect" "fusemap_tagscore score" "fusemap_vloop match" \
               "fusemap_vloop detect" "fusemap_vloop train-vocabulary" \
               "fusemap_bench_images contact-sheet"; do
  name=${command%% *}
  [[ -n ${bin[$name]:-} ]] && expect 0 "$command --help" "${bin[$name]}" "${command#* }" --help
done

echo "exit code checks: $failures failure(s)"
[[ $failures -eq 0 ]]
