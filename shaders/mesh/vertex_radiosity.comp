// Vertex radiosity: each mesh vertex looked up in the scattering maps as the combine pass looks
// up pixels (shaders/mesh/map_lookup.glsl). Vertices a layer sees are stamped known (a = 1), the
// others 0; vertex_fill.comp then fills those from their neighbours.
layout(local_size_x = 64) in;

#include "mesh/map_lookup.glsl"

#include "mesh/mesh_vertices.glsl"
layout(std430, binding = 1) writeonly buffer Radiosity { vec4 radiosityOut[]; };
uniform int vertexCount;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= vertexCount) return;
    vec3 p = meshPosition(uint(i));
    vec3 n = meshNormal(uint(i));
    float length2 = dot(n, n);
    n = length2 > 0.0 ? n * inversesqrt(length2) : vec3(0.0, 0.0, 1.0);
    MapLookup maps = lookUpScatteringMaps(p, n);
    radiosityOut[i] = maps.weight > 0.0 ? vec4(maps.radiosity, 1.0) : vec4(0.0);
}
