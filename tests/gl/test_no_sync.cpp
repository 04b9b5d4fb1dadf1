// No render path waits for the GPU (issue 30): once a renderer has warmed up, neither a frame
// after a light change nor an unchanged frame makes a synchronising call — a read-back, a
// glFinish, a mapping, a fence wait or a blocking query result — unless an option asks for one
// (finishEachPass, gpuPassTimes), and but for the path tracer on software rasterisers. The test
// counts them by wrapping glad's entry points.
#include "support/gl_test.h"
#include "support/scenes.h"

#include "gl/device.h"
#include "gl/gl.h"

#include <catch2/catch.hpp>
#include <sss/hybrid_compositor.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/option_names.h>
#include <sss/procedural.h>
#include <sss/volume_scattering_renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <string>

using namespace sss;

namespace {

int g_syncs = 0;
std::string g_lastSync;

void counted(const char* name) {
    ++g_syncs;
    g_lastSync = name;
}

// The real entry points, restored when the scope ends.
struct Originals {
    PFNGLFINISHPROC finish = glad_glFinish;
    PFNGLGETNAMEDBUFFERSUBDATAPROC getNamedBufferSubData = glad_glGetNamedBufferSubData;
    PFNGLGETBUFFERSUBDATAPROC getBufferSubData = glad_glGetBufferSubData;
    PFNGLGETTEXTUREIMAGEPROC getTextureImage = glad_glGetTextureImage;
    PFNGLGETTEXTURESUBIMAGEPROC getTextureSubImage = glad_glGetTextureSubImage;
    PFNGLGETTEXIMAGEPROC getTexImage = glad_glGetTexImage;
    PFNGLREADPIXELSPROC readPixels = glad_glReadPixels;
    PFNGLREADNPIXELSPROC readnPixels = glad_glReadnPixels;
    PFNGLMAPBUFFERRANGEPROC mapBufferRange = glad_glMapBufferRange;
    PFNGLMAPNAMEDBUFFERRANGEPROC mapNamedBufferRange = glad_glMapNamedBufferRange;
    PFNGLMAPBUFFERPROC mapBuffer = glad_glMapBuffer;
    PFNGLMAPNAMEDBUFFERPROC mapNamedBuffer = glad_glMapNamedBuffer;
    PFNGLCLIENTWAITSYNCPROC clientWaitSync = glad_glClientWaitSync;
    PFNGLGETQUERYOBJECTIVPROC getQueryObjectiv = glad_glGetQueryObjectiv;
    PFNGLGETQUERYOBJECTUIVPROC getQueryObjectuiv = glad_glGetQueryObjectuiv;
    PFNGLGETQUERYOBJECTI64VPROC getQueryObjecti64v = glad_glGetQueryObjecti64v;
    PFNGLGETQUERYOBJECTUI64VPROC getQueryObjectui64v = glad_glGetQueryObjectui64v;
};
Originals g_real;

/// While alive, every synchronising GL call adds to g_syncs (and still runs).
class SyncCounter {
public:
    SyncCounter() {
        g_real = Originals{};
        g_syncs = 0;
        glad_glFinish = [] { counted("glFinish"), g_real.finish(); };
        glad_glGetNamedBufferSubData = [](GLuint b, GLintptr o, GLsizeiptr s, void* d) {
            counted("glGetNamedBufferSubData"), g_real.getNamedBufferSubData(b, o, s, d);
        };
        glad_glGetBufferSubData = [](GLenum t, GLintptr o, GLsizeiptr s, void* d) {
            counted("glGetBufferSubData"), g_real.getBufferSubData(t, o, s, d);
        };
        glad_glGetTextureImage = [](GLuint t, GLint l, GLenum f, GLenum ty, GLsizei s, void* p) {
            counted("glGetTextureImage"), g_real.getTextureImage(t, l, f, ty, s, p);
        };
        glad_glGetTextureSubImage = [](GLuint t, GLint l, GLint x, GLint y, GLint z, GLsizei w, GLsizei h, GLsizei d,
                                       GLenum f, GLenum ty, GLsizei s, void* p) {
            counted("glGetTextureSubImage"), g_real.getTextureSubImage(t, l, x, y, z, w, h, d, f, ty, s, p);
        };
        glad_glGetTexImage = [](GLenum t, GLint l, GLenum f, GLenum ty, void* p) {
            counted("glGetTexImage"), g_real.getTexImage(t, l, f, ty, p);
        };
        glad_glReadPixels = [](GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, void* p) {
            counted("glReadPixels"), g_real.readPixels(x, y, w, h, f, t, p);
        };
        glad_glReadnPixels = [](GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, GLsizei s, void* p) {
            counted("glReadnPixels"), g_real.readnPixels(x, y, w, h, f, t, s, p);
        };
        glad_glMapBufferRange = [](GLenum t, GLintptr o, GLsizeiptr l, GLbitfield a) {
            return counted("glMapBufferRange"), g_real.mapBufferRange(t, o, l, a);
        };
        glad_glMapNamedBufferRange = [](GLuint b, GLintptr o, GLsizeiptr l, GLbitfield a) {
            return counted("glMapNamedBufferRange"), g_real.mapNamedBufferRange(b, o, l, a);
        };
        glad_glMapBuffer = [](GLenum t, GLenum a) { return counted("glMapBuffer"), g_real.mapBuffer(t, a); };
        glad_glMapNamedBuffer = [](GLuint b, GLenum a) { return counted("glMapNamedBuffer"), g_real.mapNamedBuffer(b, a); };
        glad_glClientWaitSync = [](GLsync s, GLbitfield f, GLuint64 t) {
            return counted("glClientWaitSync"), g_real.clientWaitSync(s, f, t);
        };
        // Query results block unless only availability is asked.
        glad_glGetQueryObjectiv = [](GLuint q, GLenum p, GLint* v) {
            if (p != GL_QUERY_RESULT_AVAILABLE) counted("glGetQueryObjectiv");
            g_real.getQueryObjectiv(q, p, v);
        };
        glad_glGetQueryObjectuiv = [](GLuint q, GLenum p, GLuint* v) {
            if (p != GL_QUERY_RESULT_AVAILABLE) counted("glGetQueryObjectuiv");
            g_real.getQueryObjectuiv(q, p, v);
        };
        glad_glGetQueryObjecti64v = [](GLuint q, GLenum p, GLint64* v) {
            if (p != GL_QUERY_RESULT_AVAILABLE) counted("glGetQueryObjecti64v");
            g_real.getQueryObjecti64v(q, p, v);
        };
        glad_glGetQueryObjectui64v = [](GLuint q, GLenum p, GLuint64* v) {
            if (p != GL_QUERY_RESULT_AVAILABLE) counted("glGetQueryObjectui64v");
            g_real.getQueryObjectui64v(q, p, v);
        };
    }
    ~SyncCounter() {
        glad_glFinish = g_real.finish;
        glad_glGetNamedBufferSubData = g_real.getNamedBufferSubData;
        glad_glGetBufferSubData = g_real.getBufferSubData;
        glad_glGetTextureImage = g_real.getTextureImage;
        glad_glGetTextureSubImage = g_real.getTextureSubImage;
        glad_glGetTexImage = g_real.getTexImage;
        glad_glReadPixels = g_real.readPixels;
        glad_glReadnPixels = g_real.readnPixels;
        glad_glMapBufferRange = g_real.mapBufferRange;
        glad_glMapNamedBufferRange = g_real.mapNamedBufferRange;
        glad_glMapBuffer = g_real.mapBuffer;
        glad_glMapNamedBuffer = g_real.mapNamedBuffer;
        glad_glClientWaitSync = g_real.clientWaitSync;
        glad_glGetQueryObjectiv = g_real.getQueryObjectiv;
        glad_glGetQueryObjectuiv = g_real.getQueryObjectuiv;
        glad_glGetQueryObjecti64v = g_real.getQueryObjecti64v;
        glad_glGetQueryObjectui64v = g_real.getQueryObjectui64v;
    }
    SyncCounter(const SyncCounter&) = delete;
    SyncCounter& operator=(const SyncCounter&) = delete;
};

const DirectionalLight kKey{.direction = {-1.0f, -1.0f, -0.6f}};
const DirectionalLight kNudged{.direction = {-1.0f, -1.1f, -0.5f}};

struct FrameSyncs {
    int change = 0, fixed = 0;
    std::string last;
};

/// Warms `renderer` up (shaders, tables, uploads), then counts the synchronising calls of one
/// frame after a light change and of one unchanged frame.
template <typename Renderer>
FrameSyncs countSyncs(Renderer& renderer, const Camera& camera) {
    RenderTarget target(48, 32);
    for (const DirectionalLight& light : {kKey, kNudged, kKey}) {
        renderer.setLights({light});
        renderer.render(camera, target);
    }
    FrameSyncs counts;
    SyncCounter counter;
    renderer.setLights({kNudged});
    renderer.render(camera, target);
    counts.change = g_syncs;
    renderer.render(camera, target);
    counts.fixed = g_syncs - counts.change;
    counts.last = g_lastSync;
    return counts;
}

void checkNoSyncs(const FrameSyncs& counts) {
    INFO("the last synchronising call: " << counts.last);
    CHECK(counts.change == 0);
    CHECK(counts.fixed == 0);
}

}  // namespace

