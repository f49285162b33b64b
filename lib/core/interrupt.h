// Ctrl-C (SIGINT) and kill (SIGTERM) stop a run at the next safe point instead of killing it
// mid-write: the handler only raises a flag; long loops (parallel_for, the stage boundaries) call
// throw_if_interrupted(), the exception unwinds through write_file_atomically, which removes its
// temporary file, and the command exits with 128 + the signal number. Earlier outputs are never
// touched, because every output is renamed into place only when it is complete.
#pragma once
#include <stdexcept>

namespace hairfit {

// Thrown by throw_if_interrupted(); not an InputError: the input was fine.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return signal_; }
  // The conventional exit status of a program stopped by the signal: 130 for SIGINT, 143 for SIGTERM.
  int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

// Installs the SIGINT and SIGTERM handlers. After the first signal the default action is restored,
// so a second Ctrl-C ends the program at once (then a temporary file may remain).
void install_interrupt_handlers();

// The signal received since the handlers were installed, or 0.
int interrupt_signal();
inline bool interrupted() { return interrupt_signal() != 0; }

// Throws Interrupted if a signal has arrived. Cheap (one atomic load): call it at stage boundaries
// and between work items.
void throw_if_interrupted();

// Raises the flag as the handler would (for tests); 0 clears it.
void set_interrupt_signal(int signal);

}  // namespace hairfit
