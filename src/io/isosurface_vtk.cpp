// Isosurface extraction through VTK 9 (SSS_WITH_VTK): flying edges, windowed-sinc smoothing,
// quadric decimation, normals. VTK's headers stay in this file.
#include "sss/isosurface.h"

#include "sss/error.h"
#include "util/format.h"

#if SSS_WITH_VTK
#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkDecimatePro.h>
#include <vtkQuadricDecimation.h>
#include <vtkShortArray.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>
#include <vtkWindowedSincPolyDataFilter.h>
#endif

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace sss {
namespace {

[[noreturn]] void invalid(const std::string& field, const std::string& reason) {
    throw Error(ErrorKind::InvalidArgument, "IsosurfaceOptions", field, reason);
}

void validate(const Volume& volume, const IsosurfaceOptions& o) {
    const auto [lo, hi] = volume.valueRange();
    if (!std::isfinite(o.value) || !(o.value > lo && o.value < hi))
        invalid("value", "must lie strictly between the volume's smallest and largest values (" +
                             detail::formatNumber(lo) + ", " + detail::formatNumber(hi) + "), got " +
                             detail::formatNumber(o.value));
    if (o.smoothingIterations < 0)
        invalid("smoothingIterations", "must be >= 0, got " + std::to_string(o.smoothingIterations));
    if (o.maxTriangles < 0) invalid("maxTriangles", "must be >= 0, got " + std::to_string(o.maxTriangles));
}

#if SSS_WITH_VTK

// The voxels as VTK image data in physical units, centred on the volume's centre. VTK keeps its
// own copy: a volume is at most 4 GiB, and the extraction runs once.
vtkSmartPointer<vtkImageData> toImageData(const Volume& volume) {
    const glm::ivec3 dims = volume.dims();
    const glm::dvec3 spacing(volume.spacing());
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(dims.x, dims.y, dims.z);
    image->SetSpacing(spacing.x, spacing.y, spacing.z);
    const glm::dvec3 half = 0.5 * glm::dvec3(dims - 1) * spacing;
    image->SetOrigin(-half.x, -half.y, -half.z);
    vtkSmartPointer<vtkDataArray> scalars;
    switch (volume.type()) {
        case VoxelType::UInt8: scalars = vtkSmartPointer<vtkUnsignedCharArray>::New(); break;
        case VoxelType::UInt16: scalars = vtkSmartPointer<vtkUnsignedShortArray>::New(); break;
        case VoxelType::Int16: scalars = vtkSmartPointer<vtkShortArray>::New(); break;
        case VoxelType::Float32: scalars = vtkSmartPointer<vtkFloatArray>::New(); break;
    }
    scalars->SetNumberOfComponents(1);
    scalars->SetNumberOfTuples(static_cast<vtkIdType>(volume.voxelCount()));
    // Little-endian voxels, as every Debian target stores them: a plain copy.
    std::memcpy(scalars->GetVoidPointer(0), volume.bytes().data(), volume.bytes().size());
    image->GetPointData()->SetScalars(scalars);
    return image;
}

// Whether most normals point towards lower values: the volume one voxel along each normal of
// every 64th vertex, against one voxel back (nearest voxels).
bool pointsToLowerValues(const Volume& volume, const std::vector<glm::vec3>& positions,
                         const std::vector<glm::vec3>& normals) {
    const glm::vec3 spacing = volume.spacing();
    const glm::vec3 half = 0.5f * glm::vec3(volume.dims() - 1) * spacing;
    const float step = std::max({spacing.x, spacing.y, spacing.z});
    auto valueNear = [&](glm::vec3 p) {
        const glm::ivec3 v = glm::clamp(glm::ivec3(glm::round((p + half) / spacing)), glm::ivec3(0), volume.dims() - 1);
        return volume.valueAt(v.x, v.y, v.z);
    };
    long votes = 0;
    for (std::size_t i = 0; i < positions.size(); i += 64) {
        const double ahead = valueNear(positions[i] + step * normals[i]), behind = valueNear(positions[i] - step * normals[i]);
        votes += ahead < behind ? 1 : ahead > behind ? -1 : 0;
    }
    return votes >= 0;
}

Mesh toMesh(const Volume& volume, vtkPolyData* surface, const IsosurfaceOptions& o) {
    vtkPoints* points = surface->GetPoints();
    vtkDataArray* normals = surface->GetPointData()->GetNormals();
    if (!points || !normals || surface->GetNumberOfPolys() == 0)
        invalid("value", "gives an empty surface (" + detail::formatNumber(o.value) + ")");
    std::vector<glm::vec3> positions(static_cast<std::size_t>(points->GetNumberOfPoints()));
    std::vector<glm::vec3> vertexNormals(positions.size());
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
        double p[3], n[3];
        points->GetPoint(i, p);
        normals->GetTuple(i, n);
        positions[static_cast<std::size_t>(i)] = glm::vec3(p[0], p[1], p[2]);
        vertexNormals[static_cast<std::size_t>(i)] = glm::vec3(n[0], n[1], n[2]);
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(static_cast<std::size_t>(surface->GetNumberOfPolys()) * 3);
    vtkCellArray* polys = surface->GetPolys();
    vtkNew<vtkIdList> cell;
    for (polys->InitTraversal(); polys->GetNextCell(cell);) {
        if (cell->GetNumberOfIds() != 3) continue;  // the triangle filter leaves none
        for (int k = 0; k < 3; ++k) indices.push_back(static_cast<std::uint32_t>(cell->GetId(k)));
    }
    // A smoothed vertex can keep a zero normal where the surface pinches to a point: drop those
    // vertices' triangles rather than fail.
    std::vector<std::uint32_t> kept;
    kept.reserve(indices.size());
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        bool usable = true;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 n = vertexNormals[indices[t + k]];
            usable = usable && std::isfinite(n.x + n.y + n.z) && glm::dot(n, n) > 0.0f;
        }
        if (usable) kept.insert(kept.end(), indices.begin() + t, indices.begin() + t + 3);
    }
    for (glm::vec3& n : vertexNormals)
        if (!(glm::dot(n, n) > 0.0f) || !std::isfinite(n.x + n.y + n.z)) n = glm::vec3(0.0f, 0.0f, 1.0f);
    if (kept.empty()) invalid("value", "gives an empty surface (" + detail::formatNumber(o.value) + ")");
    if (!pointsToLowerValues(volume, positions, vertexNormals)) {
        for (glm::vec3& n : vertexNormals) n = -n;
        for (std::size_t t = 0; t + 2 < kept.size(); t += 3) std::swap(kept[t + 1], kept[t + 2]);
    }
    return Mesh::fromArrays(std::move(positions), std::move(kept), std::move(vertexNormals),
                            "isosurface " + detail::formatNumber(o.value));
}

