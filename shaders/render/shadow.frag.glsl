// SPDX-License-Identifier: MIT
// Shadow pass, fragment stage: depth only (the rasteriser writes it); nothing to shade.
#version 450 core

void main() {
}