TEST_CASE("no mesh render path waits for the GPU", "[gl][mesh][sync]") {
    test::GlTestScope gl;
    const Mesh mesh = makeFolds(48, 32);  // concave: some vertices no map sees, so the fill runs
    const Camera camera = test::orbitCamera(mesh.bounds(), 30.0f, 20.0f);
    for (MeshCombine combine : {MeshCombine::PerPixel, MeshCombine::PerVertex, MeshCombine::VertexEstimate}) {
        INFO("combine " << enumName(combine));
        MeshScatteringRenderer renderer({.shading = MeshShading::Scattering, .combine = combine, .cameras = 4,
                                         .samples = 8, .mapResolution = 64, .lightMapResolution = 64,
                                         .accumulationFrames = 1});
        renderer.setMesh(mesh);
        checkNoSyncs(countSyncs(renderer, camera));
    }
    MeshScatteringRenderer blinnPhong({.shading = MeshShading::BlinnPhong});
    blinnPhong.setMesh(mesh);
    checkNoSyncs(countSyncs(blinnPhong, camera));
    gl.requireNoErrors();
}

TEST_CASE("no volume render path waits for the GPU", "[gl][volume][sync]") {
    test::GlTestScope gl;
    const Volume volume = makeBlobsVolume(24);
    const Camera camera = test::orbitCamera(volume.worldBounds(), 35.0f, 15.0f);
    struct Case {
        VolumeRenderOptions options;
        const char* name;
    };
    const Case cases[] = {
        {{.shading = VolumeShading::EmissionAbsorption}, "emission-absorption"},
        {{.shading = VolumeShading::Gradient, .rayCaster = RayCaster::Compute}, "gradient, compute"},
        {{.shading = VolumeShading::Scattering}, "scattering"},
        {{.shading = VolumeShading::ScatteringGradient, .eyePass = true}, "scattering-gradient, eye pass"},
        {{.shading = VolumeShading::Scattering, .rayCaster = RayCaster::Compute}, "scattering, compute"},
        // Its change frame builds the preview, its "fixed" frame the full light volume.
        {{.shading = VolumeShading::Scattering, .lightVolumePreviewScale = 0.5f}, "scattering, light-volume preview"},
        {{.shading = VolumeShading::Scattering, .model = VolumeModel::Physical, .multipleScattering = true},
         "path tracer"},
        // The cache holds all its photons after the change frame: the fixed frame traces none.
        {{.shading = VolumeShading::Scattering, .model = VolumeModel::Physical, .multipleScatteringCache = true,
          .cacheResolution = 16, .cachePhotonsPerFrame = 4096, .cachePhotons = 4096,
          .cacheViewEvaluation = CacheViewEvaluation::PerCell},
         "multiple-scattering cache, per cell"},
        {{.shading = VolumeShading::Scattering, .model = VolumeModel::Physical, .multipleScatteringCache = true,
          .cacheResolution = 16, .cachePhotonsPerFrame = 4096, .cachePhotons = 4096,
          .cacheViewEvaluation = CacheViewEvaluation::PerSample},
         "multiple-scattering cache, per sample"},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        VolumeScatteringRenderer renderer(c.options);
        renderer.setVolume(volume);
        renderer.setTransferFunction(test::blobsTransferFunction());
        const FrameSyncs counts = countSyncs(renderer, camera);
        if (c.options.multipleScattering && gl::currentDeviceIsSoftware()) {
            // The one exception: llvmpipe caps an invocation's loop iterations, so there the path
            // tracer resumes paths over dispatches and reads the unfinished count after each.
            INFO("the last synchronising call: " << counts.last);
            CHECK(counts.last == "glGetNamedBufferSubData");
        } else if (c.options.multipleScatteringCache && gl::currentDeviceIsSoftware()) {
            // The same for the cache's photons, in the frames that trace them only.
            INFO("the last synchronising call: " << counts.last);
            CHECK(counts.last == "glGetNamedBufferSubData");
            CHECK(counts.fixed == 0);
        } else {
            checkNoSyncs(counts);
        }
    }
    gl.requireNoErrors();
}

TEST_CASE("the hybrid compositor waits for the GPU only when timing asks it to", "[gl][hybrid][sync]") {
    test::GlTestScope gl;
    HybridCompositor scene({.cornellBox = true});
    scene.addMesh(makeUvSphere(16, 12, 0.3f), glm::translate(glm::mat4(1.0f), {-0.4f, 0.0f, 0.0f}),
                  {.shading = MeshShading::Scattering, .mapResolution = 64, .lightMapResolution = 64,
                   .accumulationFrames = 1});
    scene.addVolume(makeBlobsVolume(24), glm::translate(glm::mat4(1.0f), {0.4f, 0.0f, 0.0f}),
                    {.shading = VolumeShading::Scattering})
        .setTransferFunction(test::blobsTransferFunction());
    Camera camera;
    camera.frame(scene.bounds());
    checkNoSyncs(countSyncs(scene, camera));

    SECTION("finishEachPass is the option that asks for waits") {
        VolumeScatteringRenderer timed({.finishEachPass = true});
        timed.setVolume(makeBlobsVolume(16));
        const FrameSyncs counts = countSyncs(timed, camera);
        CHECK(counts.fixed > 0);  // the counter sees waits where there are some
    }
    gl.requireNoErrors();
}
