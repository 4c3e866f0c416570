"""pvpython, opal-volume and opal-render: numbers are read strictly everywhere
(issue #32). One table of cases, each with its expected exit status and the
words its one line of stderr must hold:

- --seed: one range, [0, 2147483647], on the command line, in vtkOpalSource
  (ParaView's OpalVolume) and in the field data; an accepted seed is read
  back from the saved volume's field data as given (010 is ten, not octal
  eight), a refused one (4294967295, -1, 1e3, " 5", 0x10, ...) names Seed;
- the flags' other numbers (--width, --device, --rotate-x,
  --wavelength-step): decimal, the whole word, refused naming the parameter;
- the environment: OPAL_VULKAN_DEVICE (an index in digits naming a device,
  or part of a device's name; "99999999999999999999", "-1", " 0", "1x"
  refused naming it), OPAL_VULKAN_VALIDATION (0 or 1) and
  OPAL_VULKAN_MEMORY_LIMIT_MB (digits)."""
import os
import subprocess

from paraview import servermanager as sm
from paraview.simple import LoadPlugin
from vtkmodules.vtkCommonCore import vtkLogger, vtkOutputWindow
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import opal_test_config as config
from opal_test_support import check, child_environment, finish

output = os.path.join(config.OUTPUT_DIRECTORY, "numbers")
os.makedirs(output, exist_ok=True)
volume_path = os.path.join(output, "seed.vti")
image_path = os.path.join(output, "image.vti")
small = ["--dimensions", "20", "10", "20", "--domain-count", "3"]
render_small = small + ["--width", "16", "--height", "12", "--save-image", image_path, "-o",
                        os.path.join(output, "image.png")]


def field(path, name):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    array = reader.GetOutput().GetFieldData().GetAbstractArray(name)
    return array.GetVariantValue(0).ToString() if array else None


def run_case(what, command, environment, status, words):
    """Runs one case; checks its exit status and, when it fails, its one line naming `words`."""
    for path in (volume_path, image_path):
        if os.path.exists(path):
            os.remove(path)
    env = child_environment()
    env.update(environment)
    result = subprocess.run(command, env=env, capture_output=True, text=True, timeout=120)
    said = result.stderr.strip()
    check(result.returncode == status, f"{what}: exit {status} (got {result.returncode}: {said})")
    if status != 0:
        check(len(said.splitlines()) == 1 and all(w in said for w in words),
              f"{what}: one line naming {words} (got: {said})")
    return result.returncode == 0


# --seed: (value, exit status, what the refusal names or the seed read back)
SEEDS = [
    ("0", 0, "0"),
    ("1", 0, "1"),
    ("2147483647", 0, "2147483647"),
    ("010", 0, "10"),
    ("4294967295", 2, ["--seed", "Seed must lie in [0, 2147483647]", "4294967295"]),
    ("4294967296", 2, ["--seed", "Seed must lie in [0, 2147483647]", "4294967296"]),
    ("99999999999999999999", 2, ["--seed", "Seed must lie in [0, 2147483647]"]),
    ("-1", 2, ["--seed", "Seed must lie in [0, 2147483647]", "-1"]),
    ("1e3", 2, ["--seed", "Seed must be a whole number", "1e3"]),
    ("1.5", 2, ["--seed", "Seed must be a whole number"]),
    (" 5", 2, ["--seed", "Seed must be a whole number"]),
    ("+5", 2, ["--seed", "Seed must be a whole number"]),
    ("0x10", 2, ["--seed", "Seed must be a whole number"]),
    ("", 2, ["--seed", "Seed must be a whole number"]),
]
for value, status, expected in SEEDS:
    command = [config.OPAL_VOLUME] + small + ["--seed", value, "-o", volume_path]
    if run_case(f"--seed {value!r}", command, {}, status, expected) and status == 0:
        read = field(volume_path, "Seed")
        check(read == expected, f"--seed {value!r}: the field data's Seed is {expected} (got {read})")

# The other numbers of the flags (opal-render parses them before any work).
FLAGS = [
    (["--width", "0x10"], 2, ["--width", "ImageSize must be a whole number"]),
    (["--width", "99999999999"], 2, ["--width", "ImageSize must lie in [0, 16384]"]),
    (["--height", " 12"], 2, ["--height", "ImageSize must be a whole number"]),
    (["--device", "-5"], 2, ["--device", "DeviceIndex must lie in [-1, 2147483647]"]),
    (["--device", "1x"], 2, ["--device", "DeviceIndex must be a whole number"]),
    (["--device-memory-limit", "-1"], 2, ["--device-memory-limit", "DeviceMemoryLimit must lie in"]),
    (["--rotate-x", "inf"], 2, ["--rotate-x", "ModelRotation must be finite"]),
    (["--rotate-x", "0x1p3"], 2, ["--rotate-x", "ModelRotation must be a number in decimal"]),
    (["--wavelength-step", " 5"], 2, ["--wavelength-step", "WavelengthStep must be a number in decimal"]),
    (["--domain-count", "3.5"], 2, ["--domain-count", "DomainCount must be a whole number"]),
    (["--bragg-orders", "2"], 0, None),
]
for flag, status, expected in FLAGS:
    run_case(" ".join(flag), [config.OPAL_RENDER] + render_small + flag, {}, status, expected)
