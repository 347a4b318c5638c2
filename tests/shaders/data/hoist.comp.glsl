// Test fixture: #extension and #version after other lines, a header included twice, a #pragma once header.
#include "once.h"
#version 450 core
#include "once.h"
#extension GL_ARB_shader_ballot : enable
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float value; };
void main() { value = once_value() + float(INJECTED); }
