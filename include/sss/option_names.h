#pragma once
/// @file
/// The names of the option enums, as scene files and command lines spell them ("per-vertex",
/// "scattering-gradient", ...): one table per enum, so every front end and the scene files
/// agree on them.

#include "sss/api.h"
#include "sss/bssrdf.h"
#include "sss/camera.h"
#include "sss/display.h"
#include "sss/mesh_scattering_renderer.h"
#include "sss/volume.h"
#include "sss/volume_scattering_renderer.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

SSS_BEGIN_API

namespace sss {

/// A name of an enum value.
template <class Enum>
struct EnumName {
    Enum value;
    std::string_view name;
};

/// Every value of `Enum` with its name, in declaration order. Specialized for MeshShading,
/// MeshCombine, ScatteringProfile, VolumeShading, VolumeModel, LightVolumeFallback, RayCaster,
/// CacheViewEvaluation, LightPropagation, CropSpace, ToneMap, Projection, VoxelType and
/// VolumeReconstruction.
template <class Enum>
std::span<const EnumName<Enum>> enumNames();

/// The name of `value`.
template <class Enum>
std::string_view enumName(Enum value) {
    for (const EnumName<Enum>& entry : enumNames<Enum>())
        if (entry.value == value) return entry.name;
    return "?";
}

/// The value called `name` (exact spelling), or nothing.
template <class Enum>
std::optional<Enum> parseEnumName(std::string_view name) {
    for (const EnumName<Enum>& entry : enumNames<Enum>())
        if (entry.name == name) return entry.value;
    return std::nullopt;
}

/// "a, b or c": the names of `Enum`, for messages.
template <class Enum>
std::string enumNameList() {
    std::string list;
    const auto names = enumNames<Enum>();
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) list += i + 1 == names.size() ? " or " : ", ";
        list += names[i].name;
    }
    return list;
}

template <> std::span<const EnumName<MeshShading>> enumNames<MeshShading>();
template <> std::span<const EnumName<MeshCombine>> enumNames<MeshCombine>();
template <> std::span<const EnumName<ScatteringProfile>> enumNames<ScatteringProfile>();
template <> std::span<const EnumName<VolumeShading>> enumNames<VolumeShading>();
template <> std::span<const EnumName<VolumeModel>> enumNames<VolumeModel>();
template <> std::span<const EnumName<LightVolumeFallback>> enumNames<LightVolumeFallback>();
template <> std::span<const EnumName<RayCaster>> enumNames<RayCaster>();
template <> std::span<const EnumName<CacheViewEvaluation>> enumNames<CacheViewEvaluation>();
template <> std::span<const EnumName<LightPropagation>> enumNames<LightPropagation>();
template <> std::span<const EnumName<ToneMap>> enumNames<ToneMap>();
template <> std::span<const EnumName<Projection>> enumNames<Projection>();
template <> std::span<const EnumName<VoxelType>> enumNames<VoxelType>();
template <> std::span<const EnumName<VolumeReconstruction>> enumNames<VolumeReconstruction>();

}  // namespace sss

SSS_END_API
