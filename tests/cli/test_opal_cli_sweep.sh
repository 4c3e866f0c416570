#!/bin/bash
# Every numeric flag of both programs, taken from their --help, through
# hostile values (NaN, +-Inf, 0, -1, the largest double, the smallest
# denormal, 1e9): each run is refused before any work (exit 2, one line on
# stderr naming the flag or its parameter) or writes a finite image (exit 0; the render refuses a NaN or an
# infinity in any output itself). Never a crash (exit >= 128), a hang (the
# 30 s timeout) or a failure after the work started.
# Two runs at a time, each in a folder of its own: a run is one thread for
# most of its time (the device's set-up), and the machine has two cores.
# Usage: test_opal_cli_sweep.sh OPAL_RENDER OPAL_VOLUME WORK_FOLDER
render=$1 volume=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
values=(nan inf -inf 0 -1 1.7976931348623157e308 4.9e-324 1e9)
runs=0

# check FOLDER PROGRAM OUTPUT FLAG VALUE... -- BASE_ARGS...: one run; writes
# FOLDER/failure when it is neither a clean refusal nor a written image.
check() {
  local folder=$1 program=$2 output=$3 flag=$4; shift 4
  local args=()
  while [[ $1 != -- ]]; do args+=("$1"); shift; done
  shift
  mkdir -p "$folder" && cd "$folder" || return
  timeout 30 "$program" "$@" "$flag" "${args[@]}" -o "$output" >out.txt 2>err.txt
  local status=$?
  [[ $status == 0 ]] && return
  # Refused: one line naming the flag or its parameter (--light-radius: LightRadius).
  local parameter
  parameter=$(echo "${flag#--}" | sed -E 's/(^|-)([a-z])/\U\2/g')
  [[ $status == 2 && $(wc -l <err.txt) == 1 ]] && grep -q -e "$flag" -e "$parameter" err.txt && return
  echo "FAILED: $(basename "$program") $flag ${args[*]}: exit $status: $(head -c 300 err.txt | tr '\n' ' ')" >failure
}

# sweep PROGRAM OUTPUT BASE_ARGS...: every numeric flag of PROGRAM's --help through every value.
sweep() {
  local program=$1 output=$2; shift 2
  local flags flag type x count v
  flags="flags-$(basename "$program").txt"
  "$program" --help | grep -oE "^\s+--[a-z-]+ (FLOAT|INT|UINT)( x [0-9])?" | sed 's/^ *//' >"$flags"
  [[ -s $flags ]] || echo "FAILED: no numeric flags found in $program --help" >"no-flags-$(basename "$program")"
  while read -r flag type x count; do
    for v in "${values[@]}"; do
      local args=()
      for ((i = 0; i < ${count:-1}; i++)); do args+=("$v"); done
      while (($(jobs -rp | wc -l) >= 2)); do wait -n; done
      check "run-$runs" "$program" "$output" "$flag" "${args[@]}" -- "$@" &
      runs=$((runs + 1))
    done
  done <"$flags"
}

sweep "$render" out.png --dimensions 20 10 25 --domain-count 5 --width 16 --height 12
sweep "$volume" out.vti --dimensions 20 10 25 --domain-count 5
wait
cat run-*/failure no-flags-* 2>/dev/null
failures=$(cat run-*/failure no-flags-* 2>/dev/null | wc -l)
echo "test_opal_cli_sweep: $runs runs, $failures failure(s)"
[[ $failures == 0 ]]
