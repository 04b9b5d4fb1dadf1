// Post-classification through the transfer-function table, shared by the ray caster and the
// light-volume propagation so both see exactly the same colour and opacity.
uniform sampler3D volumeTexture;
uniform sampler2D transferFunction;   // one row of N entries; entry i belongs to value i/(N-1)
uniform float transferFunctionEntries;
uniform vec2 valueScaleOffset;        // TF coordinate = sample * x + y (data range -> [0,1])

// The texel coordinate of a data value in a one-row table of `entries` entries over the TF's range.
float transferFunctionCoordinate(float value, float entries) {
    float x = clamp(value * valueScaleOffset.x + valueScaleOffset.y, 0.0, 1.0);
    return (x * (entries - 1.0) + 0.5) / entries;
}

#include "volume/reconstruction.glsl"

// The data's normalised value at texture coordinate tc, as the options reconstruct it.
float volumeValue(vec3 tc) { return reconstruct(volumeTexture, tc).r; }

vec4 classify(float value) {
    return texture(transferFunction, vec2(transferFunctionCoordinate(value, transferFunctionEntries), 0.5));
}

// The opacity alone, from a one-channel copy of the table's alpha (R32F): where the light reads
// nothing else of the transfer function, a quarter of the channels to filter, the same values.
float classifyOpacity(sampler2D opacities, float value) {
    return texture(opacities, vec2(transferFunctionCoordinate(value, transferFunctionEntries), 0.5)).r;
}

// Opacity of a path `pathLength` long when the TF's opacity is defined per `referenceLength`.
float correctOpacity(float alpha, float pathLength, float referenceLength) {
    return 1.0 - pow(1.0 - min(alpha, 1.0), pathLength / referenceLength);
}
