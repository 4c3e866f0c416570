#!/usr/bin/env bash
# Temporary files and the earlier contents kept aside cannot be hijacked in
# a shared folder: their names are unpredictable and created exclusively, so
# a symbolic link planted under a name the program could have used is never
# written through, and a file of that name is never changed or deleted.
# The names were once .NAME.partial-PID.EXT and .NAME.earlier-PID.EXT: each
# case plants one of them for the run's own PID (exec keeps the shell's).
# Usage: test_temporary_files.sh OPAL_RENDER OPAL_VOLUME WORK_DIR
source "$(dirname "$0")/output_test_support.sh"

# Plants a link to victim (or a file) under the template's name with PID
# replaced by the run's PID, then runs the command in its place.
plant_and_run() {
  bash -c 'name=${1//PID/$$}; if [[ $0 == link ]]; then ln -s victim "$name"; else echo planted >"$name"; fi
    shift; exec "$@"' "$@"
}

# what to plant | its name | file-size limit in KB (none) | the outputs
cases=(
  "link|.out.partial-PID.png|none|-o out.png"
  "file|.out.partial-PID.png|none|-o out.png"
  "link|.out.earlier-PID.png|none|-o out.png"
  "file|.out.earlier-PID.png|none|-o out.png"
  "link|.out.partial-PID.jpg|none|-o out.jpg"
  "link|.out.partial-PID.exr|none|-o out.exr"
  "link|.out.partial-PID.vti|none|--save-image out.vti"
  "link|.out.earlier-PID.vti|none|-o first.png --save-volume out.vti"
  "file|.out.partial-PID.exr|4|-o first.png -o out.exr"
  "file|.first.earlier-PID.png|4|-o first.png -o out.exr"
)
for row in "${cases[@]}"; do
  IFS='|' read -r what template limit arguments <<<"$row"
  read -r -a outputs <<<"$arguments"
  target=${outputs[-1]}
  echo victim >victim && echo old >"$target" && echo old >first.png
  (
    [[ $limit == none ]] || ulimit -f "$limit"
    plant_and_run "$what" "$template" "$render" "${uniform[@]}" "${outputs[@]}" >case.out 2>case.err
  )
  status=$?
  pattern=${template//PID/[0-9]*}
  planted=$(compgen -G "$pattern")
  [[ $(cat victim) == victim ]] || fail "$what at $template ($arguments): the planted link is not written through"
  if [[ $what == link ]]; then
    [[ -L $planted && $(readlink "$planted") == victim ]] || fail "$what at $template ($arguments): the link stays"
  else
    [[ -f $planted && $(cat "$planted") == planted ]] || fail "$what at $template ($arguments): the file stays unchanged"
  fi
  if [[ $limit == none ]]; then
    [[ $status == 0 ]] || fail "$what at $template ($arguments): written (got $status: $(cat case.err))"
    [[ -f $target && ! -L $target && $(head -c 3 "$target") != old ]] || fail "$arguments: $target is the new file"
  else
    [[ $status == 1 && $(cat first.png) == old && $(cat "$target") == old ]] ||
      fail "$what at $template ($arguments): the failed set keeps its earlier files (got $status)"
  fi
  rm -f "$planted" victim case.out case.err
  [[ -z $(leftovers) ]] || fail "$what at $template ($arguments): nothing else is left: $(leftovers)"
  rm -f "$target" first.png
done

# The names themselves, where strace can watch: created with O_EXCL under 12
# random letters or digits, and different in each run.
if strace -f -o /dev/null true 2>/dev/null; then
  names=()
  for run in 1 2; do
    echo old >out.png
    strace -f -e trace=openat,link -o trace.txt "$render" "${small[@]}" -o out.png >/dev/null 2>&1
    grep -qE 'openat\(.*"(\./)?\.out\.partial-[A-Za-z0-9]{12}\.png", O_RDWR\|O_CREAT\|O_EXCL' trace.txt ||
      fail "the temporary file is created exclusively under an unpredictable name: $(grep partial trace.txt)"
    grep -qE 'link\("out\.png", "(\./)?\.out\.earlier-[A-Za-z0-9]{12}\.png"\) = 0' trace.txt ||
      fail "the earlier contents are linked under an unpredictable name: $(grep earlier trace.txt)"
    names+=("$(grep -oE '\.out\.(partial|earlier)-[A-Za-z0-9]{12}' trace.txt | sort -u)")
  done
  [[ ${names[0]} != "${names[1]}" ]] || fail "each run has names of its own"
  rm -f trace.txt out.png
else
  echo "strace cannot trace here: the names' form is not checked"
fi
finish