#endif

}  // namespace

Mesh extractIsosurface(const Volume& volume, const IsosurfaceOptions& options) {
    validate(volume, options);
#if SSS_WITH_VTK
    vtkNew<vtkFlyingEdges3D> edges;
    edges->SetInputData(toImageData(volume));
    edges->SetValue(0, options.value);
    edges->ComputeNormalsOff();  // recomputed after smoothing and decimation
    edges->ComputeGradientsOff();
    edges->ComputeScalarsOff();
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputConnection(edges->GetOutputPort());
    vtkAlgorithmOutput* last = triangles->GetOutputPort();
    vtkNew<vtkWindowedSincPolyDataFilter> smooth;
    if (options.smoothingIterations > 0) {
        smooth->SetInputConnection(last);
        smooth->SetNumberOfIterations(options.smoothingIterations);
        smooth->SetPassBand(0.1);
        smooth->NonManifoldSmoothingOn();
        smooth->NormalizeCoordinatesOn();
        last = smooth->GetOutputPort();
    }
    // Quadric collapses first; they stop short on real scans (a CT head kept 400 000 of 450 000
    // triangles for a budget of 150 000: open borders where the scan is cut, thin parts), so the
    // rest goes to a decimation that may also remove border vertices.
    vtkNew<vtkQuadricDecimation> decimate;
    decimate->VolumePreservationOn();
    vtkNew<vtkDecimatePro> finish;
    finish->PreserveTopologyOff();
    finish->SplittingOff();
    finish->BoundaryVertexDeletionOn();
    if (options.maxTriangles > 0) {
        triangles->Update();
        const auto reduceTo = [&](auto& filter, vtkIdType count) {
            if (count <= options.maxTriangles) return false;
            filter.SetInputConnection(last);
            filter.SetTargetReduction(1.0 - static_cast<double>(options.maxTriangles) / static_cast<double>(count));
            filter.Update();
            last = filter.GetOutputPort();
            return true;
        };
        if (reduceTo(*decimate, triangles->GetOutput()->GetNumberOfPolys()))
            reduceTo(*finish, decimate->GetOutput()->GetNumberOfPolys());
    }
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputConnection(last);
    normals->SplittingOff();  // smooth normals everywhere: the scattering needs no hard edges
    normals->ConsistencyOn();
    normals->AutoOrientNormalsOff();
    normals->ComputePointNormalsOn();
    normals->ComputeCellNormalsOff();
    normals->Update();
    return toMesh(volume, normals->GetOutput(), options);
#else
    throw Error(ErrorKind::Unsupported,
                "extractIsosurface needs libsss built with SSS_WITH_VTK=ON (libvtk9-dev): VTK's flying edges");
#endif
}

}  // namespace sss
