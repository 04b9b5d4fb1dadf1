// Post-classification through the transfer-function table, shared by the ray caster and the
// light-volume propagation so both see exactly the same colour and opacity.
uniform sampler3D volumeTexture;
uniform sampler2D transferFunction;   // one row of N entries; entry i belongs to value i/(N-1)
uniform float transferFunctionEntries;
uniform vec2 valueScaleOffset;        // TF coordinate = sample * x + y (data range -> [0,1])

vec4 classify(float value) {
    float x = clamp(value * valueScaleOffset.x + valueScaleOffset.y, 0.0, 1.0);
    float u = (x * (transferFunctionEntries - 1.0) + 0.5) / transferFunctionEntries;
    return texture(transferFunction, vec2(u, 0.5));
}

// Opacity of a path `pathLength` long when the TF's opacity is defined per `referenceLength`.
float correctOpacity(float alpha, float pathLength, float referenceLength) {
    return 1.0 - pow(1.0 - min(alpha, 1.0), pathLength / referenceLength);
}
