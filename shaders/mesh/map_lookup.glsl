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
    vec2 texel = 1.0 / vec2(textureSize(scatteringDepth, 0).xy);
    MapLookup result = MapLookup(vec3(0.0), 0.0, vec3(0.0), 0.0);
    vec3 weighted = vec3(0.0);
    for (int k = 0; k < cameraCount; ++k) {
        // Move the lookup away from the silhouette as seen by camera k, where a texel may belong
        // to the background or to the other side of the object.
        vec3 axis = cameraAxis[k];
        vec3 q = p - seamShrink * (n - axis * dot(n, axis));
        vec4 clip = cameraViewProjection[k] * vec4(q, 1.0);
        vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
        // 3x3 percentage-closer filter: the fraction of neighbours at least as far as this point.
        float v = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                float stored = texture(scatteringDepth, vec3(window.xy + vec2(dx, dy) * texel, float(k))).r;
                v += window.z - depthBias <= stored ? 1.0 : 0.0;
            }
        v /= 9.0;
        vec4 map = texture(scatteringMaps, vec3(window.xy, float(k)));
        if (map.a <= 0.0) continue;        // the camera saw no surface there
        vec3 radiosity = map.rgb / map.a;  // mean over accumulated frames and covered texels
        // Trust a layer by how squarely its camera sees the surface: a surface turned away from
        // camera k is not in its map at all (the texel belongs to whatever faces the camera, which
        // the depth bias may let through at thin parts), and a grazing view smears neighbouring
        // surfaces into the texel.
        float facing = dot(n, axis);
        float w = v * (facing > 0.0 ? facing * facing : 0.0);
        weighted += w * radiosity;
        result.weight += w;
        result.covered += radiosity;
        result.coverage += 1.0;
    }
    if (result.weight > 0.0) result.radiosity = weighted / result.weight;
    if (result.coverage > 0.0) result.covered /= result.coverage;
    return result;
}
