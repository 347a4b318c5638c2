// Test fixture: includes a file that does not exist (line 3).
#version 450 core
#include "does_not_exist.h"
layout(local_size_x = 1) in;
void main() {}
