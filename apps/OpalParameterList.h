// The parameter tables as JSON (opal-render --list-parameters): "model" and
// "render", each row's name, type, components, range (null: no bound),
// enumeration names, flag, default and description, for scripts and for the
// test that holds the ParaView XML to them.
#pragma once

#include <string>

std::string parameterListJson();
