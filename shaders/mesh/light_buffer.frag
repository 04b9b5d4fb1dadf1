in vec3 worldPosition;
in vec3 worldNormal;
layout(location = 0) out vec4 outPosition;  // w = 1 marks a covered texel (cleared to 0)
layout(location = 1) out vec4 outNormal;
void main() {
    vec3 n = normalize(worldNormal);
    // Two-sided: the surface the light sees faces it, whichever way the mesh winds.
    if (!gl_FrontFacing) n = -n;
    outPosition = vec4(worldPosition, 1.0);
    outNormal = vec4(n, 0.0);
}
