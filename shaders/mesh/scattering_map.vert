layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inTexcoord;
uniform mat4 model;
uniform mat3 normalMatrix;
out vec3 vsModelPosition;
out vec3 vsWorldPosition;
out vec3 vsWorldNormal;
out vec2 vsTexcoord;
void main() {
    vsModelPosition = inPosition;
    vsWorldPosition = (model * vec4(inPosition, 1.0)).xyz;
    vsWorldNormal = normalMatrix * inNormal;
    vsTexcoord = inTexcoord;
}
