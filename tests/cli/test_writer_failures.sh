#!/usr/bin/env bash
# No writer ends the process mid-write: under a file-size limit (writes fail
# with EFBIG, as on a full disk) each format's failure comes back as an error.
# Per format, the first output fits and is written, the second does not: exit
# 1 naming the second and the limit, both files keep their earlier contents
# (the first is restored), and no temporary or earlier copy is left behind.
# libjpeg's default handler called exit() here, leaving the first replaced.
# Usage: test_writer_failures.sh OPAL_RENDER OPAL_VOLUME WORK_DIR
source "$(dirname "$0")/output_test_support.sh"

# limit in KB | image | the outputs, the failing one last
cases=(
  "2|uniform|-o first.png -o second.tif"
  "2|uniform|-o first.png -o second.tiff"
  "3|uniform|-o first.png -o second.jpg"
  "3|uniform|-o first.png -o second.jpeg"
  "4|uniform|-o first.png -o second.exr"
  "8|uniform|-o first.png --save-image second.vti"
  "8|uniform|-o first.png --save-volume second.vti"
  "6|stone|-o first.jpg -o second.png"
  "8|volume|-o second.vti"
)
# Runs the row's program on its image under the limit; stdout and stderr to case.out, case.err.
run_limited() {
  local limit=$1 image=$2; shift 2
  if [[ $image == volume ]]; then
    (ulimit -f "$limit"; "$volume" --dimensions 40 20 50 --domain-count 30 "$@" >case.out 2>case.err)
  else
    local -n pixels=$image
    (ulimit -f "$limit"; "$render" "${pixels[@]}" "$@" >case.out 2>case.err)
  fi
}
for row in "${cases[@]}"; do
  IFS='|' read -r limit image arguments <<<"$row"
  read -r -a outputs <<<"$arguments"
  first=${outputs[1]} second=${outputs[-1]}
  echo old >"$first" && echo old >"$second"
  before=$(folder_state)
  run_limited "$limit" "$image" "${outputs[@]}"
  status=$?
  [[ $status == 1 ]] || fail "$arguments under ${limit} KB: exit 1 (got $status: $(cat case.err))"
  grep -q "could not write $second: the file would be larger than the file-size limit of $((limit * 1024)) bytes" \
    case.err || fail "$arguments under ${limit} KB: the error names $second and the limit: $(cat case.err)"
  rm -f case.out case.err
  [[ $(cat "$first") == old && $(cat "$second") == old ]] || fail "$arguments: both files keep their earlier contents"
  [[ $(folder_state) == "$before" ]] || fail "$arguments: no file is left behind: $(leftovers)"
  rm -f "$first" "$second"
done
finish
