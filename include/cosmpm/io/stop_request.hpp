#pragma once
// SIGINT (Ctrl-C) and SIGTERM as a request to stop at the end of the current step, so a run
// finishes its output index, removes its temporary files and can write a checkpoint. A
// second signal stops the process at once, as if no handler were installed.
//
//   io::StopRequest stop;
//   while (sim.time() < end && !stop.requested()) sim.step(dt);
//   if (stop.requested()) std::printf("stopped by %s\n", stop.signal_name());
#include <csignal>

namespace cosmpm::io {

class StopRequest {
 public:
  // Installs the handlers for the lifetime of the object (one at a time per process).
  StopRequest() {
    received() = 0;
    previous_interrupt_ = std::signal(SIGINT, &StopRequest::handle);
    previous_terminate_ = std::signal(SIGTERM, &StopRequest::handle);
  }
  StopRequest(const StopRequest&) = delete;
  StopRequest& operator=(const StopRequest&) = delete;
  ~StopRequest() {
    std::signal(SIGINT, previous_interrupt_ == SIG_ERR ? SIG_DFL : previous_interrupt_);
    std::signal(SIGTERM, previous_terminate_ == SIG_ERR ? SIG_DFL : previous_terminate_);
  }

  bool requested() const { return received() != 0; }
  // The signal that asked to stop (0 if none).
  int signal_number() const { return static_cast<int>(received()); }
  const char* signal_name() const {
    const int s = signal_number();
    return s == SIGINT ? "SIGINT" : s == SIGTERM ? "SIGTERM" : "no signal";
  }
  // The conventional exit status of a process stopped by the signal: 128 + its number.
  int exit_status() const { return 128 + signal_number(); }

 private:
  static volatile std::sig_atomic_t& received() {
    static volatile std::sig_atomic_t value = 0;
    return value;
  }
  static void handle(int signal) {
    if (received() != 0) {
      // Asked twice: stop now.
      std::signal(signal, SIG_DFL);
      std::raise(signal);
      return;
    }
    received() = signal;
    std::signal(signal, &StopRequest::handle);  // some systems reset the handler
  }

  using Handler = void (*)(int);
  Handler previous_interrupt_ = SIG_DFL;
  Handler previous_terminate_ = SIG_DFL;
};

}  // namespace cosmpm::io
