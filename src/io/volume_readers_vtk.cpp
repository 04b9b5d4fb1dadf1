// NIfTI, VTK XML image data, DICOM series and MetaImage through VTK 9 (SSS_WITH_VTK). VTK's
// headers stay in this file: they cost several seconds of compile time per translation unit.
#include "io/volume_decoding.h"

#include "sss/log.h"

#if SSS_WITH_VTK
#include <vtkDICOMImageReader.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageReader.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkType.h>
#include <vtkXMLImageDataReader.h>
#include <vtkmetaio/metaImage.h>
#include <zlib.h>
#endif

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

namespace sss::detail {

#if SSS_WITH_VTK

// ---- VTK: collect what readers report instead of printing it ---------------------------------

// VTK reports errors through a process-wide output window; while a load runs, this one keeps
// the text so the exception can carry it. The mutex serialises VTK loads.
class CapturingOutputWindow : public vtkOutputWindow {
public:
    static CapturingOutputWindow* New();
    vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
    void DisplayText(const char* text) override { record(text); }
    void DisplayErrorText(const char* text) override { record(text); }
    void DisplayWarningText(const char* text) override { record(text); }
    void DisplayGenericWarningText(const char* text) override { record(text); }
    void DisplayDebugText(const char*) override {}
    std::string first;  // the first message, reduced to its last line

private:
    void record(const char* text) {
        if (!first.empty() || !text) return;
        std::string s(text);
        while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
        // "ERROR: In <source>, line N\n<class> (0x...): message": keep the message.
        if (std::size_t nl = s.rfind('\n'); nl != std::string::npos) s = s.substr(nl + 1);
        if (std::size_t p = s.find("): "); p != std::string::npos && p < 40) s = s.substr(p + 3);
        first = s.empty() ? "unknown error" : s;
    }
};
vtkStandardNewMacro(CapturingOutputWindow);

class VtkCapture {
public:
    VtkCapture() : m_lock(mutex()) {
        m_previous = vtkOutputWindow::GetInstance();
        m_previous->Register(nullptr);  // keep it alive while ours is installed
        vtkOutputWindow::SetInstance(m_window);
        // The pipeline also logs failures to stderr through vtkLogger.
        m_verbosity = vtkLogger::GetCurrentVerbosityCutoff();
        vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    }
    ~VtkCapture() {
        vtkLogger::SetStderrVerbosity(m_verbosity);
        vtkOutputWindow::SetInstance(m_previous);
        m_previous->UnRegister(nullptr);
    }
    VtkCapture(const VtkCapture&) = delete;
    VtkCapture& operator=(const VtkCapture&) = delete;
    const std::string& first() const { return m_window->first; }

private:
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    std::lock_guard<std::mutex> m_lock;
    vtkNew<CapturingOutputWindow> m_window;
    vtkOutputWindow* m_previous = nullptr;
    vtkLogger::Verbosity m_verbosity = vtkLogger::VERBOSITY_OFF;
};

// The image a VTK reader produced, or a Parse error with what the reader said.
Decoded fromVtkImage(const std::string& prefix, vtkImageData* image, const VtkCapture& capture, bool readerFailed) {
    if (readerFailed || !capture.first().empty() || !image)
        fail(ErrorKind::Parse, prefix, capture.first().empty() ? "the reader failed" : capture.first());
    int extent[6];
    image->GetExtent(extent);
    const std::array<long long, 3> dims{extent[1] - extent[0] + 1LL, extent[3] - extent[2] + 1LL,
                                        extent[5] - extent[4] + 1LL};
    vtkDataArray* scalars = image->GetPointData() ? image->GetPointData()->GetScalars() : nullptr;
    if (!scalars && image->GetPointData() && image->GetPointData()->GetNumberOfArrays() > 0)
        scalars = image->GetPointData()->GetArray(0);
    if (!scalars || dims[0] < 1 || dims[1] < 1 || dims[2] < 1) fail(ErrorKind::Parse, prefix, "the file has no voxels");
    checkDims(prefix, dims);
    if (scalars->GetNumberOfComponents() != 1)
        fail(ErrorKind::Parse, prefix,
             std::to_string(scalars->GetNumberOfComponents()) +
                 " components per voxel are not supported (only scalar volumes are)");
    const std::size_t count = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
    if (static_cast<std::size_t>(scalars->GetNumberOfTuples()) != count)
        fail(ErrorKind::Parse, prefix, "the file holds " + std::to_string(scalars->GetNumberOfTuples()) +
                                           " voxels, its header says " + std::to_string(count));
    Decoded d;
    d.dims = glm::ivec3(int(dims[0]), int(dims[1]), int(dims[2]));
    const void* data = scalars->GetVoidPointer(0);
    switch (scalars->GetDataType()) {
    case VTK_UNSIGNED_CHAR: d.type = VoxelType::UInt8; d.bytes = toBytes<uint8_t>(data, count); break;
    case VTK_CHAR:
    case VTK_SIGNED_CHAR: d.type = VoxelType::Int16; d.bytes = widenInt8(data, count); break;
    case VTK_SHORT: d.type = VoxelType::Int16; d.bytes = toBytes<int16_t>(data, count); break;
    case VTK_UNSIGNED_SHORT: d.type = VoxelType::UInt16; d.bytes = toBytes<uint16_t>(data, count); break;
    case VTK_FLOAT: d.type = VoxelType::Float32; d.bytes = toBytes<float>(data, count); break;
    default: fail(ErrorKind::Parse, prefix, unsupportedType(scalars->GetDataTypeAsString()));
    }
    const double* s = image->GetSpacing();
    d.spacing = glm::dvec3(std::abs(s[0]), std::abs(s[1]), std::abs(s[2]));
    return d;
}

// vtkNIFTIImageReader trusts the header: an unknown datatype or a file shorter than its dims
// say crashes it (found by tests/fuzz/fuzz_volume_formats). So the header is checked first, and
// the (decompressed) file must hold every voxel. zlib reads .nii and .nii.gz alike.
void checkNiftiHeader(const std::string& file, const std::string& prefix) {
    std::unique_ptr<gzFile_s, int (*)(gzFile)> in(gzopen(file.c_str(), "rb"), gzclose);
    if (!in) fail(ErrorKind::Io, prefix, "cannot open the file");
    std::array<unsigned char, 540> h{};
    const int got = gzread(in.get(), h.data(), static_cast<unsigned>(h.size()));
    if (got < 4) fail(ErrorKind::Parse, prefix, "not a NIfTI-1 or NIfTI-2 file (shorter than its header)");
    auto read = [&](std::size_t at, std::size_t bytes, bool swap) {
        uint64_t v = 0;
        for (std::size_t i = 0; i < bytes; ++i) v |= uint64_t(h[at + (swap ? bytes - 1 - i : i)]) << (8 * i);
        return v;
    };
    const uint64_t sizeLe = read(0, 4, false), sizeBe = read(0, 4, true);
    const bool swap = sizeBe == 348 || sizeBe == 540;
    const uint64_t headerSize = swap ? sizeBe : sizeLe;
    if (headerSize != 348 && headerSize != 540)
        fail(ErrorKind::Parse, prefix, "not a NIfTI-1 or NIfTI-2 file (sizeof_hdr is neither 348 nor 540)");
    if (static_cast<uint64_t>(got) < headerSize) fail(ErrorKind::Parse, prefix, "the NIfTI header is cut off");
    const bool two = headerSize == 540;
    const auto i16 = [&](std::size_t at) { return static_cast<int16_t>(read(at, 2, swap)); };
    const auto i64 = [&](std::size_t at) { return static_cast<int64_t>(read(at, 8, swap)); };
    const int datatype = i16(two ? 12 : 70), bitpix = i16(two ? 14 : 72);
    std::array<int64_t, 8> dim{};
    for (int i = 0; i < 8; ++i) dim[i] = two ? i64(16 + 8 * i) : i16(40 + 2 * i);
    double voxOffset = 0.0;
    if (two) {
        voxOffset = double(i64(168));
    } else {
        const uint32_t bits = static_cast<uint32_t>(read(108, 4, swap));
        float f = 0.0f;
        std::memcpy(&f, &bits, 4);
        voxOffset = f;
    }
    // The voxel types libsss keeps (uint8, int8 -> int16, int16, uint16, float32) and their sizes.
    int bytes = 0;
    switch (datatype) {
    case 2: case 256: bytes = 1; break;
    case 4: case 512: bytes = 2; break;
    case 16: bytes = 4; break;
    default: fail(ErrorKind::Parse, prefix, unsupportedType("NIfTI datatype " + std::to_string(datatype)));
    }
    if (bitpix != 8 * bytes)
        fail(ErrorKind::Parse, prefix, "bitpix " + std::to_string(bitpix) + " does not match datatype " +
                                           std::to_string(datatype));
    if (dim[0] < 1 || dim[0] > 7) fail(ErrorKind::Parse, prefix, "dim[0] " + std::to_string(dim[0]) + " is not in 1..7");
    uint64_t count = 1;
    for (int i = 1; i <= dim[0]; ++i) {
        if (dim[i] < 1 || dim[i] > 8192)
            fail(ErrorKind::Parse, prefix, "dim[" + std::to_string(i) + "] " + std::to_string(dim[i]) + " is not in 1..8192");
        if (i > 3 && dim[i] != 1)
            fail(ErrorKind::Parse, prefix, std::to_string(dim[0]) + "-dimensional data (time series, vectors) is not supported");
        count *= static_cast<uint64_t>(dim[i]);
    }
    if (!(voxOffset >= double(headerSize) && voxOffset < 1e12))
        fail(ErrorKind::Parse, prefix, "vox_offset " + std::to_string(voxOffset) + " is not past the header");
    // Count the bytes there are (all of them, for compressed files).
    uint64_t total = static_cast<uint64_t>(got);
    std::vector<unsigned char> chunk(1 << 16);
    for (int n; (n = gzread(in.get(), chunk.data(), static_cast<unsigned>(chunk.size()))) > 0;) total += uint64_t(n);
    int zerr = Z_OK;
    gzerror(in.get(), &zerr);
    if (zerr != Z_OK && zerr != Z_STREAM_END) fail(ErrorKind::Parse, prefix, "the compressed data is damaged");
    const uint64_t needed = static_cast<uint64_t>(voxOffset) + count * uint64_t(bytes);
    if (total < needed)
        fail(ErrorKind::Parse, prefix, "the file holds " + std::to_string(total) + " bytes, its header needs " +
                                           std::to_string(needed));
}

Decoded readNifti(const std::string& file, const std::string& prefix) {
    checkNiftiHeader(file, prefix);
    VtkCapture capture;
    vtkNew<vtkNIFTIImageReader> reader;
    if (!reader->CanReadFile(file.c_str())) fail(ErrorKind::Parse, prefix, "not a NIfTI-1 or NIfTI-2 file");
    reader->SetFileName(file.c_str());
    reader->Update();
    Decoded d = fromVtkImage(prefix, reader->GetOutput(), capture, reader->GetErrorCode() != 0);
    // The reader reverses the slices when qfac is -1, so the matrices are rotations here.
    vtkMatrix4x4* m = reader->GetQFormMatrix() ? reader->GetQFormMatrix() : reader->GetSFormMatrix();
    if (m)
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) d.direction[c][r] = m->GetElement(r, c);
    // Scaled data (scl_slope/scl_inter) becomes float32 in real units.
    const double slope = reader->GetRescaleSlope(), inter = reader->GetRescaleIntercept();
    if (slope != 0.0 && (slope != 1.0 || inter != 0.0)) {
        const Volume raw = Volume::fromData(d.dims, d.type, d.bytes);
        std::vector<uint8_t> out(raw.voxelCount() * 4);
        std::size_t i = 0;
        for (int z = 0; z < d.dims.z; ++z)
            for (int y = 0; y < d.dims.y; ++y)
                for (int x = 0; x < d.dims.x; ++x, ++i) {
                    const float v = static_cast<float>(raw.valueAt(x, y, z) * slope + inter);
                    std::memcpy(out.data() + 4 * i, &v, 4);
                }
        d.type = VoxelType::Float32;
        d.bytes = std::move(out);
    }
    return d;
}

