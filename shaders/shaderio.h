// shaderio.h: the interface between the host and the GPU, declared once for C++ and GLSL, in three parts:
//   shaderio_core.h   how one header is both languages (namespace, types, VGEO_INLINE)
//   shaderio_scene.h  the .vgeo structs, which are the scene's GPU buffers byte for byte
//   shaderio_frame.h  the renderer's bindings, frame constants, counters and working-list encodings
#ifndef VGEO_SHADERIO_H
#define VGEO_SHADERIO_H

#include "shaderio_frame.h"

#endif
