// The meshes seen from a light (hybrid scenes): depth, and which mesh is nearest.
layout(location = 0) in vec3 inPosition;
uniform mat4 modelToClip;
void main() { gl_Position = modelToClip * vec4(inPosition, 1.0); }
