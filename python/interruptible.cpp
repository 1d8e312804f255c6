#include "python/interruptible.h"

#include <pybind11/pybind11.h>

#include <Python.h>

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

namespace svbrdf::python {

namespace py = pybind11;

void call_interruptibly(const std::function<void(const std::atomic<bool>& cancel)>& work) {
  std::atomic<bool> cancel{false};
  std::exception_ptr failure;
  std::optional<py::error_already_set> interrupted;  // what a signal handler raised
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  {
    py::gil_scoped_release unlocked;
    std::thread worker([&] {
      try {
        work(cancel);
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      done = true;
      finished.notify_one();
    });
    std::unique_lock<std::mutex> lock(mutex);
    // Python runs its handlers on the main thread only: on any other, PyErr_CheckSignals does nothing
    // and the call runs to its end, as a Python loop there would.
    while (!finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
      if (interrupted) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire locked;
        if (PyErr_CheckSignals() != 0) interrupted.emplace();  // fetches the exception the handler raised
      }
      if (interrupted) cancel = true;
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (interrupted) throw *interrupted;
  if (failure) std::rethrow_exception(failure);
}

}  // namespace svbrdf::python
