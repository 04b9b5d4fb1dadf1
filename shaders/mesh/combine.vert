layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inTexcoord;
uniform mat4 model;
uniform mat4 viewProjection;
uniform mat3 normalMatrix;
out vec3 modelPosition;
out vec3 modelNormal;
out vec3 worldPosition;
out vec3 worldNormal;
out vec2 texcoord;
out vec3 vertexRadiosity;
// Per vertex, from src/mesh/vertex_radiosity_pass.cpp: rgb radiosity (filled everywhere).
layout(std430, binding = 0) readonly buffer VertexRadiosity { vec4 radiosityOfVertex[]; };
void main() {
    modelPosition = inPosition;
    modelNormal = inNormal;
    texcoord = inTexcoord;
    vertexRadiosity = radiosityOfVertex[gl_VertexID].rgb;
    vec4 world = model * vec4(inPosition, 1.0);
    worldPosition = world.xyz;
    worldNormal = normalMatrix * inNormal;
    gl_Position = viewProjection * world;
}
