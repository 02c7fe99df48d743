# Sourced by the benchmark scripts' tests with their arguments (SOURCE_DIR BUILD_DIR): sets -u,
# $src, FUSEMAP_BUILD (the binaries the scripts run), a scratch folder $work removed on exit
# holding $work/logs/corridor.gfs.log (write_corridor_log), and fail MESSAGE (printed, counted
# in $failures).
set -u
src=$1
export FUSEMAP_BUILD=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# write_corridor_log FILE: a small synthetic CARMEN log, a robot creeping down a corridor
# towards its end wall: 40 scans 5 cm apart, 181 beams, side walls 2 m away, the end wall 4 m
# ahead at the start; odometry and GMapping's poses exact.
write_corridor_log() {
  awk 'BEGIN {
    for (k = 0; k < 40; ++k) {
      t = 1 + k * 0.2; x = k * 0.05
      printf "ODOM %.3f 0 0 0.25 0 0 %.3f host %.3f\n", x, t - 0.1, t - 0.1
      line = "FLASER 181"
      for (i = 0; i < 181; ++i) {
        a = (i - 90) * 3.14159265 / 180; s = sin(a) < 0 ? -sin(a) : sin(a)
        r = (a > 0.5 || a < -0.5) ? 2.0 / s : 4.0 - x
        line = line sprintf(" %.3f", r > 8 ? 8 : r)
      }
      printf "%s %.3f 0 0 %.3f 0 0 %.3f host %.3f\n", line, x, x, t, t
    }
  }' >"$1"
}

mkdir -p "$work/logs"
write_corridor_log "$work/logs/corridor.gfs.log"
