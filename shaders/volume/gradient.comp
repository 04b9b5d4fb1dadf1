// The gradient volume (sss::VolumeRenderOptions::gradientVolume): per voxel, the central
// differences of the normalised data one voxel apart on each axis, with clamp-to-edge indices.
// Sampled trilinearly, these give exactly the ray caster's on-the-fly gradient (the difference of
// two trilinear samples one voxel apart is the trilinear interpolation of the per-voxel central
// differences), so the ray caster reads one texel instead of six.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D volumeTexture;
uniform ivec3 volumeDims;
uniform int storeValues;
uniform float encodeScale;   // d in [-1, 1] is stored as d * encodeScale + encodeOffset
uniform float encodeOffset;  // (GradientEncoding: RGBA8 or RGBA16, the format bound)
layout(binding = 0) uniform writeonly image3D gradients;

float at(ivec3 i) { return texelFetch(volumeTexture, clamp(i, ivec3(0), volumeDims - 1), 0).r; }

void main() {
    ivec3 i = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(i, volumeDims))) return;
    vec3 d = vec3(at(i + ivec3(1, 0, 0)) - at(i - ivec3(1, 0, 0)), at(i + ivec3(0, 1, 0)) - at(i - ivec3(0, 1, 0)),
                  at(i + ivec3(0, 0, 1)) - at(i - ivec3(0, 0, 1)));
    imageStore(gradients, i, vec4(d * encodeScale + encodeOffset, storeValues != 0 ? at(i) : 0.0));
}
