#pragma once
// Command-line parsing and scene loading shared by sss-render and sss-viewer: numbers and
// vectors from option values, the data directory, and meshes/volumes named by a path or by
// "procedural:NAME".
#include <sss/display.h>
#include <sss/mesh.h>
#include <sss/volume_scattering_renderer.h>
#include <sss/volume.h>

#include <glm/vec3.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

namespace examples {

/// Bad command-line usage: reported on stderr with exit code 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Walks argv option by option: `for (OptionCursor args(argc, argv); args.next();)`, then
/// option() is the current word and value() takes the word after it as its argument.
class OptionCursor {
public:
    OptionCursor(int argc, char** argv) : m_argc(argc), m_argv(argv) {}
    bool next() {
        if (++m_index >= m_argc) return false;
        m_option = m_argv[m_index];
        return true;
    }
    const std::string& option() const { return m_option; }
    bool isHelp() const { return m_option == "--help" || m_option == "-h"; }
    /// @throws UsageError "<option>: missing value" at the end of argv.
    std::string value() {
        if (m_index + 1 >= m_argc) throw UsageError(m_option + ": missing value");
        return m_argv[++m_index];
    }

private:
    int m_argc;
    char** m_argv;
    int m_index = 0;
    std::string m_option;
};

float parseFloat(const std::string& option, const std::string& text);
int parseInt(const std::string& option, const std::string& text);
std::vector<std::string> split(const std::string& text, char separator);
glm::vec3 parseVec3(const std::string& option, const std::string& text);  ///< "X,Y,Z"
glm::ivec3 parseDims(const std::string& option, const std::string& text);  ///< "XxYxZ"
/// A plane and where it is given.
struct ParsedClipPlane {
    sss::ClipPlane plane;
    sss::CropSpace space;
};
/// "PX,PY,PZ,NX,NY,NZ": a point on the plane and the normal of the side kept (world space); or
/// "NX,NY,NZ,D": the points p of the volume's normalised data coordinates with n . p + d >= 0.
ParsedClipPlane parseClipPlane(const std::string& option, const std::string& text);
/// Every plane of `texts` (parseClipPlane) into `clip`, all in one space.
void addClipPlanes(const std::string& option, const std::vector<std::string>& texts, sss::VolumeClip& clip);
/// "X0,Y0,Z0,X1,Y1,Z1": the crop box's corners, min below max on each axis; in `space` Data,
/// normalised data coordinates in [0, 1].
std::pair<glm::vec3, glm::vec3> parseCrop(const std::string& option, const std::string& text, sss::CropSpace space);
/// "LO,HI" with LO < HI (a value window, e.g. --tf-range -1000,2000).
std::optional<std::pair<double, double>> parseRange(const std::string& option, const std::string& text);
float parseExposure(const std::string& option, const std::string& text);  ///< stops in [-64, 64]

/// --data-dir if given, else $SSS_DATA_DIR, else ../shared/data if it exists, else empty.
std::filesystem::path dataDirectory(const std::string& dataDirOption);

/// procedural:sphere|torus|slab|folds, or an .obj file (relative paths not found as given are looked up
/// in dataDir and dataDir/meshes). Throws UsageError for an unknown procedural name.
sss::Mesh loadSceneMesh(const std::string& path, const std::filesystem::path& dataDir);
/// procedural:blobs|shell|bucky, a NRRD/MetaImage/NIfTI/.vti file or DICOM directory
/// (Volume::load), or else a headerless raw file read with `options` (Volume::loadRaw). Looked
/// up like meshes, in dataDir/volumes.
sss::Volume loadSceneVolume(const std::string& path, const std::filesystem::path& dataDir,
                            const sss::RawLoadOptions& options = {});

/// Runs `body` and maps what it throws to a message on stderr ("<program>: ...") and an exit
/// code: 2 for bad usage (UsageError, sss::Error InvalidArgument), 1 for other failures.
int runReportingErrors(const char* program, const std::function<int()>& body);

}  // namespace examples
