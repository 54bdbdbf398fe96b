// bouncer._core: the Python module's one native entry point. run(words) runs a bouncer
// command line in this process (tools/run_command.hpp: the same parsing, validation and
// code as the command-line tool) on a worker thread, with the GIL released, and returns what
// the command printed. The pure-Python layer (python/bouncer/__init__.py) builds the words
// from keyword arguments and turns the JSON and CSV into result objects and numpy arrays.
//
// Interrupts: the calling thread waits for the worker in slices of 50 ms and, between them,
// takes the GIL to let Python run its signal handlers (PyErr_CheckSignals: Ctrl-C in a
// notebook). When a handler raises (KeyboardInterrupt), the worker's cancel flag is set
// (io/cancel.hpp), the command unwinds at its next check (output files are written all or
// none, so none is left half written), and the exception is re-raised here.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bouncer/io/cancel.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/scalar/thread_caches.hpp"
#include "cli_common.hpp"
#include "run_command.hpp"

namespace py = pybind11;

namespace {

const char* kind_name(bouncer::cli::CommandOutcome::Kind k) {
  using K = bouncer::cli::CommandOutcome::Kind;
  switch (k) {
    case K::ok: return "ok";
    case K::help: return "help";
    case K::input: return "input";
    case K::output: return "output";
    case K::internal: return "internal";
    case K::cancelled: return "cancelled";
  }
  return "internal";
}

py::dict run(const std::vector<std::string>& words) {
  bouncer::cli::CommandOutcome outcome;
  bouncer::cli::CommandCapture capture;
  std::exception_ptr failure;
  std::atomic<bool> cancel{false};
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      const bouncer::MpfrThreadCaches caches;  // MPFR's per-thread caches, freed at the end
      const bouncer::CancelScope cancel_scope(&cancel);
      const bouncer::cli::CaptureScope capture_scope(&capture);
      try {
        outcome = bouncer::cli::run_command(words, false);
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(m);
      done = true;
      cv.notify_all();
    });
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(m);
        if (cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) break;
      }
      if (interrupted) continue;  // cancelled: wait for the command to unwind
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {  // a handler raised; the error stays set until we return
        interrupted = true;
        cancel.store(true);
      }
    }
    worker.join();
  }
  if (interrupted) throw py::error_already_set();
  if (failure) std::rethrow_exception(failure);
  py::dict r;
  r["status"] = outcome.status;
  r["kind"] = kind_name(outcome.kind);
  r["message"] = outcome.message;
  r["unknown_option"] = outcome.unknown_option;
  r["out"] = py::bytes(capture.out.str());
  r["csv"] = py::bytes(capture.csv);
  return r;
}

}  // namespace

PYBIND11_MODULE(_core, mod) {
  mod.doc() = "bouncer's native core: runs bouncer command lines in this process (see the bouncer package)";
  mod.def("run", &run, py::arg("words"),
          "Run a bouncer command line (words[0] is the program name) in this process, with the GIL released; "
          "returns {status, kind, message, unknown_option, out, csv}. Ctrl-C cancels it (KeyboardInterrupt).");
  mod.attr("version") = bouncer::build_info().version;
  mod.attr("commit") = bouncer::build_info().commit;
}
