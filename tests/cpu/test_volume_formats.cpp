// Volume::load for NRRD, MetaImage, NIfTI-1/2, VTK XML image data and DICOM series, and the
// Int16/Float32 voxel types. Every file is written here into a temp directory: NRRD, MetaImage,
// NIfTI-1 and DICOM by a few lines of code below (so the expected layout is spelled out, not
// taken from the library under test), NIfTI-2 and .vti by VTK's writers.
#include "sss/volume.h"

#include "test_helpers.h"

#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkXMLImageDataWriter.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <algorithm>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

using Catch::Contains;
using sss::ErrorKind;
using sss::Volume;
using sss::VoxelType;

namespace {

const glm::ivec3 kDims(4, 3, 2);  // every side different: a swapped axis shows
const glm::vec3 kSpacing(0.5f, 0.75f, 2.0f);

// Test values per type, at file index (x, y, z): negatives for the signed types.
double valueOf(VoxelType type, int x, int y, int z) {
    const int i = x + kDims.x * (y + kDims.y * z);
    switch (type) {
    case VoxelType::UInt8: return 10 + 9 * i;
    case VoxelType::UInt16: return 40000 + 1000 * i;
    case VoxelType::Int16: return -1024 + 137 * i;
    case VoxelType::Float32: return -2.5 + 0.375 * i;
    }
    return 0;
}

// Little-endian voxel bytes of valueOf in file order.
std::string voxelBytes(VoxelType type) {
    std::string out;
    for (int z = 0; z < kDims.z; ++z)
        for (int y = 0; y < kDims.y; ++y)
            for (int x = 0; x < kDims.x; ++x) {
                const double v = valueOf(type, x, y, z);
                char b[4];
                std::size_t n = sss::bytesPerVoxel(type);
                if (type == VoxelType::Float32) {
                    const float f = static_cast<float>(v);
                    std::memcpy(b, &f, 4);
                } else {
                    const auto u = static_cast<uint16_t>(static_cast<int32_t>(v));
                    b[0] = static_cast<char>(u & 0xff);
                    b[1] = static_cast<char>(u >> 8);
                }
                out.append(b, n);
            }
    return out;
}

// Checks dims, spacing, type and every value; `fileIndex` maps a loaded voxel to the file's.
void checkVolume(const Volume& v, VoxelType type, glm::ivec3 dims, glm::vec3 spacing,
                 const std::function<glm::ivec3(glm::ivec3)>& fileIndex) {
    REQUIRE(v.dims() == dims);
    CHECK(v.type() == type);
    for (int a = 0; a < 3; ++a) CHECK(v.spacing()[a] == Approx(spacing[a]).epsilon(1e-6));
    int wrong = 0;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const glm::ivec3 f = fileIndex({x, y, z});
                const double expected = valueOf(type, f.x, f.y, f.z);
                if (v.valueAt(x, y, z) != expected) {
                    if (++wrong <= 3) FAIL_CHECK("voxel " << x << "," << y << "," << z << " is " << v.valueAt(x, y, z) << ", expected " << expected);
                }
            }
    CHECK(wrong == 0);
}

glm::ivec3 same(glm::ivec3 p) { return p; }

const char* nrrdType(VoxelType t) {
    switch (t) {
    case VoxelType::UInt8: return "uint8";
    case VoxelType::UInt16: return "uint16";
    case VoxelType::Int16: return "int16";
    case VoxelType::Float32: return "float";
    }
    return "";
}

const char* metaType(VoxelType t) {
    switch (t) {
    case VoxelType::UInt8: return "MET_UCHAR";
    case VoxelType::UInt16: return "MET_USHORT";
    case VoxelType::Int16: return "MET_SHORT";
    case VoxelType::Float32: return "MET_FLOAT";
    }
    return "";
}

// An attached-header NRRD with the given "space directions" (one vector per file axis).
std::string nrrdFile(VoxelType type, const std::string& directions) {
    std::ostringstream h;
    h << "NRRD0004\n# written by the libsss tests\ntype: " << nrrdType(type) << "\ndimension: 3\nspace: left-posterior-superior\n"
      << "sizes: " << kDims.x << ' ' << kDims.y << ' ' << kDims.z << "\nspace directions: " << directions
      << "\nendian: little\nencoding: raw\n\n";
    return h.str() + voxelBytes(type);
}

