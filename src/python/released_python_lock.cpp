#include "python/released_python_lock.h"

#include <unistd.h>

#include <condition_variable>
#include <csignal>
#include <mutex>
#include <thread>

#include "core/interrupt.h"

namespace vkdr {
namespace {

std::mutex workMutex;
std::condition_variable workEnded;
int workInFlight = 0;
bool exiting = false;
std::thread::id exitingThread;  // the thread that runs the atexit handlers, whose calls go on

// Whether this thread's work must not go on: another's, once the process exits.
bool parked() {
    return exiting && std::this_thread::get_id() != exitingThread;
}

[[noreturn]] void waitForTheProcessToEnd() {
    for (;;) pause();
}

}  // namespace

ReleasedPythonLock::ReleasedPythonLock() : state_(PyEval_SaveThread()) {
    std::unique_lock lock(workMutex);
    if (parked()) {
        lock.unlock();
        waitForTheProcessToEnd();
    }
    ++workInFlight;
}

ReleasedPythonLock::~ReleasedPythonLock() noexcept(false) {
    {
        std::unique_lock lock(workMutex);
        --workInFlight;
        workEnded.notify_all();
        if (parked()) {
            lock.unlock();
            waitForTheProcessToEnd();
        }
    }
    PyEval_RestoreThread(state_);
}

void finishModuleWorkAtExit() {
    auto finish = []() {
        std::unique_lock lock(workMutex);
        exiting = true;
        exitingThread = std::this_thread::get_id();
        if (workInFlight == 0) return;
        // The renderer stops at its next poll; loading and writing files run to their end.
        int none = 0;
        const bool asked = interrupt_detail::signalReceived.compare_exchange_strong(none, SIGTERM);
        workEnded.wait(lock, [] { return workInFlight == 0; });
        // Atexit handlers that run after this one may still render.
        if (asked) interrupt_detail::signalReceived.store(0);
    };
    pybind11::module_::import("atexit").attr("register")(pybind11::cpp_function(finish));
}

}  // namespace vkdr
