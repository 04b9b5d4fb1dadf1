#pragma once
/// @file
/// Library log. libsss never writes to stdout; messages (GL debug output, context creation,
/// shader warnings) go to a handler the application may replace. The default handler prints
/// warnings and errors to stderr.

#include "sss/api.h"
#include <functional>
#include <string_view>

SSS_BEGIN_API

namespace sss {

enum class LogLevel { Debug, Info, Warning, Error };

using LogHandler = std::function<void(LogLevel, std::string_view message)>;

/// Replaces the process-wide log handler; an empty handler restores the default. Thread-safe.
void setLogHandler(LogHandler handler);

/// Sends a message to the current handler.
void log(LogLevel level, std::string_view message);

}  // namespace sss

SSS_END_API
