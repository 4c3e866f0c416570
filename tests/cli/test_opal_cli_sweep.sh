#!/bin/bash
# Every numeric flag of both programs, taken from their --help, through
# hostile values (NaN, +-Inf, 0, -1, the largest double, the smallest
# denormal, 1e9): each run is refused before any work (exit 2, one line on
# stderr naming the flag or its parameter) or writes a finite image (exit 0; the render refuses a NaN or an
# infinity in any output itself). Never a crash (exit >= 128), a hang (the
# 30 s timeout) or a failure after the work started.
# Usage: test_opal_cli_sweep.sh OPAL_RENDER OPAL_VOLUME WORK_FOLDER
render=$1 volume=$2 work=$3
mkdir -p "$work" && cd "$work" || exit 1
failures=0
values=(nan inf -inf 0 -1 1.7976931348623157e308 4.9e-324 1e9)

# sweep PROGRAM OUTPUT BASE_ARGS...: every numeric flag of PROGRAM's --help through every value.
sweep() {
  local program=$1 output=$2; shift 2
  local flag type x count v
  "$program" --help | grep -oE "^\s+--[a-z-]+ (FLOAT|INT|UINT)( x [0-9])?" | sed 's/^ *//' >flags.txt
  [[ -s flags.txt ]] || { echo "FAILED: no numeric flags found in $program --help"; failures=$((failures + 1)); }
  while read -r flag type x count; do
    for v in "${values[@]}"; do
      local args=()
      for ((i = 0; i < ${count:-1}; i++)); do args+=("$v"); done
      timeout 30 "$program" "$@" "$flag" "${args[@]}" -o "$output" >out.txt 2>err.txt
      local status=$?
      [[ $status == 0 ]] && continue
      # Refused: one line naming the flag or its parameter (--light-radius: LightRadius).
      local parameter
      parameter=$(echo "${flag#--}" | sed -E 's/(^|-)([a-z])/\U\2/g')
      [[ $status == 2 && $(wc -l <err.txt) == 1 ]] && grep -q -e "$flag" -e "$parameter" err.txt && continue
      echo "FAILED: $(basename "$program") $flag ${args[*]}: exit $status: $(head -c 300 err.txt | tr '\n' ' ')"
      failures=$((failures + 1))
    done
  done <flags.txt
}

sweep "$render" out.png --dimensions 20 10 25 --domain-count 5 --width 16 --height 12
sweep "$volume" out.vti --dimensions 20 10 25 --domain-count 5
echo "test_opal_cli_sweep: $failures failure(s)"
[[ $failures == 0 ]]
