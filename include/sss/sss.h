#pragma once
/// @file
/// Everything in the public libsss API. The renderers (sss::sss) define most of it; the CPU
/// ground truths of sss/mesh_reference.h, sss/volume_reference.h, sss/volume_path_tracer.h and
/// sss/random_walk.h need sss::reference, and the file functions (Mesh::load, Volume::load,
/// Image::savePng, ...) need sss::io: find_package(sss COMPONENTS io reference).
#include "sss/bounds.h"
#include "sss/bssrdf.h"
#include "sss/camera.h"
#include "sss/context.h"
#include "sss/display.h"
#include "sss/error.h"
#include "sss/frame_accumulator.h"
#include "sss/gpu_memory.h"
#ifdef SSS_WITH_GLFW
#include "sss/glfw_context.h"
#endif
#include "sss/host_frame.h"
#include "sss/hybrid_compositor.h"
#include "sss/image.h"
#include "sss/image_compare.h"
#include "sss/isosurface.h"
#include "sss/light.h"
#include "sss/log.h"
#include "sss/materials.h"
#include "sss/mesh.h"
#include "sss/mesh_reference.h"
#include "sss/mesh_scattering_renderer.h"
#include "sss/procedural.h"
#include "sss/random_walk.h"
#include "sss/render_target.h"
#include "sss/stats.h"
#include "sss/timing.h"
#include "sss/transfer_function.h"
#include "sss/transfer_function_editor.h"
#include "sss/volume.h"
#include "sss/volume_path_tracer.h"
#include "sss/volume_reference.h"
#include "sss/volume_scattering_renderer.h"
