// Light buffer: the object seen from one light (orthographic for directional lights, perspective
// for point lights), drawn once per light into that light's layer. (A geometry shader that
// fanned every triangle out to all layers cost 1.5 ms for the bunny on an H200, whose raster
// stages run on a small graphics partition.)
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inTexcoord;
uniform mat4 model;
uniform mat3 normalMatrix;
uniform mat4 lightViewProjection;
out vec3 worldPosition;
out vec3 worldNormal;
out vec2 texcoord;
void main() {
    worldPosition = (model * vec4(inPosition, 1.0)).xyz;
    worldNormal = normalMatrix * inNormal;
    texcoord = inTexcoord;
    gl_Position = lightViewProjection * vec4(worldPosition, 1.0);
}