Decoded readVti(const std::string& file, const std::string& prefix) {
    VtkCapture capture;
    vtkNew<vtkXMLImageDataReader> reader;
    if (!reader->CanReadFile(file.c_str())) fail(ErrorKind::Parse, prefix, "not a VTK XML image data (.vti) file");
    reader->SetFileName(file.c_str());
    reader->Update();
    Decoded d = fromVtkImage(prefix, reader->GetOutput(), capture, reader->GetErrorCode() != 0);
    vtkMatrix3x3* m = reader->GetOutput()->GetDirectionMatrix();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) d.direction[c][r] = m->GetElement(r, c);
    return d;
}

// vtkDICOMImageReader reads a pixel data element that ends early without complaint, and crashes
// on some files cut inside their header. So every file with a DICOM preamble is walked element
// by element first (framing only: tag, VR, length): each must fit in the file, and one must be
// the pixel data (7FE0,0010). Elements of undefined length (sequences, encapsulated pixel data)
// end the walk, since their extent needs a full parse.
void checkDicomFraming(const std::filesystem::path& dir, const std::string& prefix) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path(), std::ios::binary);
        const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (data.size() < 132 || data.compare(128, 4, "DICM") != 0) continue;
        const std::string name = entry.path().filename().string();
        auto u16 = [&](std::size_t at) {
            return static_cast<uint32_t>(static_cast<uint8_t>(data[at]) | (static_cast<uint8_t>(data[at + 1]) << 8));
        };
        auto u32 = [&](std::size_t at) { return u16(at) | (u16(at + 2) << 16); };
        auto upper = [](char c) { return c >= 'A' && c <= 'Z'; };
        std::size_t pos = 132;
        bool pixels = false, undefinedLength = false;
        while (pos < data.size() && !pixels && !undefinedLength) {
            if (pos + 8 > data.size())
                fail(ErrorKind::Parse, prefix, name + ": cut off inside an element header at byte " + std::to_string(pos));
            const uint32_t group = u16(pos), element = u16(pos + 2);
            const bool explicitVr = upper(data[pos + 4]) && upper(data[pos + 5]);
            const std::string vr = explicitVr ? data.substr(pos + 4, 2) : "";
            const bool longForm = vr == "OB" || vr == "OW" || vr == "OF" || vr == "OD" || vr == "OL" || vr == "OV" ||
                                  vr == "SQ" || vr == "UT" || vr == "UN" || vr == "UC" || vr == "UR";
            std::size_t header = 8;
            uint32_t length = 0;
            if (!explicitVr) {
                length = u32(pos + 4);
            } else if (longForm) {
                header = 12;
                if (pos + 12 > data.size())
                    fail(ErrorKind::Parse, prefix, name + ": cut off inside an element header at byte " + std::to_string(pos));
                length = u32(pos + 8);
            } else {
                length = u16(pos + 6);
            }
            if (length == 0xffffffffu) {
                undefinedLength = true;
                break;
            }
            if (pos + header + length > data.size()) {
                char tag[16];
                std::snprintf(tag, sizeof tag, "(%04X,%04X)", group, element);
                fail(ErrorKind::Parse, prefix,
                     name + ": element " + tag + " at byte " + std::to_string(pos) + " needs " + std::to_string(length) +
                         " bytes, the file ends after " + std::to_string(data.size() - pos - header));
            }
            pixels = group == 0x7FE0 && element == 0x0010;
            pos += header + length;
        }
        if (!pixels && !undefinedLength) fail(ErrorKind::Parse, prefix, name + ": no pixel data element (7FE0,0010)");
    }
}