width_case = run_case("--width 010", [config.OPAL_RENDER] + small + ["--width", "010", "--height", "12",
                      "--save-image", image_path, "-o", os.path.join(output, "image.png")], {}, 0, None)
if width_case:
    reader = vtkXMLImageDataReader()
    reader.SetFileName(image_path)
    reader.Update()
    dimensions = reader.GetOutput().GetDimensions()
    check(dimensions[0] == 10, f"--width 010 is ten pixels, not octal eight (got {dimensions[0]})")

# The environment. The device's own name, as a render records it, gives a part of a name that exists.
run_case("no device setting", [config.OPAL_RENDER] + render_small, {"OPAL_VULKAN_DEVICE": ""}, 0, None)
device = field(image_path, "VulkanDevice") or ""
ENVIRONMENT = [
    ("OPAL_VULKAN_DEVICE", "99999999999999999999", 1, ["OPAL_VULKAN_DEVICE", "99999999999999999999"]),
    ("OPAL_VULKAN_DEVICE", "4294967296", 1, ["OPAL_VULKAN_DEVICE", "4294967296"]),
    ("OPAL_VULKAN_DEVICE", "-1", 1, ["OPAL_VULKAN_DEVICE", "\"-1\""]),
    ("OPAL_VULKAN_DEVICE", " 0", 1, ["OPAL_VULKAN_DEVICE", "\" 0\""]),
    ("OPAL_VULKAN_DEVICE", "+0", 1, ["OPAL_VULKAN_DEVICE", "\"+0\""]),
    ("OPAL_VULKAN_DEVICE", "1x", 1, ["OPAL_VULKAN_DEVICE", "1x"]),
    ("OPAL_VULKAN_DEVICE", "no-such-device", 1, ["OPAL_VULKAN_DEVICE", "no-such-device"]),
    ("OPAL_VULKAN_DEVICE", "0", 0, None),
    ("OPAL_VULKAN_DEVICE", device.split(" ")[0], 0, None),
    ("OPAL_VULKAN_VALIDATION", "false", 1, ["OPAL_VULKAN_VALIDATION must be 0 or 1", "false"]),
    ("OPAL_VULKAN_VALIDATION", "2", 1, ["OPAL_VULKAN_VALIDATION must be 0 or 1"]),
    ("OPAL_VULKAN_VALIDATION", "0", 0, None),
    ("OPAL_VULKAN_MEMORY_LIMIT_MB", " 5", 1, ["OPAL_VULKAN_MEMORY_LIMIT_MB", "\" 5\""]),
    ("OPAL_VULKAN_MEMORY_LIMIT_MB", "+5", 1, ["OPAL_VULKAN_MEMORY_LIMIT_MB", "\"+5\""]),
    ("OPAL_VULKAN_MEMORY_LIMIT_MB", "99999999999999999999", 1, ["OPAL_VULKAN_MEMORY_LIMIT_MB"]),
    ("OPAL_VULKAN_MEMORY_LIMIT_MB", "1000", 0, None),
]
check(device != "", f"the image records its device ({device!r})")
for name, value, status, expected in ENVIRONMENT:
    run_case(f"{name}={value!r}", [config.OPAL_RENDER] + render_small, {name: value}, status, expected)
    if status == 0 and name == "OPAL_VULKAN_DEVICE":
        used = field(image_path, "VulkanDevice")
        check(used == device, f"{name}={value!r} renders on {device} (got {used})")

# vtkOpalSource (ParaView's OpalVolume): the same range, the same field data.
LoadPlugin(config.PLUGIN, remote=False, ns=globals())
errors = []


@calldata_type(VTK_STRING)
def record(caller, event, text):
    errors.append(text)


vtkOutputWindow.GetInstance().AddObserver("ErrorEvent", record)
for seed, accepted in ((0, True), (2147483647, True), (-1, False), (-2147483648, False)):
    del errors[:]
    # The refusal is expected: the logger's stderr is quiet meanwhile, as ctest fails on "ERR|".
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
    source = OpalVolume(Dimensions=[20, 10, 20], DomainCount=3, Seed=seed)  # noqa: F821 (from the plugin)
    source.UpdatePipeline()
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_INFO)
    named = [e for e in errors if "Seed must lie in [0, 2147483647]" in e]
    if accepted:
        read = sm.Fetch(source).GetFieldData().GetArray("Seed").GetValue(0)
        check(not errors and read == seed, f"OpalVolume Seed={seed}: built, the field data's Seed is {seed} "
              f"(got {read}, errors {errors})")
    else:
        check(len(named) == 1, f"OpalVolume Seed={seed}: refused naming Seed's range (got {errors})")
finish("TestOpalNumbers")
