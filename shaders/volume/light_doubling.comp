// The light volume by ray doubling (docs/light-volume-sweep.md, "Ray doubling"): the same light
// as the sweep of light_propagation.comp, in a few fully parallel dispatches instead of one
// dependent step per slice.
//
// A texel of a level describes a segment of the ray from its voxel centre towards the light by
// what the segment does to white light entering its far end: the colour c and the transmittance
// T it leaves with. The medium changes light as the sweep's does (c' = (1-a) c + a rgb,
// l' = (1-a) l), so light (c0, l0) leaves the segment as (T c0 + c - T, T l0). LEVEL0 samples
// the medium along a segment of `segmentLength` (the sweep's path between two slices). Each
// further level joins a voxel's segment with the one of the same length that starts where it
// ends, read filtered from the previous level:
//   c = T_near c_far + c_near - T_near,   T = T_near T_far,
// doubling the length. After log2(path / segmentLength) levels every segment reaches the box's
// face, or the point light, which ends each segment (rays from a point light's voxels all meet
// it, so a far segment lies on its near segment's ray). T, not the optical depth, is what the
// levels interpolate: between a ray through a dense structure and one beside it, the mean of T
// is the light a filtered lookup should give (interpolated optical depth measured 1.5-2x the
// mean error against the CPU reference's shadow rays, on llvmpipe).
//
// Two grids: GRID_COLOUR 0 carries T alone (one half float per texel) at the light volume's
// resolution; GRID_COLOUR 1 carries (c, T) at half that resolution, for the paper model's colour,
// which the cone blurs over several texels anyway. Its levels blur the colour arriving at the far
// end over the sweep's cone: eight taps on a ring across the ray around the centre lookup, with
// the sweep's weights. The sweep blurs once per slice with radius tan(cone) x its slice path;
// level j's ring has sqrt(2^j) times the first segment's radius, so the variances of the levels a
// path crosses add up to the sweep's over the same path (the levels' lengths are the binary
// digits of the path's segments). LAST, the transmittance grid's last level, writes the light
// volume: (c, l) = (the colour grid's c at the voxel, or white without CHROMATICITY, T).
#ifndef CHROMATICITY
#define CHROMATICITY 1
#endif
#ifndef GRID_COLOUR
#define GRID_COLOUR 0
#endif
#ifndef LEVEL0
#define LEVEL0 0
#endif
#ifndef LAST
#define LAST 0
#endif
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "volume/transfer_function.glsl"
#include "volume/clip.glsl"
#include "volume/empty_neighbourhood.glsl"

// The levels hold l alone, as does the light volume without the chromaticity (sampled as
// (1, 1, 1, l): LightVolumePass).
#if GRID_COLOUR || (LAST && CHROMATICITY)
layout(rgba16f) uniform writeonly image3D nextLevel;
#else
layout(r16f) uniform writeonly image3D nextLevel;
#endif
uniform ivec3 gridDims;
uniform vec3 voxelSize;   // the grid's voxel edge per data axis, model units
uniform vec3 boxMin;      // model-space corner of the volume box
uniform vec3 boxSize;
uniform int isPointLight;
uniform vec3 lightDirection;  // direction the light travels, model space, unit (directional)
uniform vec3 lightPosition;   // model space (point light)

struct RayToLight {
    vec3 origin;     // the voxel centre, model space
    vec3 direction;  // unit, towards the light
    float reach;     // how far the ray crosses the box before it leaves it or meets the point light
};

// Distance from `origin` (inside the box) along `direction` to the box's face.
float exitDistance(vec3 origin, vec3 direction) {
    // safeInverse (common/ray_box.glsl, via clip.glsl) makes a zero component, of either sign, a
    // huge positive one: the face to leave by along it is then the upper one, which it never reaches.
    vec3 towards = mix(boxMin, boxMin + boxSize, greaterThanEqual(direction, vec3(0.0)));
    vec3 t = (towards - origin) * safeInverse(direction);
    return max(0.0, min(min(t.x, t.y), t.z));
}

RayToLight rayToLight(ivec3 voxel) {
    RayToLight ray;
    ray.origin = boxMin + (vec3(voxel) + 0.5) * voxelSize;
    vec3 toLight = isPointLight != 0 ? lightPosition - ray.origin : -lightDirection;
    float toPointLight = isPointLight != 0 ? length(toLight) : 3.0e38;
    // A voxel centred exactly on a point light has nothing between it and the light.
    ray.direction = toPointLight > 0.0 ? normalize(toLight) : vec3(0.0, 0.0, 1.0);
    ray.reach = min(toPointLight, exitDistance(ray.origin, ray.direction));
    return ray;
}

vec3 textureCoordinate(vec3 position) { return (position - boxMin) / boxSize; }

