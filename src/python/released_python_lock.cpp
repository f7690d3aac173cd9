#include "python/released_python_lock.h"

#include <pthread.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <csignal>
#include <mutex>
#include <new>
#include <thread>

#include "core/interrupt.h"

namespace vkdr {
namespace {

// Taken without Python's lock, or after it (never the other way round): a thread that
// waits for Python's lock never holds this one.
std::mutex workMutex;
std::condition_variable workEnded;
int workInFlight = 0;  // threads between releasing Python's lock and taking it back
bool exiting = false;
std::thread::id exitingThread;  // the thread that runs the atexit handlers, whose calls go on

// Whether this thread's work must not go on: another's, once the process exits.
bool parked() {
    return exiting && std::this_thread::get_id() != exitingThread;
}

[[noreturn]] void waitForTheProcessToEnd() {
    for (;;) pause();
}

void workEnds(std::unique_lock<std::mutex>& lock) {
    --workInFlight;
    workEnded.notify_all();
    lock.unlock();
}

// Waits, without Python's lock, until no thread is in the module's work; Ctrl-C (which
// Python only notes while its lock is free) raises KeyboardInterrupt out of the wait,
// and the process exits with the work still in flight.
void waitForWorkInFlight() {
    for (;;) {
        {
            PyThreadState* state = PyEval_SaveThread();
            std::unique_lock lock(workMutex);
            const bool done = workEnded.wait_for(lock, std::chrono::milliseconds(100), [] { return workInFlight == 0; });
            lock.unlock();
            PyEval_RestoreThread(state);
            if (done) return;
        }
        if (PyErr_CheckSignals() != 0) throw pybind11::error_already_set();
    }
}

void finishAtExit() {
    bool asked = false;
    {
        std::unique_lock lock(workMutex);
        exiting = true;
        exitingThread = std::this_thread::get_id();
        if (workInFlight == 0) return;
        // The renderer stops at its next poll; loading and writing files run to their end.
        int none = 0;
        asked = interrupt_detail::signalReceived.compare_exchange_strong(none, SIGTERM);
    }
    waitForWorkInFlight();
    // Atexit handlers that run after this one may still render.
    if (asked) interrupt_detail::signalReceived.store(0);
}

// A forked child has one thread: the parent's others, and their work, are not in it.
void forgetOtherThreadsAfterFork() {
    new (&workMutex) std::mutex;
    new (&workEnded) std::condition_variable;
    workInFlight = 0;
    exiting = false;
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

ReleasedPythonLock::~ReleasedPythonLock() {
    std::unique_lock lock(workMutex);
    if (parked()) {
        workEnds(lock);
        waitForTheProcessToEnd();
    }
    lock.unlock();
    // Still counted: the atexit handler waits until this thread holds Python's lock again,
    // so finalization never starts while it waits for it.
    PyEval_RestoreThread(state_);
    lock.lock();
    workEnds(lock);
}

void finishModuleWorkAtExit() {
    pthread_atfork(nullptr, nullptr, forgetOtherThreadsAfterFork);
    pybind11::module_::import("atexit").attr("register")(pybind11::cpp_function(finishAtExit));
}

}  // namespace vkdr
