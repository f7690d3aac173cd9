#pragma once
// Python's lock released while the module's own work runs, as py::gil_scoped_release
// does, but safe when a daemon thread is in that work as the interpreter exits:
// - Python 3.11 ends a thread that takes its lock back during finalization with
//   pthread_exit, whose unwinding through a destructor that may not throw (as
//   py::gil_scoped_release's) aborts the process ("terminate called without an active
//   exception");
// - work still running when exit() destroys the libraries' static state (OpenEXR's
//   thread pool, the Vulkan driver's) may crash the process.
// So at exit (an atexit handler) the module asks the work in flight to stop, as Ctrl-C
// does, and waits for it to end; a thread that then comes back, or calls in again,
// waits until the process ends, as CPython 3.14 makes every such thread do. The thread
// that exits goes on: other atexit handlers may call the module.
#include <pybind11/pybind11.h>

namespace vkdr {

class ReleasedPythonLock {
public:
    ReleasedPythonLock();
    // noexcept(false): should finalization start while the lock is taken back, Python's
    // unwinding of the thread passes through instead of aborting the process.
    ~ReleasedPythonLock() noexcept(false);
    ReleasedPythonLock(const ReleasedPythonLock&) = delete;
    ReleasedPythonLock& operator=(const ReleasedPythonLock&) = delete;

private:
    PyThreadState* state_;
};

// Registers the atexit handler above; for the module's initialisation.
void finishModuleWorkAtExit();

}  // namespace vkdr
