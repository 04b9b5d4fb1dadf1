// The light volume's image format: (c, l) in RGBA16F, or without the chromaticity l alone in
// R16F, which LightVolumePass swizzles so that sampling it still returns (1, 1, 1, l).
#if CHROMATICITY
#define LIGHT_VOLUME_FORMAT rgba16f
#else
#define LIGHT_VOLUME_FORMAT r16f
#endif
