#pragma once
// Long calls that a Ctrl-C stops. With the GIL released, Python runs no signal handler: its C handler
// only notes the signal, and the Python one (the KeyboardInterrupt of the default) runs when the main
// thread next executes Python code, after the call. So the work runs on a thread of its own while the
// calling thread waits, taking the GIL back every 50 ms to let Python handle what arrived
// (PyErr_CheckSignals); when a handler raises, the work's cancel flag is set, the work is waited for
// (it stops at its next check of the flag) and the handler's exception is raised in its place.
#include <atomic>
#include <functional>

namespace svbrdf::python {

// Runs work(cancel) as above; called with the GIL held, returns with it held. An exception of the work
// is raised as it is (after the work ends); one of a signal handler wins over the work's result.
void call_interruptibly(const std::function<void(const std::atomic<bool>& cancel)>& work);

}  // namespace svbrdf::python
