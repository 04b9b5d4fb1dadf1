#include "sss/log.h"

#include <cstdio>
#include <mutex>

namespace sss {
namespace {

std::mutex g_logMutex;
LogHandler g_handler;

void defaultHandler(LogLevel level, std::string_view message) {
    if (level < LogLevel::Warning) return;
    const char* tag = level == LogLevel::Error ? "error" : "warning";
    std::fprintf(stderr, "sss %s: %.*s\n", tag, static_cast<int>(message.size()), message.data());
}

}  // namespace

void setLogHandler(LogHandler handler) {
    std::lock_guard lock(g_logMutex);
    g_handler = std::move(handler);
}

void log(LogLevel level, std::string_view message) {
    std::lock_guard lock(g_logMutex);
    if (g_handler)
        g_handler(level, message);
    else
        defaultHandler(level, message);
}

}  // namespace sss
