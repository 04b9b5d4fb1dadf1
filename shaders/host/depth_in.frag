// HostTarget::begin: the host's depth (blitted into a texture of its own format) becomes the
// libsss target's depth, so host geometry stops volume rays and hides libsss meshes.
uniform sampler2D hostDepth;

void main() {
    gl_FragDepth = texelFetch(hostDepth, ivec2(gl_FragCoord.xy), 0).r;
}
