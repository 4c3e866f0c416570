# What the output-file tests share (sourced): their arguments, a fresh work
# folder, the failure count, the images they render and a skip where there is
# no Vulkan device. Arguments: OPAL_RENDER OPAL_VOLUME WORK_DIR.
set -u
render=$1 volume=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAILED: $*"; failures=$((failures + 1)); }
finish() {
  echo "$(basename "$0"): $failures failure(s)"
  [[ $failures == 0 ]]
}

# A 64 x 48 render of a small stone (about a second on lavapipe).
small=(--dimensions 40 20 50 --domain-count 30 --width 64 --height 48)
# The camera turned away from the stone: one colour, so the formats' sizes
# order them for a file-size limit: PNG ~1.4 KB, TIFF ~2.2, JPEG ~3.7,
# EXR ~9, the image .vti ~97 (512 x 384, well under a second).
uniform=(--dimensions 40 20 50 --domain-count 30 --width 512 --height 384 --focal-point 0 200 0 --background 0.3 0.5 0.7)
# The stone at 128 x 96: here JPEG (~4.7 KB) is smaller than PNG (~8.9 KB).
stone=(--dimensions 40 20 50 --domain-count 30 --width 128 --height 96)

# Temporary files and earlier contents kept aside, if any are left.
leftovers() { ls -A | grep -e partial -e earlier; }

# Every entry of the folder: kind, name, link target and contents' checksum.
folder_state() {
  find . -mindepth 1 -printf '%y %p %l\n' | sort
  find . -type f -exec md5sum {} + | sort
}

"$render" "${small[@]}" -o probe.png >/dev/null 2>probe.err
if grep -q "No Vulkan device" probe.err; then
  # In CI (CI=true) lavapipe is installed and every Vulkan test must run.
  if [[ "${CI:-}" == true ]]; then echo "FAILED: no Vulkan device in CI"; exit 1; fi
  echo "SKIPPED: no Vulkan device"; exit 77
fi
rm -f probe.png probe.err
