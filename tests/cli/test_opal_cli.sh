#!/usr/bin/env bash
# The command-line programs: success writes readable PNG / EXR / VTI files and
# exits 0; each bad argument costs exactly one line and a non-zero exit;
# a failed run never replaces an earlier file or leaves a partial one.
# Usage: test_opal_cli.sh OPAL_RENDER OPAL_VOLUME WORK_DIR
set -u
render=$1 volume=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAILED: $*"; failures=$((failures + 1)); }
small=(--dimensions 40 20 50 --domain-count 30 --width 64 --height 48)

# Renders, or skips where there is no Vulkan device at all.
"$render" "${small[@]}" -o ok.png -o ok.exr --save-image image.vti --save-volume volume.vti >out.txt 2>err.txt
status=$?
if grep -q "No Vulkan device" err.txt; then
  # In CI (CI=true) lavapipe is installed and every Vulkan test must run.
  if [[ "${CI:-}" == true ]]; then echo "FAILED: no Vulkan device in CI"; exit 1; fi
  echo "SKIPPED: no Vulkan device"; exit 77
fi
[[ $status == 0 ]] || fail "a good render exits 0 (got $status: $(cat err.txt))"
for f in ok.png ok.exr image.vti volume.vti; do [[ -s $f ]] || fail "$f written"; done
grep -q "written: ok.png" out.txt || fail "it prints where the PNG is"
oiiotool --info -v ok.png | grep -q "64 x   48, 3 channel, uint8" || fail "ok.png is 64 x 48 RGB 8-bit: $(oiiotool --info ok.png)"
oiiotool --info -v ok.exr | grep -q "64 x   48, 3 channel, .*float" || fail "ok.exr is 64 x 48 RGB float: $(oiiotool --info ok.exr)"

"$render" "${small[@]}" --exr-spectral-channels -o spectral.exr >/dev/null 2>&1 || fail "spectral EXR render"
oiiotool --info -v spectral.exr | grep -q "44 channel" || fail "spectral.exr has RGB + 41 wavelength channels"

"$volume" --dimensions 40 20 50 --domain-count 30 -o v.vti >v.txt 2>&1 || fail "opal-volume exits 0"
grep -q "domains placed   30 of 30" v.txt || fail "opal-volume prints its summary"
# A partitioned volume: the summary and its pieces, built piece by piece, count what the one file holds.
"$volume" --dimensions 40 20 50 --domain-count 30 -o v.pvti --pieces 3 >p.txt 2>&1 || fail "opal-volume .pvti exits 0"
for f in v.pvti v_0.vti v_1.vti v_2.vti; do [[ -s $f ]] || fail "$f written"; done
[[ -z $(find . -maxdepth 1 -name '.v.pvti-*') ]] || fail "the .pvti's staging folder is removed"
grep -q "(3 pieces)" p.txt || fail "opal-volume says it wrote 3 pieces: $(cat p.txt)"
# Written again over the set: each piece is renamed into place (a new file, not
# the old one rewritten: a hard link to the old piece keeps the old contents),
# keeping a piece's permissions and writing through a link to another file
# system (/dev/shm where it is one: copied there).
ln v_0.vti old_0.vti && chmod 640 v_1.vti
shm=$(mktemp -p /dev/shm opal-piece-XXXXXX.vti 2>/dev/null || mktemp --suffix .vti)
mv v_2.vti "$shm" && ln -s "$shm" v_2.vti && linked_before=$(md5sum <"$shm")
"$volume" --dimensions 40 20 50 --domain-count 31 -o v.pvti --pieces 3 >/dev/null 2>&1 || fail "opal-volume .pvti again exits 0"
[[ $(stat -c %i v_0.vti) != $(stat -c %i old_0.vti) ]] || fail "a piece written again is a new file, renamed into place"
cmp -s v_0.vti old_0.vti && fail "the piece written again holds the new volume"
[[ $(stat -c %a v_1.vti) == 640 ]] || fail "a piece written again keeps its permissions (got $(stat -c %a v_1.vti))"
[[ -L v_2.vti && $(md5sum <"$shm") != "$linked_before" ]] && grep -q "</VTKFile>" "$shm" ||
  fail "a piece that is a link is written through it"
