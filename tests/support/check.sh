# The shell tests' checks: `check DESCRIPTION COMMAND...` prints ok or FAILED and counts it;
# `check_summary NAME` prints the counts and returns non-zero if any check failed.
failures=0
passes=0
check() {  # description, then a command that must succeed
  local what=$1; shift
  if "$@"; then echo "ok: $what"; passes=$((passes + 1)); else echo "FAILED: $what"; failures=$((failures + 1)); fi
}
check_summary() {
  echo "$1: $passes passed, $failures failed"
  [ "$failures" -eq 0 ]
}
