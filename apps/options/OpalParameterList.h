// The render parameters' table as JSON (opal-render --list-parameters): each
// row's name, type, components, range, enumeration names, flag, default and
// description, for scripts and for the test that holds the ParaView XML to it.
#pragma once

#include <string>

std::string renderParameterListJson();
