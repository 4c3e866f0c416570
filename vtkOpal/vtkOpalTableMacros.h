// A parameter table's rows (OPAL_RENDER_PARAMETERS, OPAL_MODEL_PARAMETERS) as a VTK class's members
// and Set/Get: expanded by the compiler and by VTK's wrappers alike, so
// ParaView and Python see SetStepSize as if it were spelled out.
#pragma once

#include "vtkSetGet.h"

#define OPAL_VTK_SET_GET(Name, Type, Count, ...) OPAL_VTK_SET_GET_##Type##_##Count(Name)
#define OPAL_VTK_SET_GET_int_1(Name) vtkSetMacro(Name, int) vtkGetMacro(Name, int)
#define OPAL_VTK_SET_GET_double_1(Name) vtkSetMacro(Name, double) vtkGetMacro(Name, double)
#define OPAL_VTK_SET_GET_bool_1(Name) vtkSetMacro(Name, bool) vtkGetMacro(Name, bool) vtkBooleanMacro(Name, bool)
#define OPAL_VTK_SET_GET_int_2(Name) vtkSetVector2Macro(Name, int) vtkGetVector2Macro(Name, int)
#define OPAL_VTK_SET_GET_double_2(Name) vtkSetVector2Macro(Name, double) vtkGetVector2Macro(Name, double)
#define OPAL_VTK_SET_GET_int_3(Name) vtkSetVector3Macro(Name, int) vtkGetVector3Macro(Name, int)
#define OPAL_VTK_SET_GET_double_3(Name) vtkSetVector3Macro(Name, double) vtkGetVector3Macro(Name, double)
#define OPAL_VTK_SET_GET_int_4(Name) vtkSetVector4Macro(Name, int) vtkGetVector4Macro(Name, int)

#define OPAL_VTK_MEMBER(Name, Type, Count, ...) OPAL_VTK_MEMBER_##Count(Name, Type)
#define OPAL_VTK_MEMBER_1(Name, Type) Type Name;
#define OPAL_VTK_MEMBER_2(Name, Type) Type Name[2];
#define OPAL_VTK_MEMBER_3(Name, Type) Type Name[3];
#define OPAL_VTK_MEMBER_4(Name, Type) Type Name[4];

// In the class's .cxx (vtkOpalArrayCopy.h): a row between the member and the
// parameters' struct `p`, and its PrintSelf line.
#define OPAL_VTK_TO_STRUCT(Name, ...) vtkOpalArrayCopy::assign(p.Name, this->Name);
#define OPAL_VTK_FROM_STRUCT(Name, ...) vtkOpalArrayCopy::assign(this->Name, p.Name);
#define OPAL_VTK_PRINT(Name, ...) vtkOpalArrayCopy::print(os, indent, #Name, this->Name);