const std::string kAlignedDirections = "(0.5,0,0) (0,0.75,0) (0,0,2)";

std::string metaHeader(VoxelType type, const std::string& transform, const std::string& dataFile) {
    std::ostringstream h;
    h << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
      << "TransformMatrix = " << transform << "\nElementSpacing = 0.5 0.75 2\nDimSize = " << kDims.x << ' ' << kDims.y << ' '
      << kDims.z << "\nElementType = " << metaType(type) << "\nElementDataFile = " << dataFile << "\n";
    return h.str();
}

// NIfTI-1 single file (.nii): 348-byte header, 4 bytes of extension flags, data. Orientation
// through the sform rows (qform_code 0), so the rows below are the direction * spacing.
std::string niftiFile(VoxelType type, const float srow[3][4]) {
    std::string h(352, '\0');
    auto put16 = [&](std::size_t at, int16_t v) { std::memcpy(&h[at], &v, 2); };
    auto put32 = [&](std::size_t at, int32_t v) { std::memcpy(&h[at], &v, 4); };
    auto putF = [&](std::size_t at, float v) { std::memcpy(&h[at], &v, 4); };
    put32(0, 348);
    const int16_t dim[8] = {3, int16_t(kDims.x), int16_t(kDims.y), int16_t(kDims.z), 1, 1, 1, 1};
    for (int i = 0; i < 8; ++i) put16(40 + 2 * i, dim[i]);
    const int16_t code = type == VoxelType::UInt8 ? 2 : type == VoxelType::Int16 ? 4 : type == VoxelType::Float32 ? 16 : 512;
    put16(70, code);
    put16(72, int16_t(8 * sss::bytesPerVoxel(type)));
    const float pixdim[8] = {1, kSpacing.x, kSpacing.y, kSpacing.z, 1, 1, 1, 1};
    for (int i = 0; i < 8; ++i) putF(76 + 4 * i, pixdim[i]);
    putF(108, 352.0f);  // vox_offset
    putF(112, 1.0f);    // scl_slope: stored values are real values
    put16(252, 0);      // qform_code
    put16(254, 1);      // sform_code: scanner anatomical
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) putF(280 + 16 * r + 4 * c, srow[r][c]);
    std::memcpy(&h[344], "n+1", 4);
    return h + voxelBytes(type);
}

const float kAlignedRows[3][4] = {{0.5f, 0, 0, 0}, {0, 0.75f, 0, 0}, {0, 0, 2.0f, 0}};

// A VTK image of the test values (for VTK's writers).
void fillImage(vtkImageData* image, VoxelType type) {
    image->SetDimensions(kDims.x, kDims.y, kDims.z);
    image->SetSpacing(kSpacing.x, kSpacing.y, kSpacing.z);
    const int vtkType = type == VoxelType::UInt8 ? VTK_UNSIGNED_CHAR
                        : type == VoxelType::UInt16 ? VTK_UNSIGNED_SHORT
                        : type == VoxelType::Int16 ? VTK_SHORT : VTK_FLOAT;
    image->AllocateScalars(vtkType, 1);
    const std::string bytes = voxelBytes(type);
    std::memcpy(image->GetScalarPointer(), bytes.data(), bytes.size());
}

// ---- a minimal DICOM writer (explicit VR little endian, one slice per file) ---------------------

