// The multiple-scattering cache's fluence at its finest cells, filtered while few photons have
// arrived (FluenceCache::denoise): a cross-bilateral filter whose range terms are the cells' own
// medium weight w and mean direct light E, both exact (fluence_density.comp), so cells average
// with the neighbours that hold medium like theirs and are lit like them, and a dense lit surface
// keeps its light apart from its dark inside and the thin medium around it. The photons' own
// values are too noisy to guide it. The spatial width shrinks to nothing as the cache refines
// (`spatialSigma`, from FluenceCache::poolingLevels); docs/multiple-scattering.md has the
// measurements behind the widths. Where the reach asked for is wider than the window, each finest
// cell pools a coarser level's cells instead (`gridLevel`: the mipmaps' weighted sums, so they are
// coarser cells of the same estimate), still chosen by their likeness to the finest cell.
//
// The once-scattered fluence's regression on E (volume/direct_slope.glsl) is pooled with the same
// weights, and the pooled fluence is carried along its line from the neighbourhood's mean E to
// the cell's own: the slope and the mean the readers combine then belong to one line, as they do
// once refined. (A coarser level's slope beside the finest cells' mean counted the light near a
// lit face twice: the GL test's dense block read 1.45 times the truth's multiple part.)
#include "volume/direct_slope.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D cacheFluence;     // w phi (rgb), w
uniform sampler3D onceMoments;      // w phi1 (rgb), w E
uniform sampler3D onceTimesDirect;  // w phi1 E (rgb), w E^2
uniform int gridLevel;              // the mip level of the cells pooled (mipmapped above 0)
uniform float spatialSigma;         // in that level's cells, > 0
uniform int radius;                 // cells, at most kRadius: where the spatial weight is still above 2 %
uniform float rangeWidening;        // >= 1: the range terms' widths over kDirectWidth and kWeightWidth
layout(rgba32f, binding = 0) uniform writeonly image3D denoised;       // w phi (rgb), w
layout(rgba32f, binding = 1) uniform writeonly image3D denoisedSlope;  // w B (rgb), w E

const int kRadius = 2;
// The range terms' widths, in (a - b) / (a + b) of the two cells' values.
const float kDirectWidth = 0.5;
const float kWeightWidth = 0.2;

// The gridLevel cells that hold the workgroup's cells and a margin of kRadius, read once: per
// cell w phi and w, the slope's moments, and the base-2 logarithms of E and w (for cells without
// medium, zero: they add nothing).
const int kTile = 4 + 2 * kRadius;
shared vec4 tileFluence[kTile * kTile * kTile];
shared vec4 tileOnce[kTile * kTile * kTile];
shared vec4 tileOnceTimesDirect[kTile * kTile * kTile];
shared vec2 tileGuide[kTile * kTile * kTile];

vec2 guideOf(vec4 fluence, vec4 once) { return vec2(log2(max(once.a / fluence.a, 1e-30)), log2(fluence.a)); }

ivec3 tileOrigin() { return ((ivec3(gl_WorkGroupID) * 4) >> gridLevel) - kRadius; }

void loadTile(ivec3 size) {
    ivec3 origin = tileOrigin();
    for (int i = int(gl_LocalInvocationIndex); i < kTile * kTile * kTile; i += 64) {
        ivec3 n = origin + ivec3(i % kTile, (i / kTile) % kTile, i / (kTile * kTile));
        vec4 fluence = vec4(0.0), once = vec4(0.0), onceTimesE = vec4(0.0);
        vec2 guide = vec2(0.0);
        if (all(greaterThanEqual(n, ivec3(0))) && all(lessThan(n, size))) fluence = texelFetch(cacheFluence, n, gridLevel);
        if (fluence.a > 0.0) {
            once = texelFetch(onceMoments, n, gridLevel);
            onceTimesE = texelFetch(onceTimesDirect, n, gridLevel);
            guide = guideOf(fluence, once);
        } else {
            fluence = vec4(0.0);
        }
        tileFluence[i] = fluence;
        tileOnce[i] = once;
        tileOnceTimesDirect[i] = onceTimesE;
        tileGuide[i] = guide;
    }
}

void main() {
    loadTile(textureSize(cacheFluence, gridLevel));
    barrier();
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, textureSize(cacheFluence, 0)))) return;
    vec4 ownFluence = texelFetch(cacheFluence, c, 0);
    // The pooled cell that holds c, and c's centre in that level's cells.
    ivec3 local = (c >> gridLevel) - tileOrigin();
    int own = (local.z * kTile + local.y) * kTile + local.x;
    vec3 centre = (vec3(c) + 0.5) / float(1 << gridLevel) - 0.5 - vec3(c >> gridLevel);
    if (!(ownFluence.a > 0.0)) {
        imageStore(denoised, c, vec4(0.0));
        imageStore(denoisedSlope, c, vec4(0.0));
        return;
    }
    // (a - b) / (a + b) is about ln(a / b) / 2; each term is a Gaussian, exp2 of a sum.
    const float kHalfLn2 = 0.34657359, kLog2e = 1.44269504;
    vec2 widths = rangeWidening * vec2(kDirectWidth, kWeightWidth);
    vec2 guideScale = -kLog2e * kHalfLn2 * kHalfLn2 / (widths * widths);
    float spatialScale = -kLog2e / (2.0 * spatialSigma * spatialSigma);
    vec4 ownOnce = texelFetch(onceMoments, c, 0);
    vec2 ownGuide = guideOf(ownFluence, ownOnce);
    vec4 fluence = vec4(0.0), once = vec4(0.0), onceTimesE = vec4(0.0);
    for (int z = -radius; z <= radius; ++z)
        for (int y = -radius; y <= radius; ++y)
            for (int x = -radius; x <= radius; ++x) {
                int n = own + (z * kTile + y) * kTile + x;
                vec2 d = tileGuide[n] - ownGuide;
                vec3 offset = vec3(x, y, z) - centre;
                float k = exp2(dot(guideScale, d * d) + spatialScale * dot(offset, offset));
                fluence += k * tileFluence[n];
                once += k * tileOnce[n];
                onceTimesE += k * tileOnceTimesDirect[n];
            }
    if (!(fluence.a > 0.0)) {  // c beyond an odd-sized level's last cell, with no medium around it
        fluence = ownFluence;
        once = ownOnce;
        onceTimesE = texelFetch(onceTimesDirect, c, 0);
    }
    vec3 slope = directSlope(fluence.a, once, onceTimesE);
    float w = ownFluence.a, ownE = ownOnce.a / w;
    vec3 phi = max(fluence.rgb / fluence.a + slope * (ownE - once.a / fluence.a), vec3(0.0));
    imageStore(denoised, c, vec4(w * phi, w));
    imageStore(denoisedSlope, c, vec4(w * slope, w * ownE));
}
