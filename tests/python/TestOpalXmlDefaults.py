"""pvpython: the default of every property of the plugin's proxies, as the
ParaView XML (paraview_plugin/*.xml) states it, equals the default of the C++
member it sets, so ParaView, pvpython and C++ users start from one setting.

For each proxy of each XML file, and each of its vector properties:
  1. the XML file's default_values equal the definition ParaView loaded from
     the plugin (a stale build fails here) and the value the property holds
     right after creation, and that value lies in the property's domains;
  2. they equal the member's value in a freshly constructed C++ object that
     ParaView has never set anything on (NewInstance of the proxy's object);
  3. the proxy's own object, which ParaView has pushed the defaults into, prints
     the same values, so the setter named by command="SetX" sets the member
     that PrintSelf prints as X.
The classes are not wrapped in Python (no GetX from Python), so the C++ values
are read from PrintSelf ("  X: v0 v1 ..." lines), which prints every property;
doubles print with 6 significant digits, hence the relative tolerance.

Optional argument: the directory of the XML files (default: the source tree's
paraview_plugin next to this script)."""
import glob
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

from paraview import servermanager as sm
from paraview.simple import LoadPlugin

import opal_test_config as config
from opal_test_support import check, finish

XML_DIRECTORY = (sys.argv[1] if len(sys.argv) > 1 else
                 os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "paraview_plugin"))
# Properties that carry no default of a C++ member, and why.
SKIPPED_KINDS = {
    "InputProperty": "a pipeline connection (SetInputConnection), not a value with a default",
    "ProxyProperty": "refers to another proxy, not a value with a default",
}
RELATIVE_TOLERANCE = 1e-5  # PrintSelf prints doubles with 6 significant digits

LoadPlugin(config.PLUGIN, remote=False, ns=globals())  # adds OpalVolume() etc. here
skipped = []


def parse_values(kind, text):
    """Numbers (or strings) of an XML default_values or a PrintSelf line."""
    words = text.split()
    if kind == "StringVectorProperty":
        return words or [""]  # an empty string is one value
    words = [{"On": "1", "Off": "0", "true": "1", "false": "0"}.get(w, w) for w in words]
    return [int(w) if kind in ("IntVectorProperty", "IdTypeVectorProperty") else float(w) for w in words]


def same(a, b):
    if len(a) != len(b):
        return False
    return all(x == y or (isinstance(x, float) and math.isclose(x, y, rel_tol=RELATIVE_TOLERANCE))
               for x, y in zip(a, b))


def printed_members(vtk_object):
    """Name -> text of the top-level "  Name: value" lines of the object's Print (last one wins)."""
    members = {}
    for line in str(vtk_object).splitlines():
        match = re.match(r"^  (\w+):(.*)$", line)
        if match:
            members[match.group(1)] = match.group(2)
    return members


def proxy_properties(proxy):
    """Names of all properties of the proxy as ParaView defined it."""
    names, iterator = set(), proxy.SMProxy.NewPropertyIterator()
    iterator.Begin()
    while not iterator.IsAtEnd():
        names.add(iterator.GetKey())
        iterator.Next()
    return names


def in_domains(element, values):
    """Whether the values lie in the property's range, enumeration and boolean domains, read as
    ParaView reads them (min/max per element). ParaView 5.11's own IsInDomains() cannot tell:
    its range check rejects every value below the range's max."""
    for domain in element:
        if domain.tag in ("IntRangeDomain", "DoubleRangeDomain"):
            kind = domain.tag.replace("RangeDomain", "VectorProperty")
            low, high = parse_values(kind, domain.get("min", "")), parse_values(kind, domain.get("max", ""))
            if any((i < len(low) and v < low[i]) or (i < len(high) and v > high[i])
                   for i, v in enumerate(values)):
                return False
        elif domain.tag == "EnumerationDomain":
            if not set(values) <= {int(entry.get("value")) for entry in domain.iter("Entry")}:
                return False
        elif domain.tag == "BooleanDomain" and not set(values) <= {0, 1}:
            return False
    return True


