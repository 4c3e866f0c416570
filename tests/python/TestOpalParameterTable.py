"""pvpython: the ParaView XML of Opal Spectral Render agrees with the render
parameters' table (OPAL_RENDER_PARAMETERS, printed by opal-render
--list-parameters), row by row:
  - every row is a property of that name, and every property of the proxy is
    a row or one of the filter's own settings (FILTER_SETTINGS);
  - its kind (Int/DoubleVectorProperty), number_of_elements and default_values
    are the row's type, components and default (0 where the row takes the
    volume's value);
  - its range domain is the row's range, its enumeration the row's names in
    order, a boolean row has a BooleanDomain; a property without a range
    domain is a row without an upper bound or one whose bounds are rules
    validate states (UNRANGED);
  - the object ParaView made prints the row (PrintSelf).
TestOpalXmlDefaults holds the XML defaults to the C++ members as well."""
import json
import os
import subprocess
import xml.etree.ElementTree as ET

from paraview import servermanager as sm
from paraview.simple import LoadPlugin

import opal_test_config as config
from opal_test_support import check, finish

XML = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "paraview_plugin",
                   "OpalSpectralRender.xml")
# Properties of the filter that are not render parameters, and why.
FILTER_SETTINGS = {
    "Input": "the pipeline connection",
    "PresetPlacement": "whether the volume's placement comes first (the proxy fills ModelRotation)",
    "DeviceIndex": "the Vulkan device, not the frame",
    "DeviceMemoryLimit": "the device's memory limit, not the frame",
}
# Rows whose XML gives a narrower range on purpose (a slider, an animation's
# first keyframes), each within the row's range.
NARROWER_RANGES = {
    "ModelRotation": "the Animation View's first keyframes: a tilt of -15 to 15 degrees",
}

rows = json.loads(subprocess.run([config.OPAL_RENDER, "--list-parameters"], check=True,
                                 capture_output=True, text=True).stdout)
check(len(rows) >= 29, f"opal-render lists the table ({len(rows)} rows)")
proxy_xml = next(p for p in ET.parse(XML).getroot().iter() if p.get("name") == "OpalSpectralRender")
properties = {e.get("name"): e for e in proxy_xml if e.tag.endswith("Property")}
by_name = {row["name"]: row for row in rows}

for name in properties:
    check(name in by_name or name in FILTER_SETTINGS, f"property {name} is a table row or a filter setting")

LoadPlugin(config.PLUGIN, remote=False, ns=globals())
source = sm.filters.OpalSpectralRender()
printed = {}
for line in str(source.GetClientSideObject()).splitlines():
    if line.startswith("  ") and ":" in line:
        key, _, value = line.strip().partition(":")
        printed.setdefault(key, value.split())


def numbers(text, kind):
    return [(int if kind == "int" else float)(w) for w in text.split()]


def check_range(row, element):
    domain = next((d for d in element if d.tag.endswith("RangeDomain")), None)
    name = row["name"]
    if domain is None:
        check(row["max"] is None, f"{name}: a range domain, as the row has a range [{row['min']}, {row['max']}]")
        return
    kind = "int" if row["type"] == "int" else "double"
    low, high = numbers(domain.get("min"), kind), numbers(domain.get("max", ""), kind)
    if name in NARROWER_RANGES:
        check(all((row["min"] is None or row["min"] <= v) and (row["max"] is None or v <= row["max"])
                  for v in low + high),
              f"{name}: the XML's range {low}-{high} lies within the row's [{row['min']}, {row['max']}]")
        return
    upper = [] if row["max"] is None else [row["max"]] * row["components"]
    check(low == [row["min"]] * row["components"] and high == upper,
          f"{name}: the XML's range {low}-{high} is the row's [{row['min']}, {row['max']}]")


for row in rows:
    name, element = row["name"], properties.get(row["name"])
    if not check(element is not None, f"row {name} is a property of OpalSpectralRender"):
        continue
    expected_kind = "DoubleVectorProperty" if row["type"] == "double" else "IntVectorProperty"
    check(element.tag == expected_kind, f"{name}: {element.tag}, the row's type {row['type']}")
    check(int(element.get("number_of_elements")) == row["components"],
          f"{name}: {element.get('number_of_elements')} elements, the row's {row['components']}")
    check(element.get("command") == "Set" + name, f"{name}: command Set{name}")
    default = numbers(element.get("default_values"), "double")
    check(default == [float(v) for v in row["default"]], f"{name}: XML default {default}, the row's {row['default']}")
    enumeration = [e.get("text") for e in element.iter("Entry")]
    check(enumeration == row["choices"], f"{name}: the XML's entries {enumeration} are the row's {row['choices']}")
    check((row["type"] == "bool") == any(d.tag == "BooleanDomain" for d in element),
          f"{name}: a BooleanDomain exactly where the row is a bool")
    if not row["choices"] and row["type"] != "bool":
        check_range(row, element)
    check(name in printed and [float(v) for v in printed[name]] == [float(v) for v in row["default"]],
          f"{name}: PrintSelf prints the row's default {row['default']} (got {printed.get(name)})")
    check(bool(row["description"]) and (row["flag"] == "" or row["flag"].startswith("--")),
          f"{name}: a description and a flag (or none) in the table")

finish("TestOpalParameterTable", f"{len(rows)} rows")