struct DicomWriter {
    std::string out;
    void element(uint16_t group, uint16_t elem, const char* vr, std::string value) {
        if (value.size() % 2) value.push_back(std::strcmp(vr, "UI") == 0 || std::strcmp(vr, "OB") == 0 ? '\0' : ' ');
        auto u16 = [&](uint16_t v) { out.push_back(char(v & 0xff)), out.push_back(char(v >> 8)); };
        auto u32 = [&](uint32_t v) { u16(uint16_t(v & 0xffff)), u16(uint16_t(v >> 16)); };
        u16(group);
        u16(elem);
        out.append(vr, 2);
        const bool longForm = !std::strcmp(vr, "OB") || !std::strcmp(vr, "OW") || !std::strcmp(vr, "UN");
        if (longForm) {
            u16(0);
            u32(uint32_t(value.size()));
        } else {
            u16(uint16_t(value.size()));
        }
        out += value;
    }
    void us(uint16_t group, uint16_t elem, uint16_t v) {
        element(group, elem, "US", std::string{char(v & 0xff), char(v >> 8)});
    }
};

// Slice k of an int16 series at patient z = zPosition[k]; pixel (column x, row y) = valueOf at
// (x, y, sliceValues).
std::string dicomSlice(int instance, double zPosition, int sliceValues, double intercept) {
    DicomWriter meta;
    meta.element(0x0002, 0x0001, "OB", std::string("\0\1", 2));
    meta.element(0x0002, 0x0002, "UI", "1.2.840.10008.5.1.4.1.1.2");
    meta.element(0x0002, 0x0003, "UI", "1.2.3.4.5." + std::to_string(instance));
    meta.element(0x0002, 0x0010, "UI", "1.2.840.10008.1.2.1");
    meta.element(0x0002, 0x0012, "UI", "1.2.3.4.6");
    DicomWriter file;
    file.out = std::string(128, '\0') + "DICM";
    const uint32_t length = uint32_t(meta.out.size());
    file.element(0x0002, 0x0000, "UL", std::string{char(length & 0xff), char((length >> 8) & 0xff), char((length >> 16) & 0xff), char(length >> 24)});
    file.out += meta.out;
    DicomWriter d;
    d.element(0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2");
    d.element(0x0008, 0x0018, "UI", "1.2.3.4.5." + std::to_string(instance));
    d.element(0x0008, 0x0060, "CS", "CT");
    d.element(0x0018, 0x0050, "DS", "2");
    d.element(0x0020, 0x000D, "UI", "1.2.3.4.7");
    d.element(0x0020, 0x000E, "UI", "1.2.3.4.8");
    d.element(0x0020, 0x0013, "IS", std::to_string(instance));
    std::ostringstream position;
    position << "0\\0\\" << zPosition;
    d.element(0x0020, 0x0032, "DS", position.str());
    d.element(0x0020, 0x0037, "DS", "1\\0\\0\\0\\1\\0");
    d.us(0x0028, 0x0002, 1);
    d.element(0x0028, 0x0004, "CS", "MONOCHROME2");
    d.us(0x0028, 0x0010, uint16_t(kDims.y));  // rows
    d.us(0x0028, 0x0011, uint16_t(kDims.x));  // columns
    d.element(0x0028, 0x0030, "DS", "0.75\\0.5");  // row spacing (y), column spacing (x)
    d.us(0x0028, 0x0100, 16);
    d.us(0x0028, 0x0101, 16);
    d.us(0x0028, 0x0102, 15);
    d.us(0x0028, 0x0103, 1);  // signed
    std::ostringstream icpt;
    icpt << intercept;
    d.element(0x0028, 0x1052, "DS", icpt.str());
    d.element(0x0028, 0x1053, "DS", "1");
    std::string pixels;
    for (int y = 0; y < kDims.y; ++y)
        for (int x = 0; x < kDims.x; ++x) {
            const auto u = static_cast<uint16_t>(static_cast<int16_t>(valueOf(VoxelType::Int16, x, y, sliceValues) - intercept));
            pixels.push_back(char(u & 0xff));
            pixels.push_back(char(u >> 8));
        }
    d.element(0x7FE0, 0x0010, "OW", pixels);
    return file.out + d.out;
}

const VoxelType kTypes[] = {VoxelType::UInt8, VoxelType::UInt16, VoxelType::Int16, VoxelType::Float32};

}  // namespace

