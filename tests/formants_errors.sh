#!/usr/bin/env bash
# Bad input to fsai_formants: exit status 2 and one clear stderr line.
# usage: formants_errors.sh FSAI_FORMANTS
set -u
demo=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0
fail=0
expect_error() {
  local regex=$1
  shift
  timeout 120 "$demo" --output "$work/out" --snapshots 0 "$@" >"$work/stdout" 2>"$work/stderr"
  local status=$?
  local lines
  lines=$(grep -c . "$work/stderr")
  if [ "$status" -eq 2 ] && [ "$lines" -eq 1 ] && grep -Eq "$regex" "$work/stderr"; then
    pass=$((pass + 1))
    echo "ok   [$*] -> $(cat "$work/stderr")"
  else
    fail=$((fail + 1))
    echo "FAIL [$*]: status $status (want 2), $lines stderr line(s), want /$regex/:"
    sed 's/^/     /' "$work/stderr"
  fi
}
printf 'x_cm,area_cm2\n1,abc\n' >"$work/nonnumeric.csv"
printf 'x_cm,area_cm2\n1,-0.5\n' >"$work/negative.csv"
printf 'x_cm,area_cm2\n2,1\n1,1\n' >"$work/nonmonotone.csv"
printf 'x,A\n1,1\n' >"$work/header.csv"

expect_error 'vowel' --vowel y
expect_error 'cannot open' --area-function "$work/missing.csv"
expect_error 'nonnumeric.csv:2: not a number' --area-function "$work/nonnumeric.csv"
expect_error 'area must be > 0' --area-function "$work/negative.csv"
expect_error 'x must increase' --area-function "$work/nonmonotone.csv"
expect_error 'header' --area-function "$work/header.csv"
expect_error 'model' --model 3d
expect_error 'radiation' --radiation none
expect_error 'c0.*> 0' --acoustics.c0 -343
expect_error 'rho0.*> 0' --acoustics.rho0 0
expect_error 'f_max.*> 0' --pulse.f_max 0
expect_error 'duration.*> 0' --pulse.duration -1
expect_error 'mic_distance' --mic_distance 0.5
expect_error 'h.*>= 0' --h -0.001
expect_error 'radius' --tract.radius 0.001
echo "formants bad input: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
