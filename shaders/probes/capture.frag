#version 460
// Local light probe capture for draws whose material has no generated capture shader: see
// probes/capture_main.glsl.
#include "probes/capture_main.glsl"