rm -f "$shm" old_0.vti v_2.vti
# Fewer pieces than the earlier set: its extra piece goes, a file the summary
# does not name stays.
"$volume" --dimensions 40 20 50 --domain-count 30 -o v.pvti --pieces 3 >/dev/null 2>&1 && touch v_9.vti &&
  "$volume" --dimensions 40 20 50 --domain-count 30 -o v.pvti --pieces 2 >/dev/null 2>&1 || fail "opal-volume .pvti 3 then 2 pieces"
[[ -s v_0.vti && -s v_1.vti && ! -e v_2.vti && -e v_9.vti ]] || fail "the earlier set's third piece is removed, v_9.vti kept: $(ls v_*)"
[[ $(grep -c "<Piece" v.pvti) == 2 ]] || fail "the summary names 2 pieces"
rm -f v_9.vti
[[ $(grep -E "^  (empty|scattering|diffraction) " p.txt) == $(grep -E "^  (empty|scattering|diffraction) " v.txt) ]] ||
  fail "the pieces' voxel counts equal the one file's: $(cat p.txt v.txt)"
# The render's arrays only: a smaller set of pieces, with just those arrays, that counts no voxel types.
"$volume" --dimensions 40 20 50 --domain-count 30 --arrays render -o r.pvti --pieces 3 >r.txt 2>&1 ||
  fail "opal-volume --arrays render exits 0"
grep -q "the render's only" r.txt || fail "opal-volume --arrays render says what it wrote: $(cat r.txt)"
[[ $(grep -o 'Name="[A-Za-z]*"' r_1.vti | sort -u | tr '\n' ' ') == *DomainId*ScatteringCoefficient*SurfaceDistance* &&
  ! $(grep -c 'Name="VoxelType"' r_1.vti) -gt 0 && $(stat -c %s r_1.vti) -lt $(stat -c %s v_1.vti) ]] ||
  fail "a render-only piece holds the render's arrays, no VoxelType, and is smaller"
expect_one_line "unknown --arrays" "--arrays" "$volume" --dimensions 40 20 50 --arrays some -o x.vti
# Voronoi grains: a preset sets the layout; a flag given with it wins over its value.
"$volume" --dimensions 40 20 50 --preset pinfire -o grains.vti >g.txt 2>&1 || fail "opal-volume --preset pinfire exits 0"
grep -q "voronoi cells    3000, 360 ordered" g.txt || fail "pinfire: 3000 cells, 12% ordered: $(cat g.txt)"
"$volume" --dimensions 40 20 50 --preset pinfire --voronoi-cell-count 100 --ordered-fraction 0.5 -o grains.vti >g.txt 2>&1 ||
  fail "opal-volume with pinfire overridden exits 0"
grep -q "voronoi cells    100, 50 ordered" g.txt || fail "flags win over the preset: $(cat g.txt)"
grep -q "preset custom" g.txt || fail "an overridden preset is recorded as custom: $(cat g.txt)"

# Absorption, a backing and domain scattering: a render and a volume with the arrays.
"$render" "${small[@]}" --body-absorption 0.3 --body-absorption-exponent 4 --backing-thickness 2 --backing-absorption 5 \
  --domain-scattering-coefficient 0.5 --save-volume absorbing.vti -o absorbing.png >/dev/null 2>&1 || fail "an absorbing render exits 0"
grep -q 'Name="AbsorptionCoefficient"' absorbing.vti || fail "the absorbing volume carries AbsorptionCoefficient"

# The coupled-wave model with every lattice plane family (docs/design.md §7.2).
"$render" "${small[@]}" --bragg-model coupled-wave --lattice-planes fcc --coherent-layers 100 --mosaic-spread 4 \
  --sphere-refractive-index 1.45 --matrix-refractive-index 1.0 -o coupled.png >/dev/null 2>&1 \
  || fail "a coupled-wave render with fcc planes exits 0"
# A kind of opal sets the coupled-wave model and fcc planes (docs/design.md §2.11); the flag wins.
"$render" "${small[@]}" --preset black-opal -o black.png >/dev/null 2>&1 || fail "a black-opal render exits 0"
"$render" "${small[@]}" --preset black-opal --bragg-model coupled-wave --lattice-planes fcc -o black-cw.png \
  >/dev/null 2>&1 || fail "black-opal with its Bragg model named exits 0"
"$render" "${small[@]}" --preset black-opal --bragg-model paper --lattice-planes 111 -o black-paper.png \
  >/dev/null 2>&1 || fail "black-opal with the paper's Bragg model exits 0"
