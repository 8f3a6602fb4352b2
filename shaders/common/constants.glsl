// Shared constants and the enumerations that C++ mirrors (engine/render/shader_interface.h).
const float PI = 3.14159265358979323846;
const float INV_PI = 0.31830988618379067154;
const int NDF_GGX = 0;
const int NDF_BECKMANN = 1;
