// Light buffer: one layer per light, each the object seen from that light (orthographic for
// directional lights, perspective for point lights). Invocation i draws layer i.
layout(triangles, invocations = MAX_LIGHTS) in;
layout(triangle_strip, max_vertices = 3) out;
uniform int lightCount;
uniform mat4 lightViewProjection[MAX_LIGHTS];
in vec3 vsWorldPosition[];
in vec3 vsWorldNormal[];
out vec3 worldPosition;
out vec3 worldNormal;
void main() {
    if (gl_InvocationID >= lightCount) return;
    for (int v = 0; v < 3; ++v) {
        gl_Layer = gl_InvocationID;
        worldPosition = vsWorldPosition[v];
        worldNormal = vsWorldNormal[v];
        gl_Position = lightViewProjection[gl_InvocationID] * vec4(vsWorldPosition[v], 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
