#include "sss/option_names.h"

namespace sss {

// One table per enum: scene files and every command line spell the values this way.
template <>
std::span<const EnumName<MeshShading>> enumNames<MeshShading>() {
    static constexpr EnumName<MeshShading> names[] = {{MeshShading::BlinnPhong, "blinn-phong"},
                                                      {MeshShading::Scattering, "sss"}};
    return names;
}

template <>
std::span<const EnumName<MeshCombine>> enumNames<MeshCombine>() {
    static constexpr EnumName<MeshCombine> names[] = {{MeshCombine::Automatic, "auto"},
                                                      {MeshCombine::PerPixel, "per-pixel"},
                                                      {MeshCombine::PerVertex, "per-vertex"},
                                                      {MeshCombine::VertexEstimate, "vertex-estimate"}};
    return names;
}

template <>
std::span<const EnumName<ScatteringProfile>> enumNames<ScatteringProfile>() {
    static constexpr EnumName<ScatteringProfile> names[] = {{ScatteringProfile::Calibrated, "calibrated"},
                                                            {ScatteringProfile::Dipole, "dipole"}};
    return names;
}

template <>
std::span<const EnumName<VolumeShading>> enumNames<VolumeShading>() {
    static constexpr EnumName<VolumeShading> names[] = {{VolumeShading::EmissionAbsorption, "emission-absorption"},
                                                        {VolumeShading::Gradient, "gradient"},
                                                        {VolumeShading::Scattering, "scattering"},
                                                        {VolumeShading::ScatteringGradient, "scattering-gradient"}};
    return names;
}

template <>
std::span<const EnumName<VolumeModel>> enumNames<VolumeModel>() {
    static constexpr EnumName<VolumeModel> names[] = {{VolumeModel::Paper, "paper"}, {VolumeModel::Physical, "physical"}};
    return names;
}

template <>
std::span<const EnumName<LightVolumeFallback>> enumNames<LightVolumeFallback>() {
    static constexpr EnumName<LightVolumeFallback> names[] = {{LightVolumeFallback::Reduce, "reduce"},
                                                              {LightVolumeFallback::Fail, "fail"}};
    return names;
}

template <>
std::span<const EnumName<VolumeReconstruction>> enumNames<VolumeReconstruction>() {
    static constexpr EnumName<VolumeReconstruction> names[] = {{VolumeReconstruction::Trilinear, "trilinear"},
                                                               {VolumeReconstruction::CubicBSpline, "cubic"}};
    return names;
}

template <>
std::span<const EnumName<RayCaster>> enumNames<RayCaster>() {
    static constexpr EnumName<RayCaster> names[] = {
        {RayCaster::Auto, "auto"}, {RayCaster::Fragment, "fragment"}, {RayCaster::Compute, "compute"}};
    return names;
}

template <>
std::span<const EnumName<CacheViewEvaluation>> enumNames<CacheViewEvaluation>() {
    static constexpr EnumName<CacheViewEvaluation> names[] = {{CacheViewEvaluation::Auto, "auto"},
                                                              {CacheViewEvaluation::PerCell, "per-cell"},
                                                              {CacheViewEvaluation::PerSample, "per-sample"}};
    return names;
}

template <>
std::span<const EnumName<LightPropagation>> enumNames<LightPropagation>() {
    static constexpr EnumName<LightPropagation> names[] = {
        {LightPropagation::Auto, "auto"}, {LightPropagation::Sweep, "sweep"}, {LightPropagation::Doubling, "doubling"}};
    return names;
}

template <>
std::span<const EnumName<CropSpace>> enumNames<CropSpace>() {
    static constexpr EnumName<CropSpace> names[] = {{CropSpace::Data, "data"}, {CropSpace::World, "world"}};
    return names;
}

template <>
std::span<const EnumName<ToneMap>> enumNames<ToneMap>() {
    static constexpr EnumName<ToneMap> names[] = {{ToneMap::None, "none"}, {ToneMap::Filmic, "filmic"}};
    return names;
}

template <>
std::span<const EnumName<Projection>> enumNames<Projection>() {
    static constexpr EnumName<Projection> names[] = {{Projection::Perspective, "perspective"},
                                                     {Projection::Orthographic, "orthographic"}};
    return names;
}

template <>
std::span<const EnumName<VoxelType>> enumNames<VoxelType>() {
    static constexpr EnumName<VoxelType> names[] = {{VoxelType::UInt8, "uint8"},
                                                    {VoxelType::UInt16, "uint16"},
                                                    {VoxelType::Int16, "int16"},
                                                    {VoxelType::Float32, "float32"}};
    return names;
}

}  // namespace sss
