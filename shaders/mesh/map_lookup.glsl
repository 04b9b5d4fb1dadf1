// Reading a surface point's radiosity from the scattering maps (Dal Corso et al. 2017, pass 3),
// shared by the combine pass (per pixel) and the vertex-radiosity pass (per vertex): look the
// point up in every map like a shadow map and average the layers that see it.
uniform sampler2DArray scatteringMaps;   // rgb: radiosity summed over frames, a: frames (coverage)
uniform sampler2DArray scatteringDepth;  // depth of each layer's camera view
uniform int cameraCount;
uniform mat4 cameraViewProjection[MAX_CAMERAS];  // model space -> clip space of camera k
uniform vec3 cameraAxis[MAX_CAMERAS];            // model space, from the object towards camera k
uniform float depthBias;     // window-space depth
uniform float seamShrink;    // model units

struct MapLookup {
    vec3 radiosity;  // weighted mean over the layers that see the point
    float weight;    // 0: no layer sees it
    vec3 covered;    // mean over every layer with a surface at the point's texel
    float coverage;  // layers counted in covered
};

// p, n: model-space position and unit normal.
MapLookup lookUpScatteringMaps(vec3 p, vec3 n) {
    ivec2 size = textureSize(scatteringDepth, 0).xy;
    MapLookup result = MapLookup(vec3(0.0), 0.0, vec3(0.0), 0.0);
    vec3 weighted = vec3(0.0);
    for (int k = 0; k < cameraCount; ++k) {
        vec3 axis = cameraAxis[k];
        float facing = dot(n, axis);
        // Move the lookup away from the silhouette as seen by camera k, where a texel may belong
        // to the background or to the other side of the object.
        vec3 q = p - seamShrink * (n - axis * facing);
        vec4 clip = cameraViewProjection[k] * vec4(q, 1.0);
        vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
        // Bilinear over the four texels around the point, keeping only those that hold this
        // surface: their stored depth is the point's, within the bias plus how much the surface's
        // depth changes across a texel at this slope. A texel of a surface in front (an occluder)
        // or behind (past a silhouette) would bring another surface's radiosity.
        float slope = min(sqrt(max(1.0 - facing * facing, 0.0)) / max(abs(facing), 1e-3), 8.0);
        float tolerance = depthBias * (1.0 + slope);
        vec2 f = window.xy * vec2(size) - 0.5;
        ivec2 base = ivec2(floor(f));
        vec2 t = f - vec2(base);
        vec4 sum = vec4(0.0);   // radiosity summed over frames (rgb), frames (a), bilinear-weighted
        float visible = 0.0;    // bilinear weight of the texels that hold this surface
        vec4 anySum = vec4(0.0);
        for (int j = 0; j < 4; ++j) {
            ivec2 offset = ivec2(j & 1, j >> 1);
            ivec2 texel = clamp(base + offset, ivec2(0), size - 1);
            float w = (offset.x == 1 ? t.x : 1.0 - t.x) * (offset.y == 1 ? t.y : 1.0 - t.y);
            vec4 map = texelFetch(scatteringMaps, ivec3(texel, k), 0);
            anySum += w * map;
            float stored = texelFetch(scatteringDepth, ivec3(texel, k), 0).r;
            if (map.a > 0.0 && abs(window.z - stored) <= tolerance) {
                sum += w * map;
                visible += w;
            }
        }
        if (anySum.a > 0.0) {  // the camera saw some surface there
            result.covered += anySum.rgb / anySum.a;
            result.coverage += 1.0;
        }
        if (visible <= 0.0 || sum.a <= 0.0) continue;
        vec3 radiosity = sum.rgb / sum.a;  // mean over accumulated frames and valid texels
        // Trust a layer by how squarely its camera sees the surface: a surface turned away from
        // camera k is not in its map at all, and a grazing view smears neighbouring surfaces
        // into the texel.
        float w = visible * (facing > 0.0 ? facing * facing : 0.0);
        weighted += w * radiosity;
        result.weight += w;
    }
    if (result.weight > 0.0) result.radiosity = weighted / result.weight;
    if (result.coverage > 0.0) result.covered /= result.coverage;
    return result;
}
