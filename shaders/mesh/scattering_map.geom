// Scattering maps: the object seen from CAMERA_COUNT orthographic cameras locked to the model,
// one layer each, all in one draw (invocation k draws layer k).
layout(triangles, invocations = CAMERA_COUNT) in;
layout(triangle_strip, max_vertices = 3) out;
uniform mat4 cameraViewProjection[CAMERA_COUNT];  // model space -> clip space of camera k
in vec3 vsModelPosition[];
in vec3 vsWorldPosition[];
in vec3 vsWorldNormal[];
in vec2 vsTexcoord[];
out vec3 worldPosition;
out vec3 worldNormal;
out vec2 texcoord;
invariant gl_Position;  // the depth pre-pass and the accumulating passes must rasterise alike
void main() {
    for (int v = 0; v < 3; ++v) {
        gl_Layer = gl_InvocationID;
        worldPosition = vsWorldPosition[v];
        worldNormal = vsWorldNormal[v];
        texcoord = vsTexcoord[v];
        gl_Position = cameraViewProjection[gl_InvocationID] * vec4(vsModelPosition[v], 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