uniform float segmentLength;
uniform float referenceLength;  // the TF opacity's reference length (one data voxel)
// What `length` (at most segmentLength) of the ray from `origin` towards the light does to white
// light, (c, T), sampled as the sweep samples a slice's path: about one sample per data voxel, at
// least two, from the far end (the light's side) towards the origin, as the light travels.
vec4 marchSegment(vec3 origin, vec3 direction, float length) {
    vec3 start = textureCoordinate(origin);
    vec3 end = textureCoordinate(origin + length * direction);
    int n = 2 * clamp(int(ceil(0.5 * length / referenceLength)), 1, 8);
    float piece = length / float(n);
    vec4 light = vec4(1.0);
    for (int k = pathIsEmpty(0.5 * (start + end), 0.5 * (end - start)) ? -1 : n - 1; k >= 0; --k) {
        vec3 tc = mix(start, end, (float(k) + 0.5) / float(n));
        vec4 medium = lightSeesMedium(tc) ? classify(volumeValue(tc)) : vec4(0.0);
        float a = correctOpacity(medium.a, piece, referenceLength);
#if GRID_COLOUR
        light = vec4((1.0 - a) * light.rgb + a * medium.rgb, (1.0 - a) * light.a);
#else
        light.a *= 1.0 - a;
#endif
    }
    return light;
}

#if GRID_COLOUR
vec4 texelValue(vec4 light) { return light; }
vec4 levelValue(vec4 texel) { return texel; }
#else
vec4 texelValue(vec4 light) { return vec4(light.a); }
vec4 levelValue(vec4 texel) { return vec4(1.0, 1.0, 1.0, texel.r); }
#endif

#if LEVEL0
void main() {
    ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, gridDims))) return;
    RayToLight ray = rayToLight(voxel);
    imageStore(nextLevel, voxel, texelValue(marchSegment(ray.origin, ray.direction, min(segmentLength, ray.reach))));
}
#else
// The previous level, linear and clamped to its edge. Far ends within one segment of where the
// ray leaves the box or meets the light march that rest instead: the segments there end at the
// face or the light, so the level changes steeply from texel to texel, and a lookup between them
// made doubling's light up to 9 % off beside the faces rays leave by (llvmpipe, a homogeneous box).
uniform sampler3D level;
uniform float span;        // the previous level's segment length, model units
#if GRID_COLOUR
uniform float ringRadius;  // model units; 0: no cone blur at this level
uniform vec2 coneWeights;  // (centre tap, each of the 8 ring taps); centre + 8 ring = 1

// The colour arriving at the far end `far` (texture coordinates), gathered over the cone's ring.
vec3 coneColour(vec3 far, vec3 centre, vec3 direction) {
    if (ringRadius <= 0.0) return centre;
    // Two directions across the ray.
    vec3 helper = abs(direction.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 across1 = normalize(cross(direction, helper));
    vec3 across2 = cross(direction, across1);
    vec3 ring = vec3(0.0);
    for (int k = 0; k < 8; ++k) {
        float angle = float(k) * 0.78539816;
        vec3 tap = far + ringRadius * (cos(angle) * across1 + sin(angle) * across2) / boxSize;
        bool inBox = all(greaterThanEqual(tap, vec3(0.0))) && all(lessThanEqual(tap, vec3(1.0)));
        ring += inBox ? texture(level, tap).rgb : vec3(1.0);  // white beyond the box
    }
    return coneWeights.x * centre + coneWeights.y * ring;
}
#endif
#if LAST && CHROMATICITY
uniform sampler3D colourGrid;  // the colour grid's last level
#endif

void store(ivec3 voxel, vec4 light) {
#if LAST && CHROMATICITY
    light.rgb = texture(colourGrid, textureCoordinate(boxMin + (vec3(voxel) + 0.5) * voxelSize)).rgb;
    imageStore(nextLevel, voxel, light);
#else
    imageStore(nextLevel, voxel, texelValue(light));
#endif
}

void main() {
    ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, gridDims))) return;
    vec4 near = levelValue(texelFetch(level, voxel, 0));
    RayToLight ray = rayToLight(voxel);
    // Nothing to add: no light gets through, or the segment already reaches the box's face or
    // the point light.
    if (near.a == 0.0 || ray.reach <= span) {
        store(voxel, near);
        return;
    }
    vec3 farEnd = ray.origin + span * ray.direction;
    float rest = ray.reach - span;
    vec3 far = textureCoordinate(farEnd);
    vec4 arriving = rest <= segmentLength ? marchSegment(farEnd, ray.direction, rest) : levelValue(texture(level, far));
#if GRID_COLOUR
    arriving.rgb = coneColour(far, arriving.rgb, ray.direction);
#endif
    store(voxel, vec4(near.a * arriving.rgb + near.rgb - near.a, near.a * arriving.a));
}
#endif
