#pragma once
/// @file
/// Everything in the public libsss API.
#include "sss/bounds.h"
#include "sss/bssrdf.h"
#include "sss/camera.h"
#include "sss/context.h"
#include "sss/error.h"
#ifdef SSS_WITH_GLFW
#include "sss/glfw_context.h"
#endif
#include "sss/hybrid_compositor.h"
#include "sss/image.h"
#include "sss/image_compare.h"
#include "sss/light.h"
#include "sss/log.h"
#include "sss/materials.h"
#include "sss/mesh.h"
#include "sss/mesh_reference.h"
#include "sss/mesh_scattering_renderer.h"
#include "sss/procedural.h"
#include "sss/render_target.h"
#include "sss/stats.h"
#include "sss/timing.h"
#include "sss/transfer_function.h"
#include "sss/volume.h"
#include "sss/volume_reference.h"
#include "sss/volume_scattering_renderer.h"
