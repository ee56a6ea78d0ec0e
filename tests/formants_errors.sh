#!/usr/bin/env bash
# Bad input to fsai_formants (area-function files and physics values):
# exit status 2 and one clear stderr line each (cases run by bad_input.sh).
# usage: formants_errors.sh FSAI_FORMANTS
set -u
demo=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf 'x_cm,area_cm2\n1,abc\n' >"$work/nonnumeric.csv"
printf 'x_cm,area_cm2\n1,-0.5\n' >"$work/negative.csv"
printf 'x_cm,area_cm2\n2,1\n1,1\n' >"$work/nonmonotone.csv"
printf 'x,A\n1,1\n' >"$work/header.csv"
s="--snapshots 0"
"$(dirname "$0")/bad_input.sh" "$demo" \
  "vowel|$s --vowel y" \
  "cannot open|$s --area-function $work/missing.csv" \
  "nonnumeric.csv:2: not a number|$s --area-function $work/nonnumeric.csv" \
  "area must be > 0|$s --area-function $work/negative.csv" \
  "x must increase|$s --area-function $work/nonmonotone.csv" \
  "header|$s --area-function $work/header.csv" \
  "model|$s --model 3d" \
  "radiation|$s --radiation none" \
  "c0.*> 0|$s --wave.c0 -343" \
  "rho0.*> 0|$s --wave.rho0 0" \
  "f_max.*> 0|$s --pulse.f_max 0" \
  "duration.*> 0|$s --pulse.duration -1" \
  "mic_distance|$s --mic_distance 0.5" \
  "h.*>= 0|$s --h -0.001" \
  "radius|$s --tract.radius 0.001"
