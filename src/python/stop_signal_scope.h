#pragma once
#include <csignal>

#include "core/interrupt.h"

namespace vkdr {

// While the device works, the module has released Python's lock, and Python's own
// SIGINT handler only sets a flag that no Python code is running to look at. So while
// the main thread waits on device work, SIGINT is recorded where the renderer polls for
// it (core/interrupt.h): the renderer stops at its next poll and throws Interrupted,
// which the module raises as KeyboardInterrupt. Unlike the command line's handler, a
// second signal is only recorded too: it never kills the interpreter. Only the main
// thread takes SIGINT over, as Python's own handling is the main thread's, and only
// while Python's handler is its default (the caller says); a SIGINT the process ignores
// stays ignored. Python's handler is back when the scope ends.
class StopSignalScope {
public:
    explicit StopSignalScope(bool takeOver) {
        if (!takeOver) return;
        sigaction(SIGINT, nullptr, &previous_);
        if (previous_.sa_handler == SIG_IGN) return;
        struct sigaction action {};
        action.sa_handler = record;
        action.sa_flags = SA_RESTART;
        sigemptyset(&action.sa_mask);
        installed_ = sigaction(SIGINT, &action, nullptr) == 0;
    }
    ~StopSignalScope() {
        if (!installed_) return;
        sigaction(SIGINT, &previous_, nullptr);
        interrupt_detail::signalReceived.store(0);
    }
    StopSignalScope(const StopSignalScope&) = delete;
    StopSignalScope& operator=(const StopSignalScope&) = delete;

private:
    static void record(int signal) {
        int none = 0;
        interrupt_detail::signalReceived.compare_exchange_strong(none, signal);
    }

    struct sigaction previous_ {};
    bool installed_ = false;
};

}  // namespace vkdr
