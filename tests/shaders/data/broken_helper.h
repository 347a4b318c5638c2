// Test fixture: a header with a syntax error on line 5 (missing semicolon), included by broken_main.comp.glsl.
#ifndef BROKEN_HELPER_H
#define BROKEN_HELPER_H

float broken_helper(float x) { return x * 2.0f }

#endif
