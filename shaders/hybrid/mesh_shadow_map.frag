// Marks each texel of a mesh shadow map with the nearest mesh: scattering meshes skip their own
// entries (the light buffer already holds their self-shadowing).
uniform uint meshId;  // 1 + the mesh's index
layout(location = 0) out uint outId;
void main() { outId = meshId; }
