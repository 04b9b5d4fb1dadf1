#pragma once
// A textured translucent material on the GPU (sss::TexturedScattering): its reflectance and
// mean-free-path textures and the table that turns a reflectance into the profile's per-channel
// factors (shaders/mesh/textured_material.glsl). The passes that evaluate the profile at a point
// (scattering maps, vertex estimate, combine) compile with TEXTURED_MATERIAL 1 and call
// setTexturedMaterialUniforms.
#include "gl/program.h"
#include "gl/shader_source.h"
#include "gl/texture.h"
#include "mesh/reflectance_table.h"
#include "sss/bssrdf.h"
#include "sss/image.h"
#include "sss/materials.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <utility>
#include <optional>

namespace sss::detail {

/// Rows of the table: reflectance (i / (kTexturedTableRows - 1))^2, i = 0..kTexturedTableRows - 1
/// (squared: dense where dark texels' albedo changes fastest).
inline constexpr int kTexturedTableRows = 256;

/// The defines of shaders/mesh/textured_material.glsl (TEXTURED_MATERIAL 0 or 1 and its constants),
/// for every pass that includes it.
ShaderDefines texturedMaterialDefines(bool textured);

/// What the CPU needs to know of a texture to choose the sampling and the Automatic combine.
struct TexturedMaterialSummary {
    glm::dvec3 meanReflectance{0.0};  ///< linear, over the texels
    glm::dvec3 maxReflectance{0.0};   ///< linear, per channel
    double minPathScale = 1.0;        ///< the mean-free-path texture's smallest factor
};

class TexturedMaterialGpu {
public:
    /// Uploads `reflectance` (the material's texture, or the mesh's base colour), the material's
    /// mean-free-path texture and the profile's table. Throws InvalidArgument for an invalid material.
    TexturedMaterialGpu(const TexturedScattering& material, const Image8& reflectance, ScatteringProfile profile);

    const TexturedMaterialSummary& summary() const { return m_summary; }
    /// The homogeneous material with the texture's largest reflectance per channel and the
    /// longest mean free path: the widest profile, for which the disk sampling, the Automatic
    /// combine and the near field are chosen.
    const ScatteringMaterial& widestMaterial() const { return m_widest; }
    ScatteringProfile profile() const { return m_profile; }

    /// What the widest material gathers under even light per channel (textured_material.glsl's
    /// referenceGathered: the near field and the environment are that material's).
    const glm::dvec3& referenceGathered() const { return m_referenceGathered; }
    /// How densely the mesh it is drawn on holds texture coordinates: meanTexelDensity of a 1 x 1
    /// texture, per world unit. The textured rule finds a point's surroundings in the texture by it.
    void setTexcoordDensity(double perUnit) { m_texelsPerUnit = perUnit * std::sqrt(double(m_width) * m_height); }
    /// Computes what the combine reads per texel (shaders/mesh/textured_surface.comp) if the
    /// scale or the texture density changed since the last call.
    void prepareSurface(double millimetresPerUnit);
    /// Binds the textures and sets textured_material.glsl's uniforms on `program`.
    void bind(const gl::Program& program, double millimetresPerUnit) const;

private:
    TexturedScattering m_material;
    ScatteringProfile m_profile;
    TexturedMaterialSummary m_summary;
    glm::dvec3 m_referenceGathered{1.0};
    ScatteringMaterial m_widest;
    double m_texelsPerUnit = 0.0;
    int m_width = 1, m_height = 1;  // of the reflectance texture
    gl::Texture m_reflectance, m_pathScale, m_table, m_logGathered;
    gl::Texture m_surfaceAlbedo, m_surroundings;         // prepareSurface's, mipmapped
    std::optional<std::pair<double, double>> m_surfaceKey;  // millimetres per unit, texels per unit
    std::optional<gl::Program> m_surfaceProgram;
};

}  // namespace sss::detail
