layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
uniform mat4 model;
uniform mat3 normalMatrix;
out vec3 vsWorldPosition;
out vec3 vsWorldNormal;
void main() {
    vsWorldPosition = (model * vec4(inPosition, 1.0)).xyz;
    vsWorldNormal = normalMatrix * inNormal;
}
