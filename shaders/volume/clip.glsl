// Clip planes and crop box (sss/volume_clip.h) in texture coordinates, as
// src/core/volume_clip_space.h computes them: a sample is kept where dot(plane.xyz, tc) + plane.w
// >= 0 for every plane and tc lies in [cropMin, cropMax] (open faces at +-1e30).
#include "common/ray_box.glsl"

// CLIP 0 compiles the tests away where nothing is cut: a switch on a uniform still cost every
// sample its test on llvmpipe, which runs a branch's body whether or not a lane takes it.
#ifndef CLIP
#define CLIP 1
#endif

#define MAX_CLIP_PLANES 12  // VolumeClip::kMaxPlanes, and a world-space crop box's six faces
uniform int clipActive;             // 0: nothing is cut
uniform int clipLight;              // 1: the cut matter is gone for the light as well (no shadows)
uniform int clipPlaneCount;
uniform vec4 clipPlanes[MAX_CLIP_PLANES];
uniform vec3 cropMin;
uniform vec3 cropMax;

bool clipKeeps(vec3 tc) {
#if CLIP
    if (clipActive == 0) return true;
    for (int i = 0; i < clipPlaneCount; ++i)
        if (dot(clipPlanes[i].xyz, tc) + clipPlanes[i].w < 0.0) return false;
    return all(greaterThanEqual(tc, cropMin)) && all(lessThanEqual(tc, cropMax));
#else
    return true;
#endif
}

// Whether the light passes through the medium at tc (the cut matter casts no shadows).
bool lightSeesMedium(vec3 tc) {
#if CLIP
    return clipLight == 0 || clipKeeps(tc);
#else
    return true;
#endif
}

// The part of the ray tc(t) = origin + t direction, t in span = (enter, exit), that the clip
// keeps: one interval, since the kept region is convex (empty when x >= y).
vec2 clipSpan(vec3 origin, vec3 direction, vec2 span) {
#if CLIP
    if (clipActive == 0) return span;
    for (int i = 0; i < clipPlaneCount; ++i) {
        float rate = dot(clipPlanes[i].xyz, direction);
        float start = dot(clipPlanes[i].xyz, origin) + clipPlanes[i].w;
        if (rate > 0.0) span.x = max(span.x, -start / rate);
        else if (rate < 0.0) span.y = min(span.y, -start / rate);
        else if (start < 0.0) span.y = span.x;
    }
    vec3 inverse = safeInverse(direction);
    vec3 t0 = (cropMin - origin) * inverse, t1 = (cropMax - origin) * inverse;
    vec3 near = min(t0, t1), far = max(t0, t1);
    span.x = max(span.x, max(max(near.x, near.y), near.z));
    span.y = min(span.y, min(min(far.x, far.y), far.z));
#endif
    return span;
}
