#pragma once
#include <atomic>
#include <csignal>
#include <stdexcept>
#include <string>

namespace vkdr {

// SIGINT and SIGTERM ask long work to stop: the handler only records the signal, and
// the work polls for it at points where stopping leaves nothing half done (the renderer
// between batches of path segments, the optimiser between iterations), then throws
// Interrupted. A second signal stops the process at once, with the signal's default
// action, except while a file is being written (image/atomic_write.h): that write
// finishes first, so that no partial file or stray temporary is left.

// Thrown where work notices a signal. Not a vkdr::Error: the command line exits with
// 128 + the signal's number (130 for SIGINT, 143 for SIGTERM), as shells report a
// process killed by it.
class Interrupted : public std::runtime_error {
public:
    Interrupted(int signal, const std::string& message) : std::runtime_error(message), signal_(signal) {}
    int signal() const { return signal_; }
    int exitCode() const { return 128 + signal_; }

private:
    int signal_;
};

namespace interrupt_detail {
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");
inline std::atomic<int> signalReceived{0};     // the first signal, 0 while none came
inline std::atomic<int> filesBeingWritten{0};  // writes that a second signal must let finish
inline std::atomic<int> stopDeferred{0};       // a second signal that came during such a write

inline void stopNow(int signal) {
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

inline void onStopSignal(int signal) {
    int none = 0;
    if (signalReceived.compare_exchange_strong(none, signal)) return;
    // Recorded first, so that a write ending now sees it (FileWriteGuard); if no write is
    // under way after all, stop here.
    stopDeferred.store(signal);
    if (filesBeingWritten.load() == 0) stopNow(signal);
}
}  // namespace interrupt_detail

inline const char* signalName(int signal) {
    return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
}

// Installs the handler for SIGINT and SIGTERM; for a program's main().
inline void stopOnInterruptSignals() {
    struct sigaction action {};
    action.sa_handler = interrupt_detail::onStopSignal;
    // Reads and writes the signal lands in carry on: the work stops at its next poll,
    // not with a short write of the result it was printing.
    action.sa_flags = SA_RESTART;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

// The signal received so far, 0 if none.
inline int interruptSignal() {
    return interrupt_detail::signalReceived.load();
}

inline void throwIfInterrupted() {
    if (int signal = interruptSignal()) {
        throw Interrupted(signal, std::string("interrupted by ") + signalName(signal));
    }
}

// Held while a file is written: a second signal waits until it is done.
class FileWriteGuard {
public:
    FileWriteGuard() { ++interrupt_detail::filesBeingWritten; }
    ~FileWriteGuard() {
        if (--interrupt_detail::filesBeingWritten == 0) {
            if (int signal = interrupt_detail::stopDeferred.load()) interrupt_detail::stopNow(signal);
        }
    }
    FileWriteGuard(const FileWriteGuard&) = delete;
    FileWriteGuard& operator=(const FileWriteGuard&) = delete;
};

}  // namespace vkdr