Decoded readDicomSeries(const std::string& dir, const std::string& prefix) {
    checkDicomFraming(dir, prefix);
    VtkCapture capture;
    vtkNew<vtkDICOMImageReader> reader;
    reader->SetDirectoryName(dir.c_str());
    reader->Update();
    Decoded d = fromVtkImage(prefix, reader->GetOutput(), capture, reader->GetErrorCode() != 0);
    // The reader sorts the slices by position along the normal, descending, and turns rows
    // bottom-up (VTK's convention): its y and z axes run against the column direction and the
    // normal (checked by the DICOM test).
    const float* o = reader->GetImageOrientationPatient();
    const glm::dvec3 row(o[0], o[1], o[2]), col(o[3], o[4], o[5]);
    if (glm::length(row) > 0.5 && glm::length(col) > 0.5)
        d.direction = glm::dmat3(row, -col, -glm::cross(row, col));
    // The reader applies rescale slope and intercept itself (Hounsfield units out), and puts
    // PixelSpacing's first value (the row spacing, along y) on x: swap it back.
    std::swap(d.spacing.x, d.spacing.y);
    return d;
}

// ---- MetaImage (MetaIO) -------------------------------------------------------------------------

// MetaIO prints its complaints to std::cout/std::cerr; keep them for the message instead.
class StreamCapture {
public:
    StreamCapture() : m_out(std::cout.rdbuf(m_text.rdbuf())), m_err(std::cerr.rdbuf(m_text.rdbuf())) {}
    ~StreamCapture() {
        std::cout.rdbuf(m_out);
        std::cerr.rdbuf(m_err);
    }
    StreamCapture(const StreamCapture&) = delete;
    StreamCapture& operator=(const StreamCapture&) = delete;
    std::string firstLine() const {
        std::string s = m_text.str();
        s = s.substr(0, s.find('\n'));
        return s;
    }

private:
    std::ostringstream m_text;
    std::streambuf* m_out;
    std::streambuf* m_err;
};

