// Eye pass, step 1: the light each voxel scatters, TF colour * (ambient + diffuse * sum E c l),
// the source that the eye sweep (light_propagation.comp with EYE_PASS) carries towards the viewer;
// in a hybrid scene without the light the meshes hide from the voxel (MESH_SHADOWS).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

#include "common/lights.glsl"
#include "volume/transfer_function.glsl"
#include "volume/mesh_visibility.glsl"

uniform sampler3D lightVolumes[MAX_LIGHTS];
layout(rgba16f) uniform writeonly image3D litColour;
uniform ivec3 dims;             // of the light volume (and of litColour)
uniform vec3 boxMin;
uniform vec3 voxelSize;         // model units
uniform mat4 modelToWorld;
uniform float ambientStrength;
uniform float diffuseStrength;

void main() {
    ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, dims))) return;
    vec3 tc = (vec3(voxel) + 0.5) / vec3(dims);
    vec3 color = classify(volumeValue(tc)).rgb;
    vec3 worldPosition = (modelToWorld * vec4(boxMin + (vec3(voxel) + 0.5) * voxelSize, 1.0)).xyz;
    vec3 lit = ambientStrength * color;
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        vec3 radiance;
        lightDirectionAt(i, worldPosition, radiance);
        vec4 arriving = texelFetch(lightVolumes[i], voxel, 0);
        lit += diffuseStrength * color * radiance * arriving.rgb * (arriving.a * meshVisibility(i, worldPosition));
    }
    imageStore(litColour, voxel, vec4(lit, 1.0));
}
