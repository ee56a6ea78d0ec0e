#!/usr/bin/env bash
# Bad command-line input to a demo must end with exit status 2 and one clear
# line on stderr (no stack trace, no hang), serially and under MPI.
# usage: cli_errors.sh DEMO_BINARY MPIEXEC
demo=$1
mpiexec=${2:-mpirun}
source "$(dirname "$0")/common.sh"
pass=0

# expect_error REGEX ARGS... : exit 2, exactly one stderr line matching REGEX
expect_error() {
  local regex=$1
  shift
  timeout 120 "$demo" --output "$work/out" "$@" >"$work/stdout" 2>"$work/stderr"
  local status=$?
  local lines
  lines=$(grep -c . "$work/stderr")
  if [ "$status" -eq 2 ] && [ "$lines" -eq 1 ] && grep -Eq "$regex" "$work/stderr"; then
    pass=$((pass + 1))
    echo "ok   [$*] -> $(cat "$work/stderr")"
  else
    fail=$((fail + 1))
    echo "FAIL [$*]: status $status (want 2), $lines stderr line(s) (want 1), want /$regex/:"
    sed 's/^/     /' "$work/stderr"
  fi
}

printf '[study]\nh0 0.1\n' >"$work/malformed.toml"
printf '[study]\nh00 = 0.1\n' >"$work/unknown.toml"
printf '[study]\nlevels = "many"\n' >"$work/badtype.toml"

expect_error 'nonsense' --nonsense
expect_error 'study\.h0.*> 0.*-0\.1' --study.h0 -0.1
expect_error 'study\.h0' --study.h0 abc
expect_error 'study\.dim.*2 or 3' --study.dim 4
expect_error 'study\.levels' --study.levels 0
expect_error "config file '/nonexistent/fsai.toml' not found" --config /nonexistent/fsai.toml
expect_error 'malformed\.toml' --config "$work/malformed.toml"
expect_error 'study\.h00.*unknown' --config "$work/unknown.toml"
expect_error 'study\.levels.*invalid' --config "$work/badtype.toml"
expect_error "output folder '/proc/fsai_out' is not writable" --output /proc/fsai_out

# --help: status 0 and usage on stdout
if timeout 60 "$demo" --help >"$work/stdout" 2>"$work/stderr" && grep -q -- "--study.h0" "$work/stdout"; then
  pass=$((pass + 1)); echo "ok   [--help]"
else
  fail=$((fail + 1)); echo "FAIL [--help]"
fi

# Under MPI: the error reaches the user and no rank hangs
timeout 120 "$mpiexec" -n 2 "$demo" --output "$work/out" --study.h0 -1 >"$work/stdout" 2>"$work/stderr"
status=$?
if [ "$status" -ne 0 ] && [ "$status" -ne 124 ] && [ "$(grep -c 'study.h0: must be > 0' "$work/stderr")" -eq 1 ]; then
  pass=$((pass + 1)); echo "ok   [mpirun -n 2 --study.h0 -1] -> status $status"
else
  fail=$((fail + 1)); echo "FAIL [mpirun -n 2 --study.h0 -1]: status $status"; cat "$work/stderr"
fi

echo "cli_errors: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
