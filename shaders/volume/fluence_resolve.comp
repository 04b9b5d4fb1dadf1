// The multiple-scattering cache's textures from its photon sums (fluence_photons.comp): per cell,
// the fluence of light scattered at least once (rgb), each channel's flux vector (xyz: where and
// how strongly that channel's light flows), the mean channel's traceless second moment
// (xx - 1/3, yy - 1/3, xy, xz; yz in the red flux's alpha), all in the
// lights' units (colour x intensity), averaged over the cell with the weight s
// (fluence_density.comp), and premultiplied by the cell's mean weight, which the fluence
// texture's alpha holds. Readers divide the filtered values by the filtered weight: cells
// interpolate in proportion to the medium they hold, and cells without medium, which hold no
// estimate, do not pull their neighbours' values towards zero.
#include "volume/direct_slope.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

#include "volume/fluence_sums.glsl"
layout(std430, binding = 3) readonly buffer Weights { float cellWeight[]; };  // fluence_density.comp
layout(rgba32f, binding = 0) uniform writeonly image3D fluence;
layout(rgba32f, binding = 1) uniform writeonly image3D fluxRed;    // and the second moment's yz
layout(rgba32f, binding = 2) uniform writeonly image3D fluxGreen;  // and the largest direct light of
                                                                   // the cell's voxel centres
layout(rgba32f, binding = 3) uniform writeonly image3D fluxBlue;
layout(rgba32f, binding = 4) uniform writeonly image3D secondMoment;
// The once-scattered fluence's regression on the direct light E: its moments, w phi1 (rgb) and
// w E, w phi1 E (rgb) and w E^2 (the first frames' filter pools them, fluence_denoise.comp), and
// the cell's own slope, w B (rgb) and w E.
layout(rgba32f, binding = 5) uniform writeonly image3D onceMoments;
layout(rgba32f, binding = 6) uniform writeonly image3D onceTimesDirect;
layout(rgba32f, binding = 7) uniform writeonly image3D cellSlope;
layout(std430, binding = 4) readonly buffer DirectMoments { vec4 cellDirect[]; };  // fluence_density.comp
uniform ivec3 cacheCells;
uniform float sumsToFluence;  // power per photon / (photons x quanta per unit)
uniform float cellVolume;     // model units^3

// A slot's 64-bit two's-complement sum.
SumsSlot base;  // the cell's first slot

// Slot base + k's 64-bit two's-complement sum.
float slotValue(uint k) {
    SumsSlot s = nextSlot(base, k);
    return float(int(sumsWord(s, 1u))) * 4294967296.0 + float(sumsWord(s, 0u));
}

vec3 slotVector(uint k) { return vec3(slotValue(k), slotValue(k + 1u), slotValue(k + 2u)); }

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, cacheCells))) return;
    uint cellIndex = uint((c.z * cacheCells.y + c.y) * cacheCells.x + c.x);
    base = sumsOfCell(cellIndex);
    // The weighted mean fluence is the photons' sum over the cell's weight; times the mean weight,
    // the weight cancels.
    float scale = sumsToFluence / cellVolume;
    vec3 phi = slotVector(0u) * scale;
    vec3 red = slotVector(3u) * scale, green = slotVector(6u) * scale, blue = slotVector(9u) * scale;
    float w = cellWeight[cellIndex] / cellVolume;
    imageStore(fluence, c, vec4(phi, w));
    vec4 moment = vec4(slotValue(12u), slotValue(13u), slotValue(14u), slotValue(15u)) * scale;
    imageStore(fluxRed, c, vec4(red, slotValue(16u) * scale));
    imageStore(fluxGreen, c, vec4(green, w * cellDirect[cellIndex].z));
    imageStore(fluxBlue, c, vec4(blue, 0.0));
    imageStore(secondMoment, c, moment);
    vec2 moments = cellDirect[cellIndex].xy / cellVolume;  // w E, w E^2 (cell means)
    vec4 once = vec4(slotVector(17u) * scale, moments.x);
    vec4 onceTimesE = vec4(slotVector(20u) * scale, moments.y);
    imageStore(onceMoments, c, once);
    imageStore(onceTimesDirect, c, onceTimesE);
    imageStore(cellSlope, c, vec4(w * directSlope(w, once, onceTimesE), once.a));
}
