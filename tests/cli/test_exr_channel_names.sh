#!/usr/bin/env bash
# EXR spectral channels state their wavelengths exactly: whole nanometres keep
# their names (spectrum.400nm); finer steps take the decimals the finest
# wavelength needs, a comma as the decimal separator (EXR splits layers at
# dots), so names are unique and sort in wavelength order. Below a 1 nm step
# they were rounded to whole nm (spectrum.401nm held 400.5 nm) and the rest
# left unnamed (channelN).
# Usage: test_exr_channel_names.sh OPAL_RENDER OPAL_VOLUME WORK_DIR
source "$(dirname "$0")/output_test_support.sh"

tiny=(--dimensions 40 20 50 --domain-count 30 --width 16 --height 12 --exr-spectral-channels)
# wavelength range | step | the spectral channels, in order
cases=(
  "400 440|10|400 410 420 430 440"
  "380 780|200|380 580 780"
  "400 402|0.5|400,0 400,5 401,0 401,5 402,0"
  "400 400.75|0.25|400,00 400,25 400,50 400,75"
  "400 410|2.5|400,0 402,5 405,0 407,5 410,0"
  "400.1 400.4|0.1|400,1 400,2 400,3 400,4"
  "500 500.03|0.01|500,00 500,01 500,02 500,03"
  "600.125 600.375|0.125|600,125 600,250 600,375"
)
for row in "${cases[@]}"; do
  IFS='|' read -r range step wavelengths <<<"$row"
  read -r -a bounds <<<"$range"
  expected="R, G, B"
  for nm in $wavelengths; do expected+=", spectrum.${nm}nm"; done
  "$render" "${tiny[@]}" --wavelength-range "${bounds[@]}" --wavelength-step "$step" -o s.exr >/dev/null 2>case.err ||
    fail "$range nm by $step: rendered ($(cat case.err))"
  channels=$(oiiotool --info -v s.exr | sed -n 's/^ *channel list: //p')
  [[ $channels == "$expected" ]] || fail "$range nm by $step: channels $expected (got $channels)"
  rm -f s.exr case.err
done
finish
