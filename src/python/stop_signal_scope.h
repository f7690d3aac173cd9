#pragma once
#include <csignal>
#include <mutex>

#include "core/interrupt.h"

namespace vkdr {

// While the device works, the module has released Python's lock, and Python's own
// SIGINT handler only sets a flag that no Python code is running to look at. So for as
// long as any device work is under way, SIGINT is recorded where the renderer polls for
// it (core/interrupt.h); the renderer then stops at its next poll and throws
// Interrupted, which the module raises as KeyboardInterrupt. Unlike the command line's
// handler, a second signal is only recorded too: it never kills the interpreter. The
// first scope in installs the handler, the last one out restores Python's and forgets
// the signal.
class StopSignalScope {
public:
    StopSignalScope() {
        std::lock_guard lock(mutex());
        if (depth()++ == 0) {
            struct sigaction action {};
            action.sa_handler = record;
            action.sa_flags = SA_RESTART;
            sigemptyset(&action.sa_mask);
            sigaction(SIGINT, &action, &previous());
        }
    }
    ~StopSignalScope() {
        std::lock_guard lock(mutex());
        if (--depth() == 0) {
            sigaction(SIGINT, &previous(), nullptr);
            interrupt_detail::signalReceived.store(0);
        }
    }
    StopSignalScope(const StopSignalScope&) = delete;
    StopSignalScope& operator=(const StopSignalScope&) = delete;

private:
    static void record(int signal) {
        int none = 0;
        interrupt_detail::signalReceived.compare_exchange_strong(none, signal);
    }
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    static int& depth() {
        static int d = 0;
        return d;
    }
    static struct sigaction& previous() {
        static struct sigaction p {};
        return p;
    }
};

}  // namespace vkdr
