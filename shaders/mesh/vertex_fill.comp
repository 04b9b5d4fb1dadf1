// One round of the vertex-radiosity fill (src/mesh/vertex_radiosity_pass.h): every vertex no
// map saw that has a neighbour known before this round takes the mean of those neighbours.
// The fourth channel stamps when a vertex became known: 1 seen by a map, r + 1 filled in round
// r, 0 not yet. Round r reads stamps 1..r only, so a value set in a round counts from the next
// one, whatever order the invocations run in (the order-independent breadth-first fill), and
// vertices written in this round are never read by it.
layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Radiosity { vec4 radiosity[]; };
layout(std430, binding = 1) readonly buffer AdjacencyStart { uint neighbourStart[]; };
layout(std430, binding = 2) readonly buffer Adjacency { uint neighbours[]; };
layout(std430, binding = 3) buffer Filled { uint filledInRound[]; };  // per round, zeroed per run
uniform int vertexCount;
uniform int fillRound;  // r, from 1

void main() {
    // The round before filled nothing: the fill has ended (or only islands no map sees remain).
    if (fillRound > 1 && filledInRound[fillRound - 2] == 0u) return;
    int i = int(gl_GlobalInvocationID.x);
    if (i >= vertexCount || radiosity[i].w != 0.0) return;
    vec3 sum = vec3(0.0);
    float known = 0.0;
    for (uint e = neighbourStart[i]; e < neighbourStart[i + 1]; ++e) {
        vec4 neighbour = radiosity[neighbours[e]];
        if (neighbour.w > 0.0 && neighbour.w <= float(fillRound)) {
            sum += neighbour.rgb;
            known += 1.0;
        }
    }
    if (known == 0.0) return;
    radiosity[i] = vec4(sum / known, float(fillRound + 1));
    atomicAdd(filledInRound[fillRound - 1], 1u);
}