TEST_CASE("Volume::fromData holds int16 and float32 voxels", "[cpu][volume-formats]") {
    for (VoxelType type : {VoxelType::Int16, VoxelType::Float32}) {
        CAPTURE(sss::voxelTypeName(type));
        const std::string s = voxelBytes(type);
        const Volume v = Volume::fromData(kDims, type, std::vector<uint8_t>(s.begin(), s.end()), kSpacing);
        checkVolume(v, type, kDims, kSpacing, same);
        const double lo = valueOf(type, 0, 0, 0), hi = valueOf(type, 3, 2, 1);
        CHECK(v.valueRange() == std::make_pair(lo, hi));
        CHECK(v.transferFunctionRange() == std::make_pair(lo, hi));  // the data range
        CHECK(v.normalizedAt(0, 0, 0) == Approx(type == VoxelType::Int16 ? (lo + 32768) / 65535 : 0.0));
        CHECK(v.normalizedAt(3, 2, 1) == Approx(type == VoxelType::Int16 ? (hi + 32768) / 65535 : 1.0));
        // The TF-range histogram puts the lowest voxel in bin 0 and the highest in the last bin.
        const auto h = v.histogram(4, v.transferFunctionRange());
        CHECK(h[0] == 6);
        CHECK(h[3] == 6);
    }
}

TEST_CASE("Float32 volumes reject NaN and infinity", "[cpu][volume-formats]") {
    std::vector<uint8_t> bytes(8 * 4, 0);
    const float nan = std::nanf("");
    std::memcpy(bytes.data() + 12, &nan, 4);
    REQUIRE_SSS_ERROR(Volume::fromData({2, 2, 2}, VoxelType::Float32, bytes), ErrorKind::InvalidArgument,
                      Contains("voxel 3") && Contains("finite"));
}

TEST_CASE("The value window overrides the TF range, and is validated", "[cpu][volume-formats]") {
    const std::string s = voxelBytes(VoxelType::Int16);
    Volume v = Volume::fromData(kDims, VoxelType::Int16, std::vector<uint8_t>(s.begin(), s.end()));
    v.setValueWindow(std::make_pair(-1000.0, 2000.0));
    CHECK(v.transferFunctionRange() == std::make_pair(-1000.0, 2000.0));
    REQUIRE_SSS_ERROR(v.setValueWindow(std::make_pair(5.0, 5.0)), ErrorKind::InvalidArgument, Contains("lo < hi"));
    v.setValueWindow(std::nullopt);
    CHECK(v.transferFunctionRange() == v.valueRange());
    // uint8 keeps its 0..255 default.
    const Volume u8 = Volume::fromData({1, 1, 1}, VoxelType::UInt8, {7});
    CHECK(u8.transferFunctionRange() == std::make_pair(0.0, 255.0));
}

TEST_CASE("Volume::load reads NRRD of every voxel type", "[cpu][volume-formats]") {
    sss::test::TempDir dir;
    for (VoxelType type : kTypes) {
        CAPTURE(sss::voxelTypeName(type));
        const auto path = dir.write(std::string("v_") + sss::voxelTypeName(type) + ".nrrd", nrrdFile(type, kAlignedDirections));
        checkVolume(Volume::load(path), type, kDims, kSpacing, same);
    }
    // Detached header (.nhdr) with the data beside it.
    dir.write("d.raw", voxelBytes(VoxelType::Int16));
    const auto nhdr = dir.write("d.nhdr", "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 3 2\nspacings: 0.5 0.75 2\n"
                                          "endian: little\nencoding: raw\ndata file: d.raw\n");
    checkVolume(Volume::load(nhdr), VoxelType::Int16, kDims, kSpacing, same);
}

