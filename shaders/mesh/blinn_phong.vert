layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;

uniform mat4 model;
uniform mat4 viewProjection;
uniform mat3 normalMatrix;   // inverse transpose of model's upper 3x3

out vec3 worldPosition;
out vec3 worldNormal;

void main() {
    vec4 world = model * vec4(inPosition, 1.0);
    worldPosition = world.xyz;
    worldNormal = normalMatrix * inNormal;
    gl_Position = viewProjection * world;
}
