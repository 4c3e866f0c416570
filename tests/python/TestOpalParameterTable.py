"""pvpython: the ParaView XML of Opal Spectral Render agrees with the render
parameters' table (OPAL_RENDER_PARAMETERS), and that of Opal Volume with the
model parameters' table (OPAL_MODEL_PARAMETERS), both printed by opal-render
--list-parameters, row by row:
  - every row is a property of that name, and every property of the proxy is
    a row or one of the filter's own settings (FILTER_SETTINGS);
  - its kind (Int/DoubleVectorProperty), number_of_elements and default_values
    are the row's type, components and default (0 where the row takes the
    volume's value);
  - its range domain is the row's range (the render's) or lies within it (the
    volume's: its sliders are narrower, e.g. DomainCount 0-2000 of 0-100000),
    its enumeration the row's names in order, a boolean row has a
    BooleanDomain; a render property without a range domain is a row without
    an upper bound;
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

PLUGIN_XML = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "paraview_plugin")
# Each proxy, its table, and its properties that are not the table's parameters (and why).
PROXIES = {
    "OpalSpectralRender": ("filters", "render", "OpalSpectralRender.xml", {
        "Input": "the pipeline connection",
        "PresetPlacement": "whether the volume's placement comes first (the proxy fills ModelRotation)",
        "DeviceIndex": "the Vulkan device, not the frame",
        "DeviceMemoryLimit": "the device's memory limit, not the frame",
        "ShareMarch": "how the ranks of an MPI render divide the march, not the frame",
        "LastMarchShares": "what the last update did (information only), not a setting",
        "LastGatherSeconds": "what the last update measured (information only), not a setting",
        "LastScatteredLightShares": "what the last update did (information only), not a setting",
        "LastLightFieldShares": "what the last update did (information only), not a setting",
        "LastGatheredLayers": "what the last update held (information only), not a setting",
        "LastMediumLayers": "what the last update held (information only), not a setting",
    }),
    "OpalVolume": ("sources", "model", "OpalVolume.xml", {
        "Preset": "chooses the parameters a preset sets, not a parameter",
        "OutputArrays": "which arrays the volume carries, not the opal it describes",
        "LastVoronoiCellShares": "what the last update did (information only), not a setting",
    }),
}
# Rows whose XML gives a narrower range on purpose (a slider, an animation's
# first keyframes), each within the row's range.
NARROWER_RANGES = {
    "ModelRotation": "the Animation View's first keyframes: a tilt of -15 to 15 degrees",
}

tables = json.loads(subprocess.run([config.OPAL_RENDER, "--list-parameters"], check=True,
                                   capture_output=True, text=True).stdout)
check(len(tables["render"]) >= 29 and len(tables["model"]) >= 27,
      f"opal-render lists both tables ({len(tables['render'])} and {len(tables['model'])} rows)")
LoadPlugin(config.PLUGIN, remote=False, ns=globals())


def printed_rows(group, name):
    """Name -> values of the top-level PrintSelf lines of a fresh proxy's object."""
    proxy = getattr(sm.filters if group == "filters" else sm.sources, name)()
    printed = {}
    for line in str(proxy.GetClientSideObject()).splitlines():
        if line.startswith("  ") and not line.startswith("   ") and ":" in line:
            key, _, value = line.strip().partition(":")
            printed[key] = value.split()  # the last: the class's own lines come after its superclass's
    return printed


def numbers(text, kind):
    return [(int if kind == "int" else float)(w) for w in text.split()]


def check_range(row, element, sliders):
    domain = next((d for d in element if d.tag.endswith("RangeDomain")), None)
    name = row["name"]
    if domain is None:
        check(sliders or row["max"] is None,
              f"{name}: a range domain, as the row has a range [{row['min']}, {row['max']}]")
        return
    kind = "int" if row["type"] == "int" else "double"
    low, high = numbers(domain.get("min"), kind), numbers(domain.get("max", ""), kind)
    if sliders or name in NARROWER_RANGES:
        check(all((row["min"] is None or row["min"] <= v) and (row["max"] is None or v <= row["max"])
                  for v in low + high),
              f"{name}: the XML's range {low}-{high} lies within the row's [{row['min']}, {row['max']}]")
        return
    upper = [] if row["max"] is None else [row["max"]] * row["components"]
    check(low == [row["min"]] * row["components"] and high == upper,
          f"{name}: the XML's range {low}-{high} is the row's [{row['min']}, {row['max']}]")


def check_row(proxy_name, row, element, printed):
    name = row["name"]
    expected_kind = "DoubleVectorProperty" if row["type"] == "double" else "IntVectorProperty"
    check(element.tag == expected_kind, f"{proxy_name}.{name}: {element.tag}, the row's type {row['type']}")
    check(int(element.get("number_of_elements")) == row["components"],
          f"{proxy_name}.{name}: {element.get('number_of_elements')} elements, the row's {row['components']}")
    check(element.get("command") == "Set" + name, f"{proxy_name}.{name}: command Set{name}")
    default = numbers(element.get("default_values"), "double")
    check(default == [float(v) for v in row["default"]],
          f"{proxy_name}.{name}: XML default {default}, the row's {row['default']}")
    enumeration = [e.get("text") for e in element.iter("Entry")]
    check(enumeration == row["choices"], f"{proxy_name}.{name}: the XML's entries {enumeration} are the row's "
          f"{row['choices']}")
    check((row["type"] == "bool") == any(d.tag == "BooleanDomain" for d in element),
          f"{proxy_name}.{name}: a BooleanDomain exactly where the row is a bool")
    if not row["choices"] and row["type"] != "bool":
        check_range(row, element, sliders=proxy_name == "OpalVolume")
    check(name in printed and [float(v) for v in printed[name]] == [float(v) for v in row["default"]],
          f"{proxy_name}.{name}: PrintSelf prints the row's default {row['default']} (got {printed.get(name)})")
    check(bool(row["description"]) and (row["flag"] == "" or row["flag"].startswith("--")),
          f"{proxy_name}.{name}: a description and a flag (or none) in the table")


for proxy_name, (group, table, xml_file, settings) in PROXIES.items():
    root = ET.parse(os.path.join(PLUGIN_XML, xml_file)).getroot()
    proxy_xml = next(p for p in root.iter() if p.get("name") == proxy_name and p.get("class"))
    properties = {e.get("name"): e for e in proxy_xml if e.tag.endswith("Property")}
    rows = tables[table]
    by_name = {row["name"]: row for row in rows}
    for name in properties:
        check(name in by_name or name in settings, f"{proxy_name}.{name} is a table row or one of its settings")
    printed = printed_rows(group, proxy_name)
    for row in rows:
        element = properties.get(row["name"])
        if check(element is not None, f"row {row['name']} is a property of {proxy_name}"):
            check_row(proxy_name, row, element, printed)

finish("TestOpalParameterTable", f"{len(tables['render'])} render and {len(tables['model'])} model rows")
