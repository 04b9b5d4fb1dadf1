// Empty space for the light volume's medium samples (src/volume/empty_space.h): per brick of
// brickVoxels^3 data voxels, 0 where the brick and its 26 neighbours sample no opacity under the
// current transfer function.
uniform int skipEmpty;
uniform sampler3D occupiedNeighbourhoods;
uniform ivec3 dataDims;
uniform int brickVoxels;
uniform vec3 textureToBrick;  // dataDims / brickVoxels: a brick by a float product (ray_cast.glsl)

// Whether every sample of a path centred at `centre` and reaching `halfExtent` to either side
// (texture coordinates) lies within a brick of empty bricks: then each has opacity 0 and leaves
// the light exactly as it is.
bool pathIsEmpty(vec3 centre, vec3 halfExtent) {
    if (skipEmpty == 0) return false;
    vec3 inVoxels = abs(halfExtent) * vec3(dataDims);
    if (max(max(inVoxels.x, inVoxels.y), inVoxels.z) > float(brickVoxels)) return false;
    ivec3 brick = clamp(ivec3(centre * textureToBrick), ivec3(0), textureSize(occupiedNeighbourhoods, 0) - 1);
    return texelFetch(occupiedNeighbourhoods, brick, 0).r == 0.0;
}
