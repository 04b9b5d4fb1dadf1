// The multiple-scattering cache's slope of the once-scattered fluence against the direct light E,
// at one mip level: the regression within each of the level's cells (weight s), solved from the
// moments fluence_resolve.comp stores and the mipmaps sum. A coarse level's slope is its larger
// cells' own, not the mean of its children's: the level the ray caster reads while few photons
// have arrived has about as many per cell as the finest level once refined, so its slope is no
// noisier (docs/multiple-scattering.md, "While it refines"). Levels are solved in order, finest
// first: a coarse cell's largest direct light is the largest of its children's.
#include "volume/direct_slope.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D cacheFluence;     // alpha: the cell's mean weight w
uniform sampler3D onceMoments;      // w phi1 (rgb), w E
uniform sampler3D onceTimesDirect;  // w phi1 E (rgb), w E^2
uniform sampler3D cacheFluxLengths;  // alpha: w times the largest E of the cell's voxel centres
uniform int level;
layout(rgba32f, binding = 0) uniform writeonly image3D directSlopeAtLevel;  // w B (rgb), w E; at `level`
layout(rgba32f, binding = 1) uniform image3D fluxLengthsAtLevel;    // at `level` (above 0)

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, textureSize(onceMoments, level)))) return;
    float w = texelFetch(cacheFluence, c, level).a;
    vec4 once = texelFetch(onceMoments, c, level);
    vec4 onceTimesE = texelFetch(onceTimesDirect, c, level);
    imageStore(directSlopeAtLevel, c, vec4(w * directSlope(w, once, onceTimesE), once.a));
    if (level > 0) {
        // The mipmap averaged the children's largest E; the cap (ray_cast.glsl) needs the largest.
        float largest = 0.0;
        ivec3 finer = textureSize(cacheFluxLengths, level - 1);
        for (int k = 0; k < 8; ++k) {
            ivec3 child = min(2 * c + ivec3(k & 1, (k >> 1) & 1, k >> 2), finer - 1);
            float childWeight = texelFetch(cacheFluence, child, level - 1).a;
            if (childWeight > 0.0) largest = max(largest, texelFetch(cacheFluxLengths, child, level - 1).a / childWeight);
        }
        vec4 lengths = imageLoad(fluxLengthsAtLevel, c);
        imageStore(fluxLengthsAtLevel, c, vec4(lengths.rgb, w * largest));
    }
}