// MetaIO accepts uncompressed data that ends early (the rest of the buffer stays unset), so the
// size is checked first: the data is the file's tail after the ElementDataFile line (LOCAL) or
// the whole named data file.
void checkMetaImageSize(const std::string& file, const std::string& prefix, const vtkmetaio::MetaImage& image) {
    if (image.CompressedData() || !image.BinaryData()) return;
    int elementBytes = 0;
    vtkmetaio::MET_SizeOfType(image.ElementType(), &elementBytes);
    unsigned long long expected = static_cast<unsigned long long>(elementBytes) * image.ElementNumberOfChannels();
    for (int i = 0; i < image.NDims(); ++i) expected *= static_cast<unsigned long long>(image.DimSize(i));
    const std::string dataName = image.ElementDataFileName();
    unsigned long long present = 0;
    std::error_code ec;
    if (dataName == "LOCAL") {
        std::ifstream in(file, std::ios::binary);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::size_t key = text.find("ElementDataFile");
        const std::size_t end = key == std::string::npos ? std::string::npos : text.find('\n', key);
        if (end == std::string::npos) fail(ErrorKind::Parse, prefix, "the header has no ElementDataFile line");
        present = text.size() - (end + 1);
    } else if (dataName.find("LIST") == std::string::npos && dataName.find('%') == std::string::npos) {
        const std::filesystem::path data = std::filesystem::path(file).parent_path() / dataName;
        present = std::filesystem::file_size(data, ec);
        if (ec) fail(ErrorKind::Io, prefix, "cannot read the data file " + data.string() + ": " + ec.message());
    } else {
        return;  // a slice list or pattern: MetaIO checks each file
    }
    if (present < expected)
        fail(ErrorKind::Parse, prefix,
             "the data is truncated: " + std::to_string(present) + " bytes where the header needs " +
                 std::to_string(expected));
}

