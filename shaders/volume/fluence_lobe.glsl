// The multiple-scattering cache's light towards a viewer, from a cell's (or a filtered sample's)
// values: shared by the view pass (fluence_view.comp, once per cell and camera move) and the ray
// caster's per-sample form (ray_cast.glsl, CACHE_PER_SAMPLE).
//
// The radiance of each channel is taken as the HG lobe with the same first moment as the cell's
// light of that channel, phi p_HG(k, w . F / |F|), k = |F| / phi; the HG phase function convolves it to
// phi p_HG(g k, v . F / |F|) towards the viewer v (the Legendre coefficients of HG lobes
// multiply: g^l k^l). The lobe's second band is then replaced by the one the photons measured
// (docs/multiple-scattering.md).

// Within a mean free path of a lit surface the once-scattered fluence levels off while the
// direct light keeps rising (docs/multiple-scattering.md).
const float kDirectBeyondLargest = 2.0;
const float kFourPi = 12.5663706;

// Per channel, the share of the fluence that travels towards v, per steradian; g: the phase
// function's mean cosine; red, green, blue: each channel's flux vector.
vec3 lobeTowards(vec3 v, float g, vec4 weighted, vec3 red, vec3 green, vec3 blue, float mYz, vec4 m) {
    // Each channel's own direction and mean cosine (docs/multiple-scattering.md, "Each channel's
    // own angular moments"); a zero vector reads as isotropic.
    vec3 fluxLength = vec3(length(red), length(green), length(blue));
    vec3 k = min(fluxLength / max(weighted.rgb, vec3(1e-30)), vec3(0.99));
    vec3 cosTheta = mix(vec3(0.0), vec3(dot(red, v), dot(green, v), dot(blue, v)) / max(fluxLength, vec3(1e-30)),
                        greaterThan(fluxLength, vec3(0.0)));
    vec3 gk = g * k;
    vec3 d = 1.0 + gk * gk - 2.0 * gk * cosTheta;
    vec3 lobe = (1.0 - gk * gk) / (kFourPi * d * sqrt(d));
    // Band 2: (5 / 4 pi) g^2 times the measured 3/2 v.M.v / phi in place of the lobe's k^2 P2(cos).
    float vMv = m.x * v.x * v.x + m.y * v.y * v.y - (m.x + m.y) * v.z * v.z +
                2.0 * (m.z * v.x * v.y + m.w * v.x * v.z + mYz * v.y * v.z);
    float meanPhi = (weighted.r + weighted.g + weighted.b) / 3.0;
    float measured = meanPhi > 0.0 ? 1.5 * vMv / meanPhi : 0.0;
    vec3 p2 = 1.5 * cosTheta * cosTheta - 0.5;
    lobe += (5.0 / kFourPi) * g * g * (measured - k * k * p2);
    return max(lobe, vec3(0.0));
}

// The cache's light towards v at a point, premultiplied by the weight w as the cache holds it:
// at the mean direct light of the point's cell (rgb) and w; its slope against the direct light
// (rgb) and w times that mean; w times the largest direct light the slope applies to.
struct CacheTowardsViewer {
    vec4 atMean;
    vec4 slope;
    float cap;
};

// The cache's six textures at the point (FluenceCache, premultiplied by w): weighted (w phi, w;
// w > 0), redAndYz (red flux, M_yz), greenAndLargest (green flux, the largest direct light),
// blue (blue flux), moment, slope. The slope's direct light is taken at most
// kDirectBeyondLargest times the largest a voxel centre of the cell has.
CacheTowardsViewer cacheTowards(vec3 v, float g, vec4 weighted, vec4 redAndYz, vec4 greenAndLargest, vec4 blue,
                                vec4 moment, vec4 slope) {
    vec3 lobe = lobeTowards(v, g, weighted, redAndYz.xyz, greenAndLargest.xyz, blue.xyz, redAndYz.w, moment);
    return CacheTowardsViewer(vec4(weighted.rgb * lobe, weighted.a), vec4(slope.rgb * lobe, slope.a),
                              kDirectBeyondLargest * greenAndLargest.a);
}
