// trac0r's public API in one include: scenes (load, or build with
// SceneBuilder: materials, shapes, meshes from arrays, lights), the
// renderer on the CPU or OpenCL backend, batch renders with stop rules
// (batch.h), images (write, read, tone map), the noise estimate and the
// version. examples/minimal.cpp shows them in use; docs/library.md.
#ifndef TRAC0R_TRAC0R_H
#define TRAC0R_TRAC0R_H

#include "trac0r/batch.h"
#include "trac0r/camera.h"
#include "trac0r/cpu_backend.h"
#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/mesh_arrays.h"
#include "trac0r/noise.h"
#include "trac0r/renderer.h"
#include "trac0r/scene.h"
#include "trac0r/scene_builder.h"
#include "trac0r/scene_loader.h"
#include "trac0r/version.h"
#ifdef TRAC0R_HAVE_OPENCL
#include "trac0r/opencl_backend.h"
#endif

#endif