TEST_CASE("Volume::load undoes NRRD flips and axis swaps", "[cpu][volume-formats]") {
    sss::test::TempDir dir;
    const auto flipped = dir.write("flip.nrrd", nrrdFile(VoxelType::Int16, "(-0.5,0,0) (0,0.75,0) (0,0,-2)"));
    checkVolume(Volume::load(flipped), VoxelType::Int16, kDims, kSpacing,
                [](glm::ivec3 p) { return glm::ivec3(kDims.x - 1 - p.x, p.y, kDims.z - 1 - p.z); });
    // File axis 0 runs along world y, file axis 1 along world x.
    const auto swapped = dir.write("swap.nrrd", nrrdFile(VoxelType::Float32, "(0,0.5,0) (0.75,0,0) (0,0,2)"));
    checkVolume(Volume::load(swapped), VoxelType::Float32, {kDims.y, kDims.x, kDims.z}, {0.75f, 0.5f, 2.0f},
                [](glm::ivec3 p) { return glm::ivec3(p.y, p.x, p.z); });
    // Oblique: rejected, or kept in file order on request.
    const auto oblique = dir.write("oblique.nrrd", nrrdFile(VoxelType::UInt8, "(0.35355,0.35355,0) (-0.53033,0.53033,0) (0,0,2)"));
    REQUIRE_SSS_ERROR(Volume::load(oblique), ErrorKind::Parse, Contains(oblique.string()) && Contains("oblique"));
    sss::VolumeLoadOptions keep;
    keep.allowOblique = true;
    CHECK(Volume::load(oblique, keep).dims() == kDims);
}

TEST_CASE("Volume::load reads MetaImage (.mha and .mhd) with flips", "[cpu][volume-formats]") {
    sss::test::TempDir dir;
    for (VoxelType type : kTypes) {
        CAPTURE(sss::voxelTypeName(type));
        const auto mha = dir.write(std::string("m_") + sss::voxelTypeName(type) + ".mha",
                                   metaHeader(type, "1 0 0 0 1 0 0 0 1", "LOCAL") + voxelBytes(type));
        checkVolume(Volume::load(mha), type, kDims, kSpacing, same);
    }
    dir.write("m.raw", voxelBytes(VoxelType::UInt16));
    // Index axis y runs along -y.
    const auto mhd = dir.write("m.mhd", metaHeader(VoxelType::UInt16, "1 0 0 0 -1 0 0 0 1", "m.raw"));
    checkVolume(Volume::load(mhd), VoxelType::UInt16, kDims, kSpacing,
                [](glm::ivec3 p) { return glm::ivec3(p.x, kDims.y - 1 - p.y, p.z); });
}

TEST_CASE("Volume::load reads NIfTI-1 (.nii) with its sform, and NIfTI-2 (.nii.gz)", "[cpu][volume-formats]") {
    sss::test::TempDir dir;
    for (VoxelType type : kTypes) {
        CAPTURE(sss::voxelTypeName(type));
        const auto nii = dir.write(std::string("n_") + sss::voxelTypeName(type) + ".nii", niftiFile(type, kAlignedRows));
        checkVolume(Volume::load(nii), type, kDims, kSpacing, same);
    }
    const float flipX[3][4] = {{-0.5f, 0, 0, 0}, {0, 0.75f, 0, 0}, {0, 0, 2.0f, 0}};
    const auto flipped = dir.write("flip.nii", niftiFile(VoxelType::Int16, flipX));
    checkVolume(Volume::load(flipped), VoxelType::Int16, kDims, kSpacing,
                [](glm::ivec3 p) { return glm::ivec3(kDims.x - 1 - p.x, p.y, p.z); });

    vtkNew<vtkImageData> image;
    fillImage(image, VoxelType::Float32);
    vtkNew<vtkNIFTIImageWriter> writer;
    writer->SetInputData(image);
    writer->SetNIFTIVersion(2);
    const auto gz = dir.path() / "n2.nii.gz";
    writer->SetFileName(gz.string().c_str());
    writer->Write();
    REQUIRE(writer->GetErrorCode() == 0);
    checkVolume(Volume::load(gz), VoxelType::Float32, kDims, kSpacing, same);
}

