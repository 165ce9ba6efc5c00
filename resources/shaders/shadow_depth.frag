#version 450 core
// Depth only: the rasteriser writes it, with the slope-scaled polygon offset of shadow_maps.cpp.
void main() {}
