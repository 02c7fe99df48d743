# Sourced by every script that uses real UDP multicast (tests and benchmarks). They run only
# inside a private network namespace whose one interface is loopback, with 224.0.0.0/4 routed
# to it, so LCM traffic can never leave the machine.
#
#   . "$SRC/tools/netns_lib.sh"
#   netns_enter SKIP_CODE TOOL... -- "$0" "$@"
#
# Outside a namespace it re-executes the script inside a new one (unshare -n as root, else
# unshare -rn); inside, it checks that loopback is the only interface and sets up multicast.
# Missing tools or no permission exit with SKIP_CODE (77: ctest's "skipped").
netns_enter() {
  local skip_code=$1
  shift
  local tools=(unshare ip)
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do
    tools+=("$1")
    shift
  done
  shift
  if [ "${FUSEMAP_IN_NETNS:-}" != 1 ]; then
    local tool
    for tool in "${tools[@]}"; do
      if ! command -v "$tool" >/dev/null; then
        echo "SKIP: $tool not installed"
        exit "$skip_code"
      fi
    done
    if unshare -n true 2>/dev/null; then
      exec env FUSEMAP_IN_NETNS=1 unshare -n -- "$@"
    elif unshare -rn true 2>/dev/null; then
      exec env FUSEMAP_IN_NETNS=1 unshare -rn -- "$@"
    fi
    echo "SKIP: cannot create a network namespace here (unshare -n / -rn not permitted)"
    exit "$skip_code"
  fi
  if [ "$(ip -o link show | wc -l)" -ne 1 ]; then
    echo "FAIL: not in a private network namespace (interfaces: $(ip -o link show | wc -l))" >&2
    exit 1
  fi
  ip link set lo up multicast on || exit 1
  ip route add 224.0.0.0/4 dev lo || exit 1
}
