#!/usr/bin/env bash
# Two outputs of one run that are one file, however named, are refused
# before any work: exit 2, one line naming both, no file touched (a later
# failed write would otherwise delete the earlier output). Outputs that are
# different files are written.
# Usage: test_output_aliases.sh OPAL_RENDER OPAL_VOLUME WORK_DIR
source "$(dirname "$0")/output_test_support.sh"

echo old >a.png && echo old >v.vti && mkdir sub
ln -s a.png link.png       # a symbolic link to an existing file
ln -s new.png dangling.png # one to a file the run would write first
ln -s . here               # one to the folder
ln -s a.png image.vti      # one with the other flag's extension
ln a.png hard.png          # hard links: one file, two names
ln a.png hard.vti

# program | exit status | what the one line says (empty: written) | arguments
cases=(
  "render|2|-o a.png and -o a.png|-o a.png -o a.png"
  "render|2|-o a.png and -o ./a.png|-o a.png -o ./a.png"
  "render|2|-o a.png and -o sub/../a.png|-o a.png -o sub/../a.png"
  "render|2|-o a.png and -o $PWD/a.png|-o a.png -o $PWD/a.png"
  "render|2|-o a.png and -o link.png|-o a.png -o link.png"
  "render|2|-o new.png and -o dangling.png|-o new.png -o dangling.png"
  "render|2|-o a.png and -o here/a.png|-o a.png -o here/a.png"
  "render|2|-o hard.png and -o a.png|-o hard.png -o a.png"
  "render|2|-o b.exr and -o ./b.exr|-o b.png -o b.exr -o ./b.exr"
  "render|2|--save-image v.vti and --save-volume v.vti|-o b.png --save-image v.vti --save-volume v.vti"
  "render|2|-o a.png and --save-image image.vti|-o a.png --save-image image.vti"
  "render|2|-o a.png and --save-volume hard.vti|-o a.png --save-volume hard.vti"
  "render|2|--save-image here/v.vti and --save-volume v.vti|--save-image here/v.vti --save-volume v.vti"
  "volume|2|--output|-o v.vti -o ./v.vti"
  "render|0||-o c.png -o sub/c.png -o c.exr --save-image c.vti"
)
for row in "${cases[@]}"; do
  IFS='|' read -r program expected words arguments <<<"$row"
  read -r -a outputs <<<"$arguments"
  before=$(folder_state)
  if [[ $program == render ]]; then
    "$render" "${small[@]}" "${outputs[@]}" >case.out 2>case.err
  else
    "$volume" --dimensions 40 20 50 --domain-count 30 "${outputs[@]}" >case.out 2>case.err
  fi
  status=$?
  [[ $status == "$expected" ]] || fail "$arguments: exit $expected (got $status: $(cat case.err))"
  if [[ $expected == 2 ]]; then
    [[ $(wc -l <case.err) == 1 ]] || fail "$arguments: one line on stderr, got: $(cat case.err)"
    grep -qF -- "$words" case.err || fail "$arguments: the line names '$words': $(cat case.err)"
    [[ ! -s case.out ]] || fail "$arguments: refused before any work, yet printed: $(cat case.out)"
    rm -f case.out case.err
    [[ $(folder_state) == "$before" ]] || fail "$arguments: no file is touched"
  else
    for f in c.png sub/c.png c.exr c.vti; do [[ -s $f ]] || fail "$arguments: $f is written"; done
  fi
  rm -f case.out case.err
done
[[ $(cat a.png) == old && $(cat v.vti) == old && ! -e new.png ]] || fail "the aliased files keep their contents"
[[ -z $(leftovers) ]] || fail "no temporary or earlier copies are left: $(leftovers)"
finish
