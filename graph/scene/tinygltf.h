// Internal to rg_scene: tiny_gltf.h with the configuration every file of this module must share
// (the macros change inline member initialisers, so they have to be the same everywhere).
// - No stb_image inside tinygltf: images are kept encoded by our own callback and decoded in
//   image_codec.cpp, and exportGlb stores PNG bytes in a buffer view itself.
// - No external image files: the loader opens them (gltf_load_materials.cpp), so a missing image is an error that
//   names the file instead of a warning.
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop
