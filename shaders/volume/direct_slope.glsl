// The regression of the once-scattered fluence phi1 on the direct light E within a region (a
// cell, or a filter's neighbourhood), from its weighted moments: w, w phi1 (rgb) and w E,
// w phi1 E (rgb) and w E^2. B = cov(phi1, E) / var(E), the variance raised by
// kSlopeDamping times the mean of E^2 so that regions whose E barely varies (all lit or all in
// shadow) keep a small slope. Measured on the bench's bonsai and engine
// (docs/multiple-scattering.md): 0.03 let noise in (engine 25 %), 0.3 took a little of the
// bonsai's gain (11.4 against 10.8 %).
const float kSlopeDamping = 0.1;

vec3 directSlope(float w, vec4 once, vec4 onceTimesE) {
    if (!(w > 0.0)) return vec3(0.0);
    float meanE = once.a / w;
    float variance = max(onceTimesE.a / w - meanE * meanE, 0.0);
    return (onceTimesE.rgb / w - (once.rgb / w) * meanE) / (variance + kSlopeDamping * onceTimesE.a / w + 1e-30);
}