cmp -s black.png black-cw.png || fail "black-opal renders with the coupled-wave model and fcc planes"
cmp -s black.png black-paper.png && fail "a --bragg-model given wins over the preset's"

# Each bad argument: one line on stderr, non-zero exit, nothing written.
expect_one_line() {
  local name=$1 pattern=$2; shift 2
  "$@" >bad.out 2>bad.err
  local status=$?
  status_of_last=$status
  [[ $status != 0 ]] || fail "$name: exits non-zero"
  [[ $(wc -l <bad.err) == 1 ]] || fail "$name: one line on stderr, got: $(cat bad.err)"
  grep -q -- "$pattern" bad.err || fail "$name: the line names $pattern: $(cat bad.err)"
}
expect_one_line "zero width" "ImageSize" "$render" --dimensions 40 20 50 --width 0 -o x.png
expect_one_line "non-numeric width" "--width" "$render" --width abc -o x.png
expect_one_line "unknown preset" "--preset" "$render" --preset fig99 -o x.png
expect_one_line "zero wavelength step" "WavelengthStep" "$render" "${small[@]}" --wavelength-step 0 -o x.png
expect_one_line "volume fraction 0.9" "ScatteringVolumeFraction" "$render" "${small[@]}" --scattering-volume-fraction 0.9 -o x.png
expect_one_line "three vertex values" "--domain-vertex-range" "$render" --domain-vertex-range 3 4 5 -o x.png
expect_one_line "nothing to write" "nothing to write" "$render" "${small[@]}"
expect_one_line "opal-volume bad dimensions" "Dimensions" "$volume" --dimensions 0 20 50 -o x.vti
expect_one_line "unknown layout" "--domain-layout" "$volume" --domain-layout hexagons -o x.vti
expect_one_line "ordered fraction 2" "OrderedFraction" "$volume" --domain-layout voronoi --ordered-fraction 2 -o x.vti
expect_one_line "no Voronoi cells" "VoronoiCellCount" "$render" "${small[@]}" --voronoi-cell-count 0 -o x.png
expect_one_line "negative correlation length" "DiameterCorrelationLength" "$volume" --diameter-correlation-length -1 -o x.vti
expect_one_line "negative body absorption" "BodyAbsorption" "$render" "${small[@]}" --body-absorption -0.5 -o x.png
expect_one_line "NaN absorption exponent" "BodyAbsorptionExponent" "$volume" --body-absorption-exponent nan -o x.vti
expect_one_line "backing thicker than the box" "BackingThickness" "$volume" --backing-thickness 9 -o x.vti
expect_one_line "negative backing absorption" "BackingAbsorption" "$volume" --backing-absorption -1 -o x.vti
expect_one_line "negative domain scattering" "DomainScatteringCoefficient" "$render" "${small[@]}" --domain-scattering-coefficient -1 -o x.png
expect_one_line "unknown Bragg model" "--bragg-model" "$render" "${small[@]}" --bragg-model sinc -o x.png
expect_one_line "fcc with the paper's model" "LatticePlanes" "$render" "${small[@]}" --lattice-planes fcc -o x.png
expect_one_line "no coherent layers" "CoherentLayers" "$render" "${small[@]}" --bragg-model coupled-wave --coherent-layers 0 -o x.png
expect_one_line "sphere index below 1" "SphereRefractiveIndex" "$volume" --sphere-refractive-index 0.5 -o x.vti
expect_one_line "width beyond an int" "ImageSize must lie in .0, 16384" "$render" --width 99999999999 -o x.png
expect_one_line "negative seed" "Seed must lie in .0, 2147483647" "$render" --seed -1 -o x.png
# Enough digits to tell the value from the bound; one refractive-index rule for volume and render.
expect_one_line "volume fraction just past 0.74" "got 0.7400001" "$volume" --scattering-volume-fraction 0.7400001 -o x.vti
expect_one_line "volume's refractive index 5" "RefractiveIndex must lie in .1, 4)" "$volume" --refractive-index 5 -o x.vti
expect_one_line "render's refractive index 5" "RefractiveIndex must lie in .1, 4)" "$render" "${small[@]}" --refractive-index 5 -o x.png
# A volume beyond this machine's memory: refused before any work, one line, exit 2.
expect_one_line "pieces of one .vti" "--pieces" "$volume" --dimensions 40 20 50 --pieces 3 -o x.vti
expect_one_line "no pieces" "--pieces" "$volume" --dimensions 40 20 50 --pieces 0 -o x.pvti
expect_one_line "a .pvti piece beyond memory" "A piece of" "$volume" --dimensions 4000 4000 4000 --pieces 4 -o x.pvti
expect_one_line ".pvti in a missing folder" "could not write" "$volume" --dimensions 40 20 50 -o missing/x.pvti
expect_one_line "opal-volume beyond memory" "memory" "$volume" --dimensions 4000 4000 4000 -o x.vti
[[ $status_of_last == 2 ]] || fail "a volume beyond memory exits 2 (got $status_of_last)"
expect_one_line "opal-render beyond memory" "memory" "$render" --dimensions 4000 4000 4000 -o x.png
# white-opal's fields with every order (32 bytes per voxel: the volume's unpaired, energy conservation's
# Bragg shadows, and the every-order tally grid; pairs, 12 more, and the field per voxel, 16 more, only
# where they fit) beyond the device's memory: refused once the device has started, not after the
# volume's build and upload (the frame's own refusal says "the render needs").
expect_one_line "white-opal's fields beyond the device's memory" "the volume's fields for this render need about 627 MB" \
  "$render" --preset white-opal --dimensions 320 160 400 --device-memory-limit 500 -o x.png