// MetaIO trusts the header it parses: repeated or short vector fields corrupt its heap, and an
// ElementDataFile value with a '%' goes to snprintf as a format (both found by
// tests/fuzz/fuzz_volume_formats). So the header is checked line by line first, up to and
// including ElementDataFile (where MetaIO's header ends): "Key = Value" lines, each key once,
// NDims (2 or 3) before the fields sized by it, vector fields with exactly that many numbers,
// known element types, LOCAL or a plain file name for the data.
void checkMetaImageHeader(const std::string& file, const std::string& prefix) {
    std::ifstream in(file, std::ios::binary);
    std::string header(1 << 16, '\0');
    in.read(header.data(), static_cast<std::streamsize>(header.size()));
    header.resize(static_cast<std::size_t>(in.gcount()));
    auto bad = [&](const std::string& what) { fail(ErrorKind::Parse, prefix, "MetaImage header: " + what); };
    auto trim = [](std::string t) {
        const auto first = t.find_first_not_of(" \t"), last = t.find_last_not_of(" \t");
        return first == std::string::npos ? std::string() : t.substr(first, last - first + 1);
    };
    auto numbers = [&](const std::string& key, const std::string& value, std::size_t count, bool integers) {
        std::istringstream words(value);
        std::string word;
        std::size_t n = 0;
        while (words >> word) {
            char* end = nullptr;
            const double v = std::strtod(word.c_str(), &end);
            if (*end != '\0' || !std::isfinite(v) || (integers && v != std::floor(v)))
                bad(key + ": \"" + word + "\" is not " + (integers ? "an integer" : "a number"));
            ++n;
        }
        if (n != count) bad(key + ": expected " + std::to_string(count) + " values, got " + std::to_string(n));
    };
    std::set<std::string> seen;
    int nDims = 0;
    std::size_t start = 0;
    while (true) {
        if (start >= header.size()) bad("no ElementDataFile line in its first 64 KiB");
        const std::size_t end = std::min(header.find_first_of("\r\n", start), header.size());
        const std::string line = header.substr(start, end - start);
        start = end + 1;
        if (trim(line).empty()) continue;
        for (unsigned char c : line)
            if (c < 0x20 && c != '\t') bad("a control character in \"" + line.substr(0, 40) + "\"");
        const std::size_t eq = line.find('=');
        if (eq == std::string::npos) bad("expected \"Key = Value\", got \"" + line.substr(0, 60) + "\"");
        const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
        // MetaIO copies keys and string values into fixed buffers of 255 characters: only
        // identifiers of a sane length get to it (a longer key overflowed one, found by fuzzing).
        const bool identifier = !key.empty() && key.size() <= 64 && std::all_of(key.begin(), key.end(), [](unsigned char c) {
            return std::isalnum(c) || c == '_';
        });
        if (!identifier) bad("bad key in \"" + line.substr(0, 60) + "\" (keys are names of at most 64 letters, digits or _)");
        if (value.size() > 200) bad(key + ": the value is " + std::to_string(value.size()) + " characters long, at most 200 are read");
        if (!seen.insert(key).second) bad(key + " appears twice");
        const std::size_t n = static_cast<std::size_t>(nDims);
        const bool sized = key == "DimSize" || key == "ElementSpacing" || key == "ElementSize" || key == "Offset" ||
                           key == "Position" || key == "Origin" || key == "CenterOfRotation" ||
                           key == "TransformMatrix" || key == "Rotation" || key == "Orientation" ||
                           key == "AnatomicalOrientation";
        if (sized && nDims == 0) bad(key + " comes before NDims");
        if (key == "NDims") {
            numbers(key, value, 1, true);
            nDims = std::atoi(value.c_str());
            if (nDims < 2 || nDims > 3) bad("NDims " + value + " is not supported (2 or 3 are)");
        } else if (key == "DimSize") {
            numbers(key, value, n, true);
        } else if (key == "ElementSpacing" || key == "ElementSize" || key == "Offset" || key == "Position" ||
                   key == "Origin" || key == "CenterOfRotation") {
            numbers(key, value, n, false);
        } else if (key == "TransformMatrix" || key == "Rotation" || key == "Orientation") {
            numbers(key, value, n * n, false);
        } else if (key == "AnatomicalOrientation") {
            if (value.size() != n && value != "?" && value.find_first_not_of("?") != std::string::npos)
                bad(key + ": expected " + std::to_string(n) + " letters, got \"" + value + "\"");
        } else if (key == "ElementNumberOfChannels" || key == "HeaderSize" || key == "CompressedDataSize") {
            numbers(key, value, 1, true);
        } else if (key == "ElementMin" || key == "ElementMax") {
            numbers(key, value, 1, false);
        } else if (key == "ElementType") {
            if (value.rfind("MET_", 0) != 0 || value.find_first_of(" \t") != std::string::npos)
                bad("ElementType: \"" + value + "\" is not a MET_ type");
        } else if (key == "ElementDataFile") {
            if (value.empty()) bad("ElementDataFile is empty");
            if (value.find('%') != std::string::npos || value.rfind("LIST", 0) == 0)
                bad("ElementDataFile: file-name patterns and lists of slice files are not supported, got \"" + value +
                    "\"");
            return;  // MetaIO's header ends here
        }
    }
}

