// NRRD through teem (SSS_WITH_TEEM), which keeps the orientation that VTK's reader drops.
#include "io/volume_decoding.h"

#if SSS_WITH_TEEM
#include <teem/nrrd.h>
#endif

#include <memory>
#include <string>

namespace sss::detail {

#if SSS_WITH_TEEM

// ---- NRRD (teem) ---------------------------------------------------------------------------------

Decoded readNrrd(const std::string& file, const std::string& prefix) {
    std::unique_ptr<Nrrd, Nrrd* (*)(Nrrd*)> nrrd(nrrdNew(), nrrdNuke);
    // Header only first: the dims are checked before teem allocates the data.
    {
        std::unique_ptr<NrrdIoState, NrrdIoState* (*)(NrrdIoState*)> io(nrrdIoStateNew(), nrrdIoStateNix);
        nrrdIoStateSet(io.get(), nrrdIoStateSkipData, AIR_TRUE);
        if (nrrdLoad(nrrd.get(), file.c_str(), io.get())) {
            char* err = biffGetDone(NRRD);
            std::string message = err ? err : "unknown error";
            free(err);
            while (!message.empty() && message.back() == '\n') message.pop_back();
            if (std::size_t nl = message.rfind('\n'); nl != std::string::npos) message = message.substr(nl + 1);
            fail(ErrorKind::Parse, prefix, "not a readable NRRD header: " + message);
        }
    }
    const unsigned dim = nrrd->dim;
    if (dim < 2 || dim > 3)
        fail(ErrorKind::Parse, prefix,
             std::to_string(dim) + " axes are not supported (2 or 3; multi-component volumes are not)");
    std::array<long long, 3> size{1, 1, 1};
    for (unsigned i = 0; i < dim; ++i)
        size[i] = nrrd->axis[i].size > 8192 ? 8193 : static_cast<long long>(nrrd->axis[i].size);
    checkDims(prefix, size);
    nrrd.reset(nrrdNew());
    if (nrrdLoad(nrrd.get(), file.c_str(), nullptr)) {
        char* err = biffGetDone(NRRD);
        std::string message = err ? err : "unknown error";
        free(err);
        while (!message.empty() && message.back() == '\n') message.pop_back();
        // teem's first line names the outermost function; the last says what went wrong.
        if (std::size_t nl = message.rfind('\n'); nl != std::string::npos) message = message.substr(nl + 1);
        fail(ErrorKind::Parse, prefix, "cannot read the voxels: " + message);
    }
    if (nrrd->dim != dim) fail(ErrorKind::Parse, prefix, "the file changed while it was read");
    Decoded d;
    d.dims = glm::ivec3(int(nrrd->axis[0].size), int(nrrd->axis[1].size), dim == 3 ? int(nrrd->axis[2].size) : 1);
    const std::size_t count = nrrdElementNumber(nrrd.get());
    if (count != static_cast<std::size_t>(d.dims.x) * d.dims.y * d.dims.z)
        fail(ErrorKind::Parse, prefix, "the file changed while it was read");
    switch (nrrd->type) {
    case nrrdTypeUChar: d.type = VoxelType::UInt8; d.bytes = toBytes<uint8_t>(nrrd->data, count); break;
    case nrrdTypeChar: d.type = VoxelType::Int16; d.bytes = widenInt8(nrrd->data, count); break;
    case nrrdTypeShort: d.type = VoxelType::Int16; d.bytes = toBytes<int16_t>(nrrd->data, count); break;
    case nrrdTypeUShort: d.type = VoxelType::UInt16; d.bytes = toBytes<uint16_t>(nrrd->data, count); break;
    case nrrdTypeFloat: d.type = VoxelType::Float32; d.bytes = toBytes<float>(nrrd->data, count); break;
    default: fail(ErrorKind::Parse, prefix, unsupportedType(airEnumStr(nrrdType, nrrd->type)));
    }
    // "space directions" give spacing and orientation; else "spacings" (axis-aligned).
    const unsigned spaceDim = nrrd->spaceDim;
    for (unsigned i = 0; i < dim; ++i) {
        const NrrdAxisInfo& axis = nrrd->axis[i];
        if (spaceDim == 3 && std::isfinite(axis.spaceDirection[0])) {
            const glm::dvec3 v(axis.spaceDirection[0], axis.spaceDirection[1], axis.spaceDirection[2]);
            const double length = glm::length(v);
            if (!(length > 0.0)) fail(ErrorKind::Parse, prefix, "axis " + std::to_string(i) + " has a zero space direction");
            d.spacing[i] = length;
            d.direction[i] = v / length;
        } else if (std::isfinite(axis.spacing) && axis.spacing != 0.0) {
            d.spacing[i] = std::abs(axis.spacing);
            if (axis.spacing < 0.0) d.direction[i] = -d.direction[i];
        }
    }
    return d;
}

#else

Decoded readNrrd(const std::string&, const std::string& prefix) {
    fail(ErrorKind::Unsupported, prefix, "NRRD files need libsss built with SSS_WITH_TEEM=ON (libteem-dev)");
}

#endif

}  // namespace sss::detail
