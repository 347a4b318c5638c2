#pragma once
#extension GL_ARB_shader_ballot : enable
float once_value() { return 1.0f; }