TEST_CASE("Volume::load reads VTK XML image data (.vti) with its direction", "[cpu][volume-formats]") {
    sss::test::TempDir dir;
    for (VoxelType type : kTypes) {
        CAPTURE(sss::voxelTypeName(type));
        vtkNew<vtkImageData> image;
        fillImage(image, type);
        if (type == VoxelType::Int16) image->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, -1);  // z runs downwards
        vtkNew<vtkXMLImageDataWriter> writer;
        writer->SetInputData(image);
        const auto path = dir.path() / (std::string("x_") + sss::voxelTypeName(type) + ".vti");
        writer->SetFileName(path.string().c_str());
        REQUIRE(writer->Write() == 1);
        if (type == VoxelType::Int16)
            checkVolume(Volume::load(path), type, kDims, kSpacing,
                        [](glm::ivec3 p) { return glm::ivec3(p.x, p.y, kDims.z - 1 - p.z); });
        else
            checkVolume(Volume::load(path), type, kDims, kSpacing, same);
    }
}

TEST_CASE("Volume::load reads a DICOM series directory, ordered by position, in Hounsfield units",
          "[cpu][volume-formats]") {
    sss::test::TempDir dir;
    // File names and instance numbers out of order: the position along the normal decides.
    dir.write("a.dcm", dicomSlice(3, 5.0, 1, -1024.0));
    dir.write("b.dcm", dicomSlice(1, 7.0, 2, -1024.0));
    dir.write("c.dcm", dicomSlice(2, 3.0, 0, -1024.0));
    const Volume v = Volume::load(dir.path());
    checkVolume(v, VoxelType::Int16, {kDims.x, kDims.y, 3}, kSpacing, same);
}

TEST_CASE("Volume::load keeps .raw exactly as loadRaw", "[cpu][volume-formats]") {
    sss::test::TempDir dir;
    const auto path = dir.write("r_4x3x2_uint16.raw", voxelBytes(VoxelType::UInt16));
    const Volume a = Volume::load(path), b = Volume::loadRaw(path);
    CHECK(a.bytes() == b.bytes());
    CHECK(a.dims() == b.dims());
    CHECK(a.type() == VoxelType::UInt16);
    REQUIRE_SSS_ERROR(Volume::load(dir.write("bad_4x4x4.raw", "xy")), ErrorKind::Parse, Contains("Volume::loadRaw: "));
}

TEST_CASE("Each Volume::load reader rejects corrupted files with a message naming them", "[cpu][volume-formats]") {
    sss::test::TempDir dir;
    auto truncated = [](std::string s) { return s.substr(0, s.size() - 5); };
    auto expectParse = [](const std::filesystem::path& path) {
        CAPTURE(path.string());
        REQUIRE_SSS_ERROR(Volume::load(path), ErrorKind::Parse, Contains("Volume::load: " + path.string() + ": "));
    };
    expectParse(dir.write("t.nrrd", truncated(nrrdFile(VoxelType::UInt16, kAlignedDirections))));
    expectParse(dir.write("g.nrrd", "NRRD0004\ntype: banana\ndimension: 3\n\n"));
    expectParse(dir.write("t.mha", truncated(metaHeader(VoxelType::Int16, "1 0 0 0 1 0 0 0 1", "LOCAL") +
                                             voxelBytes(VoxelType::Int16))));
    expectParse(dir.write("g.mha", "this is not a header\n"));
    // Keys and values that would overflow MetaIO's 255-character buffers (found by fuzzing).
    const std::string longKey = "ObjectType = Image\nE1lement" + std::string(300, '\x9a') + " = x\nElementDataFile = LOCAL\n";
    expectParse(dir.write("k.mha", longKey));
    REQUIRE_SSS_ERROR(Volume::load(dir.write("k2.mha", longKey)), ErrorKind::Parse,
                      Contains("keys are names of at most 64 letters, digits or _"));
    REQUIRE_SSS_ERROR(Volume::load(dir.write("v.mha", "ObjectType = Image\nElementDataFile = " + std::string(300, 'd') + "\n")),
                      ErrorKind::Parse, Contains("ElementDataFile: the value is 300 characters long, at most 200 are read"));
    expectParse(dir.write("t.nii", truncated(niftiFile(VoxelType::Float32, kAlignedRows))));
    expectParse(dir.write("g.nii", std::string(400, 'x')));
    {
        vtkNew<vtkImageData> image;
        fillImage(image, VoxelType::UInt8);
        vtkNew<vtkXMLImageDataWriter> writer;
        writer->SetInputData(image);
        const auto vti = dir.path() / "t.vti";
        writer->SetFileName(vti.string().c_str());
        REQUIRE(writer->Write() == 1);
        std::ifstream in(vti, std::ios::binary);
        const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        expectParse(dir.write("t.vti", whole.substr(0, whole.size() / 2)));
    }
    expectParse(dir.write("g.vti", "<VTKFile type=\"ImageData\">"));
    sss::test::TempDir dicom;
    dicom.write("a.dcm", truncated(dicomSlice(1, 0.0, 0, 0.0)));
    expectParse(dicom.path());
    sss::test::TempDir notDicom;
    notDicom.write("readme.txt", "no images here");
    expectParse(notDicom.path());

    // Unsupported content: 64-bit voxels, several components, unknown extensions.
    const auto f64 = dir.write("f64.nrrd", "NRRD0004\ntype: double\ndimension: 3\nsizes: 1 1 1\nencoding: raw\nendian: little\n\n" +
                                               std::string(8, '\0'));
    REQUIRE_SSS_ERROR(Volume::load(f64), ErrorKind::Parse, Contains(f64.string()) && Contains("double"));
    const auto rgb = dir.write("rgb.mha", "ObjectType = Image\nNDims = 3\nDimSize = 1 1 1\nElementNumberOfChannels = 3\n"
                                          "ElementType = MET_UCHAR\nElementDataFile = LOCAL\nabc");
    REQUIRE_SSS_ERROR(Volume::load(rgb), ErrorKind::Parse, Contains(rgb.string()) && Contains("3 components"));
    const auto unknown = dir.write("v.xyz", "1234");
    REQUIRE_SSS_ERROR(Volume::load(unknown), ErrorKind::InvalidArgument, Contains(unknown.string()) && Contains(".nrrd"));
    REQUIRE_SSS_ERROR(Volume::load(dir.path() / "missing.nii"), ErrorKind::Io, Contains("missing.nii"));
}