# Counts bounded where they hung or ran out of memory.
expect_one_line "two billion domains" "DomainCount" "$volume" --domain-count 2000000000 -o x.vti
expect_one_line "two billion vertices" "DomainVertexRange" "$volume" --domain-vertex-range 3 2000000000 -o x.vti
# Settings bounded where they overflowed.
expect_one_line "infinite light radius" "LightRadius" "$render" "${small[@]}" --light-radius inf -o x.png
expect_one_line "wavelength step 1e-7" "WavelengthStep" "$render" "${small[@]}" --wavelength-step 1e-7 -o x.png
expect_one_line "diffraction gain 1e300" "DiffractionGain" "$render" "${small[@]}" --diffraction-gain 1e300 -o x.png
[[ $status_of_last == 2 ]] || fail "a bad argument exits 2 (got $status_of_last)"
expect_one_line "memory limit not a number" "OPAL_VULKAN_MEMORY_LIMIT_MB" env OPAL_VULKAN_MEMORY_LIMIT_MB=abc "$render" "${small[@]}" -o x.png
[[ ! -e x.png && ! -e x.vti ]] || fail "bad arguments write nothing"

# A failing render leaves an earlier image untouched and no partial file.
cp ok.png keep.png
"$render" "${small[@]}" --light-position 0 2 0 -o keep.png >/dev/null 2>bad.err && fail "a light inside the opal fails"
grep -q "LightPosition" bad.err || fail "the light-inside error names LightPosition: $(cat bad.err)"
cmp -s ok.png keep.png || fail "the earlier keep.png is untouched"
"$render" "${small[@]}" -o no/such/folder/x.png >/dev/null 2>bad.err && fail "an unwritable path fails"
grep -q "could not write" bad.err || fail "an unwritable path says so: $(cat bad.err)"
ls -a | grep -q partial && fail "no partial files are left behind"

# A full disk (simulated by a file-size limit of 8 KB): a clear error, the
# earlier file kept, no partial file.
cp ok.exr keep.exr
( ulimit -f 8; "$render" "${small[@]}" -o keep.exr >/dev/null 2>bad.err ) && fail "a full disk fails the write"
grep -q "could not write keep.exr" bad.err || fail "a full disk says so: $(cat bad.err)"
cmp -s ok.exr keep.exr || fail "the earlier keep.exr is untouched by the failed write"
ls -a | grep -q partial && fail "no partial file after a full disk"

# The outputs of one run are all or none: the third cannot be written, so
# the first two keep their earlier contents, and no earlier copy is left over.
cp ok.png set.png
cp ok.exr set.exr
"$render" "${small[@]}" --light-position 0 40 5 -o set.png -o set.exr -o no/such/folder/set.png >/dev/null 2>bad.err &&
  fail "an output set with an unwritable member fails"
