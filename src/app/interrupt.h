// Ctrl-C during a headless render: the first SIGINT (or SIGTERM) stops the render once the frame in flight is done,
// so that the frames already traced are written, not lost; a second one ends the process at once, as it would have.
#pragma once

namespace lueur {

/// Catches SIGINT and SIGTERM while it lives, and puts back what was there before. A signal that was ignored when
/// it was made (a job started in the background by a shell without job control) stays ignored.
class InterruptCatcher {
 public:
  InterruptCatcher();
  ~InterruptCatcher();
  InterruptCatcher(const InterruptCatcher&) = delete;
  InterruptCatcher& operator=(const InterruptCatcher&) = delete;

  /// The signal caught first (SIGINT or SIGTERM), or 0 while none has come.
  int caught() const;
};

/// "SIGINT" or "SIGTERM" (any other: "a signal"), for messages.
const char* signal_name(int signal_number);

}  // namespace lueur
