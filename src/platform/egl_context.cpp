#include "sss/context.h"
#include "sss/error.h"
#include "sss/log.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace sss {
namespace {

std::string eglErrorName(EGLint code) {
    switch (code) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
        default: {
            char buf[32];
            std::snprintf(buf, sizeof buf, "EGL error 0x%04x", static_cast<unsigned>(code));
            return buf;
        }
    }
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

bool envFlag(const char* name) {
    const char* v = std::getenv(name);
    return v && *v && std::strcmp(v, "0") != 0;
}

// EGL displays are process-wide and eglTerminate is not reference counted, so contexts that share
// a display count their users and the last one terminates it.
std::mutex g_displayMutex;
std::map<EGLDisplay, int> g_displayUsers;

void retainDisplay(EGLDisplay d) {
    std::lock_guard lock(g_displayMutex);
    ++g_displayUsers[d];
}

void releaseDisplay(EGLDisplay d) {
    std::lock_guard lock(g_displayMutex);
    if (--g_displayUsers[d] == 0) {
        g_displayUsers.erase(d);
        eglTerminate(d);
    }
}

struct DisplayCandidate {
    EglPlatform platform;
    EGLDisplay display;
    std::string description;
};

struct Devices {
    std::vector<EGLDeviceEXT> software, hardware;
};

Devices enumerateDevices(const char* clientExtensions) {
    Devices result;
    if (!hasExtension(clientExtensions, "EGL_EXT_device_enumeration") &&
        !hasExtension(clientExtensions, "EGL_EXT_device_base"))
        return result;
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (!queryDevices || !queryString) return result;
    EGLint count = 0;
    if (!queryDevices(0, nullptr, &count) || count <= 0) return result;
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
    queryDevices(count, devices.data(), &count);
    for (EGLint i = 0; i < count; ++i) {
        const char* ext = queryString(devices[static_cast<size_t>(i)], EGL_EXTENSIONS);
        (hasExtension(ext, "EGL_MESA_device_software") ? result.software : result.hardware)
            .push_back(devices[static_cast<size_t>(i)]);
    }
    return result;
}

}  // namespace

struct EglContext::Native {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
};

