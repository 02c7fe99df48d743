# Sourced by the scripts under tools/: help_from_header FILE prints FILE's leading comment block
# (its usage text), without the shebang line and the '#' marks, so that --help and the file's
# header cannot disagree.
help_from_header() {
  local line
  while IFS= read -r line; do
    [[ $line == "#!"* ]] && continue
    [[ $line == "#"* ]] || break
    line=${line#\#}
    printf '%s\n' "${line# }"
  done <"$1"
}
