#pragma once
// Python's lock released while the module's own work runs, as py::gil_scoped_release
// does, but safe when a daemon thread is in that work as the interpreter exits:
// - Python 3.11 ends a thread that takes its lock back during finalization with
//   pthread_exit, whose unwinding through a destructor (py::gil_scoped_release's) aborts
//   the process ("terminate called without an active exception");
// - work still running when exit() destroys the libraries' static state (OpenEXR's
//   thread pool, the Vulkan driver's) may crash the process.
// So at exit an atexit handler asks the work in flight to stop, as Ctrl-C does, and waits
// until every thread in it has either taken Python's lock back (before finalization, so
// safely) or, having ended its work after the handler started, waits until the process
// ends without taking it (as CPython 3.14 makes every such thread do); a thread that calls
// in after that waits too. The thread that runs the atexit handlers goes on: other atexit
// handlers may call the module.
#include <pybind11/pybind11.h>

namespace vkdr {

class ReleasedPythonLock {
public:
    ReleasedPythonLock();
    ~ReleasedPythonLock();
    ReleasedPythonLock(const ReleasedPythonLock&) = delete;
    ReleasedPythonLock& operator=(const ReleasedPythonLock&) = delete;

private:
    PyThreadState* state_;
};

// Registers the atexit handler above, and resets its count in a forked child (whose
// parent's other threads are not there); for the module's initialisation.
void finishModuleWorkAtExit();

}  // namespace vkdr