std::unique_ptr<EglContext> EglContext::create(const EglContextOptions& options) {
    const bool debug = options.debug || envFlag("SSS_GL_DEBUG");
    const bool preferSoftware = options.preferSoftware || envFlag("SSS_EGL_SOFTWARE");
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));

    std::vector<std::string> failures;
    const Devices devices = enumerateDevices(clientExtensions);

    // Order: surfaceless, device, default display + pbuffer — except that when a hardware EGL
    // device exists (an NVIDIA GPU, say) the device goes first: Mesa's surfaceless platform
    // would pick llvmpipe on such a machine, and NVIDIA's own surfaceless platform its GPU, so
    // only the device list tells hardware and software apart.
    std::vector<EglPlatform> order;
    if (options.platform != EglPlatform::Auto)
        order = {options.platform};
    else if (!devices.hardware.empty())
        order = {EglPlatform::Device, EglPlatform::Surfaceless, EglPlatform::DefaultPbuffer};
    else
        order = {EglPlatform::Surfaceless, EglPlatform::Device, EglPlatform::DefaultPbuffer};

    for (EglPlatform platform : order) {
        DisplayCandidate candidate{platform, EGL_NO_DISPLAY, ""};
        switch (platform) {
            case EglPlatform::Surfaceless:
                candidate.description = "EGL surfaceless (EGL_MESA_platform_surfaceless)";
                if (!getPlatformDisplay || !hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
                    failures.push_back(candidate.description + ": extension not available");
                    continue;
                }
                candidate.display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
                break;
            case EglPlatform::Device: {
                candidate.description = "EGL device (EGL_EXT_platform_device)";
                if (!getPlatformDisplay || !hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
                    failures.push_back(candidate.description + ": extension not available");
                    continue;
                }
                const auto& first = preferSoftware ? devices.software : devices.hardware;
                const auto& second = preferSoftware ? devices.hardware : devices.software;
                const auto& list = first.empty() ? second : first;
                if (list.empty()) {
                    failures.push_back(candidate.description + ": no EGL devices found");
                    continue;
                }
                const bool software = (&list == &devices.software);
                candidate.description = std::string("EGL device (") + (software ? "software" : "hardware") + ")";
                candidate.display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, list.front(), nullptr);
                break;
            }
            case EglPlatform::DefaultPbuffer:
            case EglPlatform::Auto:
                candidate.description = "EGL default display + pbuffer";
                candidate.display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
                break;
        }
        if (candidate.display == EGL_NO_DISPLAY) {
            failures.push_back(candidate.description + ": no display (" + eglErrorName(eglGetError()) + ")");
            continue;
        }
        EGLint major = 0, minor = 0;
        if (!eglInitialize(candidate.display, &major, &minor)) {
            failures.push_back(candidate.description + ": eglInitialize failed (" + eglErrorName(eglGetError()) + ")");
            continue;
        }
        retainDisplay(candidate.display);
        auto native = std::make_unique<Native>();
        native->display = candidate.display;
        auto fail = [&](const std::string& what) {
            failures.push_back(candidate.description + ": " + what + " (" + eglErrorName(eglGetError()) + ")");
            if (native->surface != EGL_NO_SURFACE) eglDestroySurface(native->display, native->surface);
            if (native->context != EGL_NO_CONTEXT) eglDestroyContext(native->display, native->context);
            releaseDisplay(native->display);
        };
        if (!eglBindAPI(EGL_OPENGL_API)) {
            fail("eglBindAPI(EGL_OPENGL_API) failed");
            continue;
        }
        const char* displayExtensions = eglQueryString(native->display, EGL_EXTENSIONS);
        const bool needsPbuffer = platform == EglPlatform::DefaultPbuffer ||
                                  !hasExtension(displayExtensions, "EGL_KHR_surfaceless_context");
        EGLConfig config = nullptr;
        EGLint configCount = 0;
        for (EGLint surfaceType : {EGL_PBUFFER_BIT, 0}) {
            if (needsPbuffer && surfaceType == 0) break;
            const EGLint configAttribs[] = {EGL_SURFACE_TYPE, surfaceType, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                            EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
                                            EGL_NONE};
            if (eglChooseConfig(native->display, configAttribs, &config, 1, &configCount) && configCount > 0) break;
        }
        if (configCount <= 0) {
            fail("no EGL config with OpenGL and RGBA8");
            continue;
        }
        const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
        native->context = eglCreateContext(native->display, config, EGL_NO_CONTEXT, contextAttribs);
        if (native->context == EGL_NO_CONTEXT) {
            fail("no OpenGL 4.5 core context");
            continue;
        }
        if (needsPbuffer) {
            const EGLint pbufferAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            native->surface = eglCreatePbufferSurface(native->display, config, pbufferAttribs);
            if (native->surface == EGL_NO_SURFACE) {
                fail("eglCreatePbufferSurface failed");
                continue;
            }
        }
        if (!eglMakeCurrent(native->display, native->surface, native->surface, native->context)) {
            fail("eglMakeCurrent failed");
            continue;
        }
        std::unique_ptr<EglContext> result(new EglContext());
        result->m_native = std::move(native);
        for (const std::string& f : failures) log(LogLevel::Info, "EglContext: skipped " + f);
        result->initializeGl(eglGetProcAddress, debug,
                             candidate.description);
        return result;
    }

    std::string message = "EglContext: could not create a headless OpenGL 4.5 core context:";
    for (const std::string& f : failures) message += "\n  - " + f;
    message += "\n(on Debian, scripts/install-deps.sh installs Mesa's llvmpipe driver, libgl1-mesa-dri)";
    throw Error(ErrorKind::Gl, message);
}

EglContext::~EglContext() {
    if (!m_native) return;
    if (eglGetCurrentContext() == m_native->context)
        eglMakeCurrent(m_native->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (m_native->surface != EGL_NO_SURFACE) eglDestroySurface(m_native->display, m_native->surface);
    eglDestroyContext(m_native->display, m_native->context);
    releaseDisplay(m_native->display);
}

void EglContext::makeCurrent() {
    if (!eglMakeCurrent(m_native->display, m_native->surface, m_native->surface, m_native->context))
        throw Error(ErrorKind::Gl, "EglContext::makeCurrent failed (" + eglErrorName(eglGetError()) + ")");
}

}  // namespace sss
