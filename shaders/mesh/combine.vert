layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
uniform mat4 model;
uniform mat4 viewProjection;
uniform mat3 normalMatrix;
out vec3 modelPosition;
out vec3 modelNormal;
out vec3 worldPosition;
out vec3 worldNormal;
void main() {
    modelPosition = inPosition;
    modelNormal = inNormal;
    vec4 world = model * vec4(inPosition, 1.0);
    worldPosition = world.xyz;
    worldNormal = normalMatrix * inNormal;
    gl_Position = viewProjection * world;
}