TEST_CASE("Volume::load survives every format cut short at many lengths", "[cpu][volume-formats]") {
    // A cheap stand-in for fuzzing: each prefix throws sss::Error (never a crash, a hang or
    // another exception type) or, if only trailing markup is missing, loads the right values.
    sss::test::TempDir dir;
    std::vector<std::pair<std::string, std::string>> files{
        {"c.nrrd", nrrdFile(VoxelType::Int16, kAlignedDirections)},
        {"c.mha", metaHeader(VoxelType::Float32, "1 0 0 0 1 0 0 0 1", "LOCAL") + voxelBytes(VoxelType::Float32)},
        {"c.nii", niftiFile(VoxelType::UInt16, kAlignedRows)}};
    {
        vtkNew<vtkImageData> image;
        fillImage(image, VoxelType::Int16);
        vtkNew<vtkXMLImageDataWriter> writer;
        writer->SetInputData(image);
        writer->SetFileName((dir.path() / "whole.vti").string().c_str());
        REQUIRE(writer->Write() == 1);
        std::ifstream in(dir.path() / "whole.vti", std::ios::binary);
        files.emplace_back("c.vti", std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
    }
    for (const auto& [name, whole] : files) {
        CAPTURE(name);
        const std::size_t step = std::max<std::size_t>(1, whole.size() / 60);
        for (std::size_t length = 0; length < whole.size(); length += step) {
            CAPTURE(length);
            const auto path = dir.write(name, whole.substr(0, length));
            try {
                const Volume v = Volume::load(path);
                const VoxelType type = v.type();
                checkVolume(v, type, kDims, kSpacing, same);
            } catch (const sss::Error&) {
            }
        }
    }
    sss::test::TempDir dicom;
    const std::string slice = dicomSlice(1, 0.0, 0, 0.0);
    for (std::size_t length = 0; length < slice.size(); length += 16) {
        CAPTURE(length);
        dicom.write("s.dcm", slice.substr(0, length));
        CHECK_THROWS_AS(Volume::load(dicom.path()), sss::Error);
    }
}
