// Test fixture: compiles only if broken_helper.h does; the error must be reported in that file, line 5.
#version 450 core
#include "broken_helper.h"
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float value; };
void main() { value = broken_helper(1.0f); }