Decoded readMetaImage(const std::string& file, const std::string& prefix) {
    checkMetaImageHeader(file, prefix);
    vtkmetaio::MetaImage image;
    image.AutoFreeElementData(true);
    {
        StreamCapture capture;
        // The header first: dims are checked before MetaIO allocates the data.
        if (!image.Read(file.c_str(), false))
            fail(ErrorKind::Parse, prefix,
                 "not a readable MetaImage header" + (capture.firstLine().empty() ? "" : ": " + capture.firstLine()));
        if (image.NDims() < 2 || image.NDims() > 3)
            fail(ErrorKind::Parse, prefix, std::to_string(image.NDims()) + " dimensions are not supported (2 or 3 are)");
        checkDims(prefix, {image.DimSize(0), image.DimSize(1), image.NDims() == 3 ? image.DimSize(2) : 1});
        if (image.ElementNumberOfChannels() != 1)
            fail(ErrorKind::Parse, prefix,
                 std::to_string(image.ElementNumberOfChannels()) +
                     " components per voxel are not supported (only scalar volumes are)");
        checkMetaImageSize(file, prefix, image);
        if (!image.Read(file.c_str(), true))
            fail(ErrorKind::Parse, prefix,
                 "cannot read the voxels" + (capture.firstLine().empty() ? "" : ": " + capture.firstLine()));
    }
    const int n = image.NDims();
    Decoded d;
    d.dims = glm::ivec3(image.DimSize(0), image.DimSize(1), n == 3 ? image.DimSize(2) : 1);
    const std::size_t count = static_cast<std::size_t>(d.dims.x) * d.dims.y * d.dims.z;
    const void* data = image.ElementData();
    if (!data) fail(ErrorKind::Parse, prefix, "the file has no voxels");
    switch (image.ElementType()) {
    case vtkmetaio::MET_UCHAR: d.type = VoxelType::UInt8; d.bytes = toBytes<uint8_t>(data, count); break;
    case vtkmetaio::MET_CHAR: d.type = VoxelType::Int16; d.bytes = widenInt8(data, count); break;
    case vtkmetaio::MET_SHORT: d.type = VoxelType::Int16; d.bytes = toBytes<int16_t>(data, count); break;
    case vtkmetaio::MET_USHORT: d.type = VoxelType::UInt16; d.bytes = toBytes<uint16_t>(data, count); break;
    case vtkmetaio::MET_FLOAT: d.type = VoxelType::Float32; d.bytes = toBytes<float>(data, count); break;
    default: {
        char name[80] = "unknown";
        vtkmetaio::MET_TypeToString(image.ElementType(), name);
        fail(ErrorKind::Parse, prefix, unsupportedType(name));
    }
    }
    for (int i = 0; i < n; ++i) d.spacing[i] = std::abs(image.ElementSpacing(i));
    // TransformMatrix row i is the direction of index axis i (ITK's reading of it).
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) d.direction[i][j] = image.TransformMatrix(i, j);
    return d;
}


#else

namespace {
[[noreturn]] void vtkNotBuilt(const std::string& prefix, const char* format) {
    fail(ErrorKind::Unsupported, prefix, std::string(format) +
         " files need libsss built with SSS_WITH_VTK=ON (libvtk9-dev)");
}
}  // namespace

Decoded readNifti(const std::string&, const std::string& prefix) { vtkNotBuilt(prefix, "NIfTI"); }
Decoded readVti(const std::string&, const std::string& prefix) { vtkNotBuilt(prefix, "VTK XML image data (.vti)"); }
Decoded readDicomSeries(const std::string&, const std::string& prefix) { vtkNotBuilt(prefix, "DICOM"); }
Decoded readMetaImage(const std::string&, const std::string& prefix) { vtkNotBuilt(prefix, "MetaImage"); }

#endif

}  // namespace sss::detail
