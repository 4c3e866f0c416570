#!/usr/bin/env bash
# A failed write says its true cause, taken from the failing step: a folder
# that is a file, that does not exist or that may not be written, a file
# that may not be replaced, a file-size limit. "The disk is full" only when
# it is. Each case: exit 1, one line "could not write PATH: CAUSE".
# Usage: test_write_messages.sh OPAL_RENDER OPAL_VOLUME WORK_DIR
source "$(dirname "$0")/output_test_support.sh"

touch afile && mkdir readonly && chmod 555 readonly && echo old >locked.png && chmod 444 locked.png
# program | file-size limit in KB (none) | the output flag and path | the cause the line gives
cases=(
  "render|none|-o afile/x.png|its folder afile is not a folder"
  "render|none|-o $PWD/afile/x.exr|its folder $PWD/afile is not a folder"
  "render|none|-o afile/deeper/x.jpg|its folder afile/deeper cannot exist: a part of its path is a file"
  "render|none|-o no/such/x.tif|its folder no/such does not exist"
  "render|none|--save-image afile/x.vti|its folder afile is not a folder"
  "render|none|-o x.png --save-volume no/such/x.vti|its folder no/such does not exist"
  "volume|none|-o afile/x.vti|its folder afile is not a folder"
  "render|2|-o big.exr|the file would be larger than the file-size limit of 2048 bytes"
  "volume|8|-o big.vti|the file would be larger than the file-size limit of 8192 bytes"
)
# The superuser may write anywhere: permissions are checked for others only.
if [[ $(id -u) != 0 ]]; then
  cases+=(
    "render|none|-o readonly/x.png|permission denied in its folder readonly"
    "render|none|-o locked.png|permission denied"
  )
fi
for row in "${cases[@]}"; do
  IFS='|' read -r program limit output cause <<<"$row"
  read -r -a flag_and_path <<<"$output"
  path=${flag_and_path[-1]}
  (
    [[ $limit == none ]] || ulimit -f "$limit"
    if [[ $program == render ]]; then
      "$render" "${small[@]}" "${flag_and_path[@]}" >case.out 2>case.err
    else
      "$volume" --dimensions 40 20 50 --domain-count 30 "${flag_and_path[@]}" >case.out 2>case.err
    fi
  )
  status=$?
  [[ $status == 1 ]] || fail "$output: exit 1 (got $status: $(cat case.err))"
  [[ $(wc -l <case.err) == 1 ]] || fail "$output: one line on stderr, got: $(cat case.err)"
  grep -qF -- "opal-$program: could not write $path: $cause" case.err || fail "$output: the line says '$cause': $(cat case.err)"
  grep -q "disk is full" case.err && fail "$output: the disk is not said to be full"
  rm -f case.out case.err
done
[[ $(cat locked.png) == old && -z $(ls -A readonly) ]] || fail "nothing is written where it may not be"
[[ -z $(leftovers) && ! -e big.exr && ! -e big.vti ]] || fail "no file is left behind: $(ls -A)"
chmod 755 readonly
finish
