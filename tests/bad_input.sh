#!/usr/bin/env bash
# Bad input to a demo: exit status 2 and one clear stderr line each.
# usage: bad_input.sh DEMO 'REGEX|arg arg ...' ...
set -u
demo=$1
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0
fail=0
for case in "$@"; do
  regex=${case%%|*}
  read -r -a args <<<"${case#*|}"
  timeout 120 "$demo" --output "$work/out" "${args[@]}" >"$work/stdout" 2>"$work/stderr"
  status=$?
  lines=$(grep -c . "$work/stderr")
  if [ "$status" -eq 2 ] && [ "$lines" -eq 1 ] && grep -Eq "$regex" "$work/stderr"; then
    pass=$((pass + 1))
    echo "ok   [${args[*]}] -> $(cat "$work/stderr")"
  else
    fail=$((fail + 1))
    echo "FAIL [${args[*]}]: status $status (want 2), $lines stderr line(s), want /$regex/:"
    sed 's/^/     /' "$work/stderr"
  fi
done
echo "$(basename "$demo") bad input: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
