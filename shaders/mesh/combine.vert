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
#ifndef VERTEX_EFFECTIVE
#define VERTEX_EFFECTIVE 0
#endif
#if VERTEX_EFFECTIVE
// A textured vertex estimate's entries' part of the rule per vertex (shaders/mesh/vertex_estimate.comp).
out vec3 vertexEffective;
layout(std430, binding = 1) readonly buffer VertexEffective { vec4 effectiveOfVertex[]; };
#endif
void main() {
    modelPosition = inPosition;
    modelNormal = inNormal;
    texcoord = inTexcoord;
    vertexRadiosity = radiosityOfVertex[gl_VertexID].rgb;
#if VERTEX_EFFECTIVE
    vertexEffective = effectiveOfVertex[gl_VertexID].rgb;
#endif
    vec4 world = model * vec4(inPosition, 1.0);
    worldPosition = world.xyz;
    worldNormal = normalMatrix * inNormal;
    gl_Position = viewProjection * world;
}
