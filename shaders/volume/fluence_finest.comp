// The multiple-scattering cache's values at its finest cells while they hold few photons
// (FluenceCache::settle: while the cache refines, and on grids finer than its photons once
// refined), so that its readers (the view pass, the ray caster's per-sample form)
// read level 0 whatever the photons so far. The fluence and its slope against the direct light
// are the filtered ones (fluence_denoise.comp). The light's angular shape needs more photons per
// cell: it is taken from the read level (FluenceCache::poolingLevels' shape level, whose cells hold
// enough photons), the flux and the second moment as that level's ratios to its
// fluence (the lobe's mean cosine and second band). The cell's largest direct light stays: it is
// exact at every level.
//
// Each invocation writes level 0 of the cache's textures at its own cell only, and reads level 0
// there alone (the read level's finer end, when it is 0, is that cell's texel).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D cacheFluence;  // w phi (rgb), w: the photons' estimate, mipmapped
uniform sampler3D cacheFluxRed;    // and the second moment's yz
uniform sampler3D cacheFluxGreen;  // and the largest direct light (the finest cell's is kept)
uniform sampler3D cacheFluxBlue;
uniform sampler3D cacheSecondMoment;
uniform sampler3D denoised;       // w phi (rgb), w (fluence_denoise.comp; the cells' own where it did not run)
uniform sampler3D denoisedSlope;  // w B (rgb), w E
uniform float readLevel;         // >= 0
layout(rgba32f, binding = 0) uniform writeonly image3D fluenceAtFinest;
layout(rgba32f, binding = 1) uniform writeonly image3D fluxRedAtFinest;
layout(rgba32f, binding = 2) uniform image3D fluxGreenAtFinest;
layout(rgba32f, binding = 3) uniform writeonly image3D fluxBlueAtFinest;
layout(rgba32f, binding = 4) uniform writeonly image3D secondMomentAtFinest;
layout(rgba32f, binding = 5) uniform writeonly image3D directSlopeAtFinest;

// A texture's weighted value at the read level at cell c (centre tc): the fluence's alpha there
// is its weight.
vec4 atReadLevel(sampler3D t, ivec3 c, vec3 tc) {
    int below = int(readLevel);
    float blend = readLevel - float(below);
    vec4 value = below == 0 ? texelFetch(t, c, 0) : textureLod(t, tc, float(below));
    return blend > 0.0 ? mix(value, textureLod(t, tc, float(below + 1)), blend) : value;
}

float meanChannel(vec3 v) { return (v.r + v.g + v.b) / 3.0; }

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    ivec3 size = textureSize(cacheFluence, 0);
    if (any(greaterThanEqual(c, size))) return;
    vec4 own = texelFetch(denoised, c, 0);
    float w = own.a;
    vec3 tc = (vec3(c) + 0.5) / vec3(size);
    vec4 fluence = atReadLevel(cacheFluence, c, tc);
    float inverseWeight = fluence.a > 0.0 ? 1.0 / fluence.a : 0.0;
    fluence *= inverseWeight;
    vec4 red = atReadLevel(cacheFluxRed, c, tc) * inverseWeight;
    vec3 green = atReadLevel(cacheFluxGreen, c, tc).xyz * inverseWeight;
    vec3 blue = atReadLevel(cacheFluxBlue, c, tc).xyz * inverseWeight;
    vec4 moment = atReadLevel(cacheSecondMoment, c, tc) * inverseWeight;
    float ownLargest = imageLoad(fluxGreenAtFinest, c).a;
    // The cell's fluence over the read level's: per channel, and for the mean channel.
    vec3 phi = w > 0.0 ? own.rgb / w : vec3(0.0);
    vec3 scale = mix(vec3(0.0), phi / max(fluence.rgb, vec3(1e-30)), greaterThan(fluence.rgb, vec3(0.0)));
    float meanScale = meanChannel(fluence.rgb) > 0.0 ? meanChannel(phi) / meanChannel(fluence.rgb) : 0.0;
    imageStore(fluenceAtFinest, c, vec4(w * phi, w));
    imageStore(fluxRedAtFinest, c, vec4(w * scale.r * red.xyz, w * meanScale * red.w));
    imageStore(fluxGreenAtFinest, c, vec4(w * scale.g * green, ownLargest));
    imageStore(fluxBlueAtFinest, c, vec4(w * scale.b * blue, 0.0));
    imageStore(secondMomentAtFinest, c, w * meanScale * moment);
    imageStore(directSlopeAtFinest, c, texelFetch(denoisedSlope, c, 0));
}