cmp -s ok.png set.png && cmp -s ok.exr set.exr || fail "a failed output set replaces none of its files"
"$render" "${small[@]}" --light-position 0 40 5 -o set.png -o set.exr >/dev/null 2>&1 || fail "a good output set is written"
cmp -s ok.png set.png && fail "a good output set replaces its files"
ls -a | grep -q -e partial -e earlier && fail "no partial or earlier copies are left behind"
# A signal at any moment (here SIGTERM after 0.2-1.4 s, through the volume,
# the render and the writing) leaves the set all old or all new, and no
# partial or earlier copy: signals are held while files are written.
for delay in 0.2 0.5 0.8 1.1 1.4; do
  cp ok.png sig.png && cp ok.exr sig.exr && echo old >sig.vti
  "$render" "${small[@]}" --light-position 0 40 5 -o sig.png -o sig.exr --save-image sig.vti >/dev/null 2>&1 &
  sleep "$delay"; kill -TERM $! 2>/dev/null; wait $! 2>/dev/null
  replaced=0
  cmp -s ok.png sig.png || replaced=$((replaced + 1))
  cmp -s ok.exr sig.exr || replaced=$((replaced + 1))
  [[ $(cat sig.vti 2>/dev/null) == old ]] || replaced=$((replaced + 1))
  [[ $replaced == 0 || $replaced == 3 ]] || fail "a signal after ${delay} s left a mixed set ($replaced of 3 replaced)"
  ls -a | grep -q -e partial -e earlier && fail "a signal after ${delay} s left a partial or earlier copy"
done
# The target path's edge cases, as cp treats them: a symbolic link is written
# through (the link stays), an existing file keeps its permissions, a name
# near the 255-byte limit works.
cp ok.png real.png && ln -sf real.png link.png
"$render" "${small[@]}" --light-position 0 40 5 -o link.png >/dev/null 2>&1 || fail "writing through a link works"
[[ -L link.png ]] || fail "the symbolic link stays a link"
cmp -s ok.png real.png && fail "the file the link names is replaced"
cp ok.png private.png && chmod 600 private.png
"$render" "${small[@]}" --light-position 0 40 5 -o private.png >/dev/null 2>&1 || fail "replacing a private file works"
[[ $(stat -c %a private.png) == 600 ]] || fail "a replaced file keeps its permissions (got $(stat -c %a private.png))"
long=$(printf 'n%.0s' {1..246}).png
"$render" "${small[@]}" -o "$long" >/dev/null 2>bad.err || fail "a 250-byte name works: $(cat bad.err)"
[[ -s $long ]] || fail "the 250-byte name is written"
rm -f "$long"
ls -a | grep -q -e partial -e earlier && fail "no partial or earlier copies after the path cases"
# A name whose extension is not the option's format is refused before any work.
expect_one_line "--save-image as .png" "--save-image" "$render" "${small[@]}" --save-image img.png
expect_one_line "an unknown image extension" "b.xyz" "$render" "${small[@]}" -o a.png -o b.xyz
expect_one_line "opal-volume to .png" "--output" "$volume" --dimensions 40 20 50 -o vol.png
[[ ! -e img.png && ! -e a.png && ! -e vol.png ]] || fail "refused names write nothing"

# A full disk for every format and for a set: the earlier files kept (the
# whole set), no partial file. The 256 x 192 image is larger than the limit.
cp ok.png full.png && cp ok.exr full.exr && echo old >full.vti
for output in "-o full.png" "-o full.exr" "--save-image full.vti" "-o full.png -o full.exr --save-image full.vti"; do
  ( ulimit -f 8; "$render" --dimensions 40 20 50 --domain-count 30 --width 256 --height 192 $output >/dev/null 2>bad.err ) &&
    fail "a full disk fails $output"
  grep -q "could not write" bad.err || fail "a full disk says so for $output: $(cat bad.err)"
  cmp -s ok.png full.png && cmp -s ok.exr full.exr && [[ $(cat full.vti) == old ]] ||
    fail "a full disk leaves the earlier files for $output"
  ls -a | grep -q -e partial -e earlier && fail "no partial or earlier copy after a full disk for $output"
done
( ulimit -f 8; "$volume" --dimensions 80 40 100 -o full.vti >/dev/null 2>bad.err ) && fail "a full disk fails opal-volume"
[[ $(cat full.vti) == old ]] || fail "a full disk leaves opal-volume's earlier file"

"$render" --help >/dev/null || fail "--help exits 0"
echo "test_opal_cli: $failures failure(s)"
[[ $failures == 0 ]]