def loaded_defaults(group, name):
    """Property name -> default_values of the proxy's definition as ParaView loaded it from the plugin."""
    definition = sm.ProxyManager().SMProxyManager.GetProxyDefinition(group, name)
    defaults = {}
    for i in range(definition.GetNumberOfNestedElements() if definition else 0):
        child = definition.GetNestedElement(i)
        if child.GetAttribute("name"):
            defaults[child.GetAttribute("name")] = child.GetAttribute("default_values")
    return defaults


def current_values(kind, prop):
    """The values the property holds."""
    values = [prop.GetElement(i) for i in range(prop.GetNumberOfElements())]
    return values if kind == "StringVectorProperty" else parse_values(kind, " ".join(map(str, values)))


def check_property(where, element, proxy, loaded, fresh, pushed):
    kind, name = element.tag, element.get("name")
    if element.get("information_only") == "1":
        skipped.append((f"{where}.{name}", "information-only: ParaView reads it from the object"))
        return
    command = element.get("command") or ""
    if not check(command.startswith("Set"), f"{where}.{name}: command {command!r} names a setter SetX"):
        return
    member = command[3:]
    if not check(element.get("default_values") is not None, f"{where}.{name} has default_values"):
        return
    xml = parse_values(kind, element.get("default_values"))
    count = int(element.get("number_of_elements", len(xml)))
    check(len(xml) == count, f"{where}.{name}: default_values has {count} values ({xml})")
    built = loaded.get(name)
    check(built is not None and same(xml, parse_values(kind, built)), f"{where}.{name}: the built "
          f"plugin's default {built!r} is the XML file's {xml} (rebuild the plugin?)")
    prop = proxy.GetProperty(name).SMProperty
    current = current_values(kind, prop)
    check(same(xml, current) and prop.IsValueDefault(),
          f"{where}.{name}: ParaView sets the XML default {xml} on creation (got {current})")
    check(in_domains(element, xml), f"{where}.{name}: the default {xml} lies in its domains")
    for label, members in (("a fresh C++ object", fresh), ("the object ParaView set up", pushed)):
        if check(member in members, f"{where}.{name}: {label} prints {member} (PrintSelf)"):
            value = parse_values(kind, members[member])
            check(same(xml, value), f"{where}.{name}: {label} has the XML default, "
                  f"{member} = {xml} (got {value})")


def exposed_properties(element):
    """Exposed name -> (subproxy's proxy name, its property's name) of the proxy's SubProxy elements."""
    exposed = {}
    for sub in element.iter("SubProxy"):
        target = sub.find("Proxy")
        for prop in sub.iter("Property"):
            if target is not None and prop.get("name") and sub.find("ExposedProperties") is not None:
                exposed[prop.get("exposed_name") or prop.get("name")] = (target.get("proxyname"), prop.get("name"))
    return exposed


def definition_element(proxy_name, property_name):
    """The XML element of a property of another of the plugin's proxies."""
    for path in glob.glob(os.path.join(XML_DIRECTORY, "*.xml")):
        for element in ET.parse(path).getroot().iter():
            if element.get("name") == proxy_name and element.get("class"):
                return next((c for c in element if c.get("name") == property_name), None)
    return None


def check_exposed(where, proxy, exposed):
    """An exposed property holds the default its own proxy's XML gives (that proxy's checks cover its C++)."""
    for name, (target, source) in sorted(exposed.items()):
        element = definition_element(target, source)
        if not check(element is not None, f"{where}.{name}: exposes {target}.{source}, which the XML defines"):
            continue
        xml = parse_values(element.tag, element.get("default_values"))
        current = current_values(element.tag, proxy.GetProperty(name).SMProperty)
        check(same(xml, current), f"{where}.{name}: holds {target}.{source}'s XML default {xml} (got {current})")
    return len(exposed)


