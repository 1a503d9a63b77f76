# The shared start of the test scripts (sourced, never run): the binary under test (UG_BIN), the
# repository root, a scratch folder removed at exit, and the ok / bad counters each script reports with
# `echo "$passed passed, $failed failed"` at its end.
set -u
bin="${UG_BIN:?UG_BIN must name the undergrowth binary}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); echo "ok   - $1"; }
bad() { failed=$((failed + 1)); echo "FAIL - $1"; }
