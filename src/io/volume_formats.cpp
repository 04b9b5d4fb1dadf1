// Volume::load (declared in sss/volume.h, built in the io component): picks the reader by the
// path (io/volume_decoding.h) and orients what it decoded.
#include "io/volume_decoding.h"

#include "sss/log.h"

#include <glm/mat3x3.hpp>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <mutex>
#include <new>
#include <set>
#include <sstream>
#include <string>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sss {
namespace {

using detail::Decoded;
using detail::fail;
using detail::lower;

// ---- orientation ---------------------------------------------------------------------------------

// Reorders the voxels so that index axis a runs along world axis a in increasing order, when
// the direction matrix is a signed permutation. Oblique matrices: error, or kept as they are.
Volume orient(const std::string& prefix, Decoded d, bool allowOblique) {
    std::array<int, 3> source{};  // source[a]: the file axis that runs along world axis a
    std::array<bool, 3> flip{};
    std::array<bool, 3> used{};
    bool permutation = true;
    for (int j = 0; j < 3 && permutation; ++j) {
        const glm::dvec3 column = d.direction[j];
        int axis = -1;
        for (int a = 0; a < 3; ++a)
            if (std::abs(std::abs(column[a]) - 1.0) < 1e-3) axis = a;
        for (int a = 0; a < 3; ++a)
            if (a != axis && std::abs(column[a]) > 1e-3) axis = -1;
        if (axis < 0 || used[axis]) {
            permutation = false;
            break;
        }
        used[axis] = true;
        source[axis] = j;
        flip[axis] = column[axis] < 0.0;
    }
    auto build = [&](glm::ivec3 dims, std::vector<uint8_t> bytes, glm::dvec3 spacing) {
        try {
            return Volume::fromData(dims, d.type, std::move(bytes), glm::vec3(spacing));
        } catch (const Error& e) {
            // fromData's message names itself; say which file it was.
            std::string what = e.what();
            const std::string own = "Volume::fromData: ";
            if (what.rfind(own, 0) == 0) what = what.substr(own.size());
            throw Error(e.kind(), prefix + what);
        }
    };
    if (!permutation) {
        std::ostringstream m;
        m << "the direction matrix is oblique (columns";
        for (int j = 0; j < 3; ++j)
            m << " (" << d.direction[j].x << ", " << d.direction[j].y << ", " << d.direction[j].z << ")";
        m << "); only axis-aligned orientations (signed permutations) are supported";
        if (!allowOblique) fail(ErrorKind::Parse, prefix, m.str() + "; VolumeLoadOptions::allowOblique keeps file order");
        log(LogLevel::Warning, prefix + m.str() + "; voxels kept in file order");
        return build(d.dims, std::move(d.bytes), d.spacing);
    }
    const bool identity = source == std::array<int, 3>{0, 1, 2} && !flip[0] && !flip[1] && !flip[2];
    if (identity) return build(d.dims, std::move(d.bytes), d.spacing);
    glm::ivec3 dims;
    glm::dvec3 spacing;
    for (int a = 0; a < 3; ++a) {
        dims[a] = d.dims[source[a]];
        spacing[a] = d.spacing[source[a]];
    }
    const std::size_t bpv = bytesPerVoxel(d.type);
    std::vector<uint8_t> out(d.bytes.size());
    const std::array<std::size_t, 3> stride{1, static_cast<std::size_t>(d.dims.x),
                                            static_cast<std::size_t>(d.dims.x) * static_cast<std::size_t>(d.dims.y)};
    std::size_t o = 0;
    glm::ivec3 p;
    for (p.z = 0; p.z < dims.z; ++p.z)
        for (p.y = 0; p.y < dims.y; ++p.y)
            for (p.x = 0; p.x < dims.x; ++p.x, ++o) {
                std::size_t i = 0;
                for (int a = 0; a < 3; ++a) {
                    const int index = flip[a] ? dims[a] - 1 - p[a] : p[a];
                    i += static_cast<std::size_t>(index) * stride[static_cast<std::size_t>(source[a])];
                }
                std::memcpy(out.data() + o * bpv, d.bytes.data() + i * bpv, bpv);
            }
    return build(dims, std::move(out), spacing);
}

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Volume Volume::load(const std::filesystem::path& path, const VolumeLoadOptions& options) {
    const std::string file = path.string();
    const std::string prefix = "Volume::load: " + file + ": ";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(ErrorKind::Io, prefix, "file does not exist");
    if (std::filesystem::is_directory(path, ec)) {
        bool any = false;
        for (const auto& entry : std::filesystem::directory_iterator(path, ec))
            any = any || entry.is_regular_file();
        if (!any) fail(ErrorKind::Io, prefix, "the directory has no files (a DICOM series was expected)");
        try {
            return orient(prefix, detail::readDicomSeries(file, prefix), options.allowOblique);
        } catch (const std::bad_alloc&) {
            fail(ErrorKind::Parse, prefix, "out of memory reading the series");
        }
    }
    const std::string name = lower(path.filename().string());
    if (endsWith(name, ".raw")) return loadRaw(path, options.raw);
    bool known = false;
    for (const char* ext : {".nrrd", ".nhdr", ".mhd", ".mha", ".nii", ".nii.gz", ".vti"}) known = known || endsWith(name, ext);
    if (!known)
        fail(ErrorKind::InvalidArgument, prefix,
             "unknown volume format: expected .raw, .nrrd, .nhdr, .mhd, .mha, .nii, .nii.gz, .vti or a DICOM directory");
    {
        std::ifstream probe(path, std::ios::binary);
        if (!probe) fail(ErrorKind::Io, prefix, "cannot be opened for reading");
        if (std::filesystem::file_size(path, ec) == 0 || ec) fail(ErrorKind::Parse, prefix, "the file is empty");
    }
    try {
        if (endsWith(name, ".nrrd") || endsWith(name, ".nhdr"))
            return orient(prefix, detail::readNrrd(file, prefix), options.allowOblique);
        if (endsWith(name, ".mhd") || endsWith(name, ".mha"))
            return orient(prefix, detail::readMetaImage(file, prefix), options.allowOblique);
        if (endsWith(name, ".nii") || endsWith(name, ".nii.gz"))
            return orient(prefix, detail::readNifti(file, prefix), options.allowOblique);
        return orient(prefix, detail::readVti(file, prefix), options.allowOblique);  // the one left: .vti
    } catch (const std::bad_alloc&) {
        // A header can claim up to 8192^3 voxels; the libraries allocate before we can check.
        fail(ErrorKind::Parse, prefix, "out of memory reading the voxels (are the header's sizes right?)");
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        // MetaIO formats some damaged header fields into a string of absurd length and throws
        // std::length_error (tests/fuzz/fuzz_volume_formats); whatever a reader throws is a bad file.
        fail(ErrorKind::Parse, prefix, std::string("the reader failed on a damaged header (") + e.what() + ")");
    }
}

}  // namespace sss