def create_representation(group, name, inputs):
    """A representation proxy (no paraview.simple constructor) on the first source, set up."""
    proxy = sm._getPyProxy(sm.ProxyManager().SMProxyManager.NewProxy(group, name))
    if proxy is not None and inputs:
        proxy.Input = inputs[0]
        proxy.UpdateVTKObjects()
    return proxy


def check_proxy(path, group, element, inputs):
    where = f"{os.path.basename(path)}:{element.get('name')}"
    if group in ("representations", "3d_widget_representations"):
        proxy = create_representation(group, element.get("name"), inputs if group == "representations" else [])
        if not check(proxy is not None, f"{where}: ParaView creates the representation"):
            return None
    else:
        create = globals().get(re.sub(r"\W", "", element.get("label", element.get("name"))))
        if not check(create is not None, f"{where}: paraview.simple offers the proxy"):
            return None
        has_input = element.find("InputProperty") is not None
        proxy = create(Input=inputs[0]) if has_input and inputs else create()
    pushed = proxy.GetClientSideObject()
    check(pushed.GetClassName() == element.get("class"), f"{where}: the object is a {element.get('class')}")
    fresh = pushed.NewInstance()  # constructed by C++ alone: ParaView never set anything on it
    printed_fresh, printed_pushed = printed_members(fresh), printed_members(pushed)
    loaded = loaded_defaults(group, element.get("name"))
    xml_names = {child.get("name") for child in element if child.tag.endswith("Property")}
    exposed = exposed_properties(element)
    check(proxy_properties(proxy) == xml_names | set(exposed), f"{where}: the built plugin's properties "
          f"{sorted(proxy_properties(proxy))} equal the XML file's {sorted(xml_names | set(exposed))}")
    covered = check_exposed(where, proxy, exposed)
    for child in element:
        if child.tag in SKIPPED_KINDS:
            skipped.append((f"{where}.{child.get('name')}", SKIPPED_KINDS[child.tag]))
        elif child.tag.endswith("VectorProperty"):
            check_property(where, child, proxy, loaded, printed_fresh, printed_pushed)
            covered += 1
        elif child.tag.endswith("Property"):
            check(False, f"{where}.{child.get('name')}: the test knows how to check a {child.tag}")
    print(f"{where}: {covered} properties compared")
    return proxy


def main():
    files = sorted(glob.glob(os.path.join(XML_DIRECTORY, "*.xml")))
    check(len(files) >= 3, f"the plugin's XML files are found in {XML_DIRECTORY}")
    proxies = [(path, group.get("name"), element) for path in files
               for group in ET.parse(path).getroot().iter("ProxyGroup") for element in group
               if element.get("class") and group.get("name") != "views" and
               element.tag != "NewWidgetRepresentationProxy"]
    skipped.extend((f"{os.path.basename(path)}:{element.get('name')}",
                    "a view: ParaView's RenderView and its properties, none of ours")
                   for path in files for group in ET.parse(path).getroot().iter("ProxyGroup")
                   if group.get("name") == "views" for element in group)
    skipped.extend((f"{os.path.basename(path)}:{element.get('name')}",
                    "ParaView's 3-D widget wrapper: its properties are its handle representation's, checked")
                   for path in files for element in ET.parse(path).getroot().iter("NewWidgetRepresentationProxy"))
    # Sources first: the filters take the first source as their input.
    proxies.sort(key=lambda item: item[2].find("InputProperty") is not None)
    inputs = []
    for path, group, element in proxies:
        proxy = check_proxy(path, group, element, inputs)
        if proxy is not None and group == "sources":
            # A filter on a volume with a preset shows the preset's view
            # settings instead of its XML defaults (docs/design.md §2.8).
            if "Preset" in proxy.ListProperties():
                proxy.Preset = "custom"
            inputs.append(proxy)
    for name, reason in skipped:
        print(f"skipped {name}: {reason}")


main()
finish("TestOpalXmlDefaults")
