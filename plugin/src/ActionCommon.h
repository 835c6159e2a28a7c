#pragma once
/// What the GUI actions share: errors into CloudCompare's console and the
/// wait cursor.
#include <ccMainAppInterface.h>

#include <QApplication>
#include <QString>

namespace storey::plugin {

/// "[Storey] <message>" in the console; at the default level CloudCompare
/// also shows it in a message box.
inline void consoleError(
    ccMainAppInterface* app, const QString& message,
    ccMainAppInterface::ConsoleMessageLevel level = ccMainAppInterface::ERR_CONSOLE_MESSAGE) {
  if (app != nullptr) app->dispToConsole("[Storey] " + message, level);
}

/// The wait cursor for the lifetime of the object.
class WaitCursor {
 public:
  WaitCursor() { QApplication::setOverrideCursor(Qt::WaitCursor); }
  ~WaitCursor() { QApplication::restoreOverrideCursor(); }
  WaitCursor(const WaitCursor&) = delete;
  WaitCursor& operator=(const WaitCursor&) = delete;
};

}  // namespace storey::plugin
